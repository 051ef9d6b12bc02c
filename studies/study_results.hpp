#pragma once
/// \file
/// DIR/results.json: the key values of a finished study under named keys, the one file a
/// table or a figure of the paper reads (docs/guide/cone_branch.md and
/// docs/guide/econe_contact.md list the keys). Written
/// atomically at the study's end; numbers in their shortest round-trip form; null where a
/// value does not apply (e.g. no mid-surface contact within the traced range).

#include <optional>
#include <string>
#include <vector>

#include "studies/hard_contact_check.hpp"

namespace growshell {

/// The mesh a study ran on.
struct StudyMesh {
  std::string family;                ///< scene key mesh.family: "rings", "gmsh", ...
  std::optional<double> size_slope;  ///< mesh.size_slope; none for a family without it
  long long elements = 0;
  long long unknowns = 0;
};

/// The key values of a cone_branch study (run_cone_branch_study). Excess angles in radians,
/// the thickness in metres, E_b-hat in 1/m^2, wall time in seconds.
struct ConeBranchResults {
  double thickness = 0.0;  ///< h at the centre
  int mode = 2;            ///< fold number n of the cone
  StudyMesh mesh;
  /// The branch point on the flat branch where the n-fold cone leaves it (its cone_entry
  /// event); the flat branch passes the lower modes' branch points before it.
  std::optional<double> phi_branch;
  /// The eb_max event (the maximum of E_b-hat on the cone) and E_b-hat there.
  std::optional<double> phi_max, eb_hat_max;
  /// The first contact event: the gap between non-neighbouring parts of the sheet reaches the
  /// contact distance (the thickness by default).
  std::optional<double> phi_gap_h;
  /// The midsurface_contact event: the mid-surface first passes through itself.
  std::optional<double> phi_kiss;
  /// The first sample on the cone with phi_e >= 0.1 and a negative eigenvalue.
  std::optional<double> phi_crit_stability;
  /// The largest S4 defect over the cone's samples with 0.1 <= phi_e < phi_gap_h (all samples
  /// from 0.1 on without a contact event); none for a cone other than the two-fold one.
  std::optional<double> max_s4_defect_before_contact;
  /// The symmetry_lost event.
  std::optional<double> phi_symmetry_lost;
  /// The last sample of the cone.
  std::optional<double> phi_last;
  /// The largest phi_e of the samples: the fold where a branch that turns back turned.
  std::optional<double> phi_highest;
  /// The orientation check (study.orientation_check_at): at the saved state nearest that
  /// phi_e, the turned and relaxed state of lowest energy among study.orientation_check_turns
  /// (studies/pattern_orientation_check.hpp); unset without a check or if no relaxation
  /// converged.
  struct Orientation {
    double phi_e = 0.0;
    double turn_deg = 0.0;
    double fold_angle_deg = 0.0;   ///< where its up-fold settled (the traced cone's is at 0)
    double energy_relative = 0.0;  ///< (E_turned - E_traced) / E_traced
    double s4_defect = 0.0;
    double chord_up = 0.0, chord_down = 0.0;
    double energy_change_core = 0.0, energy_change_outside = 0.0;  ///< J, split at r = h
  };
  std::optional<Orientation> orientation;
  /// Whether the trace reached its end (phi_max, or contact when it stops there) rather than
  /// giving up (step below min_step, no branch point found), and the trace's own words.
  bool completed = false;
  std::string end;
  double wall_seconds = 0.0;
};

/// results.json's text: a JSON object, 2-space indent, trailing newline, keys in this order:
/// study ("cone_branch"), thickness, mode, mesh {family, size_slope, elements, unknowns},
/// phi_branch, phi_max, eb_hat_max, phi_gap_h, phi_kiss, phi_kiss_criterion
/// ("midsurface_contact"), phi_crit_stability, max_s4_defect_before_contact,
/// phi_symmetry_lost, phi_last, phi_highest, orientation_phi, orientation_turn_deg,
/// orientation_fold_angle_deg, orientation_energy_relative, orientation_s4_defect,
/// orientation_chord_up, orientation_chord_down, orientation_energy_change_core,
/// orientation_energy_change_outside, completed, end, branch_csv ("branch.csv"), events
/// ("events.json"), wall_seconds. Unset and non-finite values are null.
std::string cone_branch_results_json(const ConeBranchResults& results);

/// Writes cone_branch_results_json to DIR/results.json atomically (write_file_atomically).
/// Throws std::runtime_error naming the file if it cannot be written.
void write_cone_branch_results(const std::string& directory, const ConeBranchResults& results);

/// The Ipopt re-solve of the relaxed skewed state under hard constraints.
struct EconeIpoptCheck {
  bool converged = false;
  std::string message;
  /// (E_penalty - E_ipopt) / E_ipopt of the elastic energies E_s + E_b of the two states.
  double relative_energy_difference = 0.0;
  double state_difference_over_h = 0.0;  ///< max |x_ipopt - x_penalty| / h
  double min_distance_over_h = 0.0;      ///< smallest pair distance at Ipopt's solution / h
};

/// The pattern-orientation check at the cone's last contact-free state
/// (studies/pattern_orientation_check.hpp), in results.json's units: angles in degrees.
struct EconeOrientationCheck {
  double phi_e = 0.0;
  double fold_angle_deg = 0.0;  ///< where the traced state's up-fold lies
  double s4_defect = 0.0;       ///< the traced state's
  double core_radius = 0.0;     ///< m: energy changes are split here
  struct Turned {
    double turn_deg = 0.0;
    bool converged = false;
    std::string message;
    double fold_angle_deg = 0.0;   ///< where the relaxed state's up-fold settled
    double energy_relative = 0.0;  ///< (E_turned - E_traced) / E_traced, E = E_s + E_b + P
    double s4_defect = 0.0;
    double chord_up = 0.0, chord_down = 0.0;
    double energy_change_core = 0.0, energy_change_outside = 0.0;  ///< J
    double lowest_eigenvalue = 0.0;                                ///< N/m
    int turn_free_index = 0;
    std::string state;  ///< the relaxed state's file, relative to the study directory
  };
  std::vector<Turned> turned;
};

/// The cone with its fold pattern turned against the mesh: the orientation check's lowest
/// relaxed state that breaks S4, traced with the contact penalty in the full space, down and
/// up. Its apex core is free to skew, which the mirror lines hold on the symmetric branch, so
/// it is the reference for energy comparisons that do not depend on how the folds lie on the
/// mesh (docs/results.md, "The apex core against the mesh").
struct EconeTurnedBranch {
  double start_phi = 0.0;  ///< the orientation check's phi_e
  double turn_deg = 0.0;   ///< the turn its start came from
  /// The range of its samples, and the lowest phi_e of those that break S4.
  std::optional<double> lowest_phi, highest_phi, lowest_phi_breaking_s4;
  /// At its highest sample: (E_turned - E_symmetric) / E_symmetric (E = E_s + E_b + P, the
  /// symmetric energy interpolated), the S4 defect and gamma (contact planes).
  std::optional<double> top_energy_relative, top_s4_defect, top_gamma;
  /// The largest (E_symmetric - E_turned) / E_symmetric over its samples, and where.
  std::optional<double> largest_energy_below_symmetric, largest_energy_below_symmetric_phi;
  /// Its first loss of stability (the negative count leaves 0), if any.
  std::optional<double> phi_crit_stability;
  std::string end;  ///< why each trace ended
};

/// An n-fold cone of study.compare_modes, traced without contact from the flat sheet and
/// compared with the two-fold cone (the contact-free cone, then the symmetric branch with
/// contact) at the same phi_e.
struct EconeComparedMode {
  int mode = 3;
  std::string directory;  ///< its cone_branch study, relative to DIR ("cone_n3")
  std::optional<double> phi_branch, phi_max, eb_hat_max;
  std::optional<double> phi_first_contact;  ///< its first gap = contact distance, if reached
  std::optional<double> highest_phi;        ///< its highest sample (phi_highest)
  /// The smallest (E_n - E_2) / E_2 over its samples where the two-fold cone was traced
  /// (E = E_s + E_b, + P on the branch with contact), and where: above 0 if it lies above.
  std::optional<double> lowest_energy_above_two_fold, lowest_energy_above_two_fold_phi;
  bool completed = false;
  std::string end;
};

/// The winding (study.wind_to): the sheet grown on from the highest stable state that breaks S4
/// (of the skewed or the turned cone) by minimisation at every step, each accepted state a
/// strict minimum of shell + penalty.
struct EconeWindUp {
  /// Where it starts: the highest stable sample that breaks S4 of the "skewed" or the
  /// "turned" branch (the higher; the lower in energy where both reach the same phi_e).
  std::string start_branch;
  double start_phi = 0.0;
  double target = 0.0;     ///< study.wind_to
  bool reached = false;    ///< the path reached the target
  std::optional<double> highest_phi;  ///< its last accepted state
  int steps = 0, failed_steps = 0;
  /// Of this run's steps (a resumed run counts its own): those taken from the secant
  /// predictor, and predictions discarded (ContactGrowthResult). In the log, not in
  /// results.json, which a resumed run writes as the uninterrupted one did.
  int predicted_steps = 0, discarded_predictions = 0;
  /// Where a stable state ended and the path dropped onto another one (a saddle pushed off).
  std::vector<double> jumps;
  /// The shapes written: at each of study.wind_shapes_at reached, and at the end.
  struct Shape {
    double phi_e = 0.0;
    std::string shell, contact;  ///< VTU files, relative to the study directory
  };
  std::vector<Shape> shapes;
  std::string end;  ///< why it ended
  double seconds = 0.0;
};

/// An energy crossing of the symmetric and the skewed branch.
struct EconeCrossing {
  double phi_e = 0.0;
  double error_estimate = 0.0;  ///< of phi_e (EnergyCrossing::error_estimate)
  bool skewed_stable = false;   ///< the skewed samples on both sides are stable
};

/// The energy ratio f = E_s / E_b, stretching over bending energy, at the highest sample of a
/// branch traced with contact: how far the state is from an isometry of the grown sheet, the
/// ratio growshell reports for the paper's Fig. 5 (physics.md lists stretching against bending
/// among the measured quantities; docs/guide/econe_contact.md, "Fig. 5").
struct EconeEnergyRatio {
  std::string branch;  ///< "symmetric", "skewed", "turned" or "wound"
  double phi_e = 0.0;  ///< of the branch's highest sample
  double f = 0.0;
};

/// One hard-contact check of the econe_contact study (study.hard_contact_at).
struct EconeHardContactPoint {
  std::string branch;  ///< "turned", "symmetric" or "skewed""
  double at = 0.0;     ///< the requested phi_e; the state checked is the nearest saved one
  std::string file;    ///< "BRANCH/hard_contact_phiP.json", relative to DIR
  HardContactCheck check;
};

/// The key values of an econe_contact study. Angles in radians, lengths in metres, energies in
/// joules, E_b-hat in 1/m^2.
struct EconeContactResults {
  double thickness = 0.0;  ///< h at the centre
  StudyMesh mesh;
  double contact_distance = 0.0;   ///< mid-surface distance at which the sheets touch
  double exclusion_radius = 0.0;   ///< physics.contact_exclusion_radius, resolved
  double penalty_stiffness = 0.0;  ///< k (N/m)
  /// The contact proxy the penalty acts on: segments per element edge
  /// (study.contact_proxy_segments) and its number of vertices.
  int proxy_segments_per_edge = 1;
  long long proxy_vertices = 0;
  /// What the penalty's pairs measure the distance to (study.contact_surface):
  /// "proxy_triangles" or "limit_surface".
  std::string contact_surface = "proxy_triangles";
  /// From the contact-free cone (stage 1): its first branch point, and its maximum of E_b-hat.
  std::optional<double> phi_branch, phi_max, eb_hat_max;
  /// Where the trace with contact started: the cone's last state.
  std::optional<double> phi_contact_start;
  /// The first contact on the symmetric branch (gap = contact distance beyond the exclusion
  /// radius, on the limit surface: the cone's contact event; the penalty's own event where the
  /// cone did not stop at contact): results.json's phi_kiss, with phi_kiss_criterion
  /// "first_contact".
  std::optional<double> phi_first_contact;
  /// The symmetric branch's first loss of stability (its turn-free index leaves 0).
  std::optional<double> phi_crit_stability;
  /// phi_e^crit by energy: where a stable skewed cone first has a lower energy than the
  /// symmetric one (studies/ground_state_exchange.hpp), and how ("energy_crossing",
  /// "stabilised_below" or "lowest_sample").
  std::optional<double> phi_crit_energy;
  std::string phi_crit_energy_criterion;
  /// The branch phi_crit_energy compares the skewed cone with: "turned" where the study traced
  /// the turned cone (it is then the lower one), else "symmetric".
  std::string phi_crit_energy_reference = "symmetric";
  /// Every energy crossing of the two branches, by phi_e, where the skewed trace is on the
  /// skewed cone (samples that break S4 within 0.05 on both sides).
  std::vector<EconeCrossing> crossings;
  /// The largest S4 defect of the symmetric branch's samples with contact.
  std::optional<double> max_s4_defect_symmetric;
  bool skewed_found = false;
  std::string skewed_message;            ///< how the skewed cone was found, or why not
  std::optional<double> skew_search_at;  ///< phi_e of the relaxed symmetric state
  /// (E_symmetric - E_skewed) / E_symmetric at skew_search_at (E = E_s + E_b + P).
  std::optional<double> skewed_energy_below_symmetric;
  /// The lowest and highest phi_e of the skewed branch's samples that break S4 (S4 defect
  /// above study.symmetry_threshold and below 0.5, a larger one being a failed measure).
  std::optional<double> skewed_lowest_phi, skewed_highest_phi;
  std::optional<EconeIpoptCheck> ipopt;
  /// The checks of study.hard_contact_at, by phi_e, in the order of study.hard_contact_branches.
  std::vector<EconeHardContactPoint> hard_contact;
  /// The pattern turned against the mesh at the contact start (study.orientation_check_turns).
  std::optional<EconeOrientationCheck> orientation_check;
  /// The turned cone traced (when the orientation check found a lower state breaking S4).
  std::optional<EconeTurnedBranch> turned;
  /// The n-fold cones of study.compare_modes, in its order.
  std::vector<EconeComparedMode> compared_modes;
  /// The winding beyond the skewed branch (study.wind_to); unset if not asked for or no stable
  /// skewed state was found to start from.
  std::optional<EconeWindUp> wound;
  /// f = E_s / E_b at the highest sample of each branch traced with contact, in the order
  /// symmetric, skewed, turned, wound (a branch without samples left out).
  std::vector<EconeEnergyRatio> energy_ratio_f;
  /// Caveats on the values above, each a sentence naming what it concerns: e.g. a turned
  /// pattern that relaxed to a lower state breaking S4, so that the symmetric branch traced
  /// with its folds on the mesh's mirror lines is not the lowest state of the sheet there.
  std::vector<std::string> warnings;
  /// Whether every stage ran to its end (the symmetric branch to phi_max, the skewed cone
  /// found and both its traces ended at a bound, or the downward one below the exchange it
  /// located), and why not ("completed (...)" says where a downward trace stopped early).
  bool completed = false;
  std::string end;
  double wall_seconds = 0.0;
};

/// results.json's text: a JSON object, 2-space indent, trailing newline, keys in this order:
/// study ("econe_contact"), thickness, mesh {family, size_slope, elements, unknowns},
/// contact_distance, exclusion_radius, penalty_stiffness, phi_branch, phi_max, eb_hat_max,
/// phi_contact_start, phi_kiss, phi_kiss_criterion ("first_contact"), phi_first_contact,
/// phi_crit_stability, phi_crit_energy, phi_crit_energy_criterion, phi_crit_energy_reference,
/// crossings [{phi_e,
/// error_estimate, skewed_stable}],
/// max_s4_defect_symmetric, skewed {found, message, search_at, energy_below_symmetric,
/// lowest_phi, highest_phi}, ipopt ({converged, message, relative_energy_difference,
/// state_difference_over_h, min_distance_over_h} or null), hard_contact [{branch, at, file,
/// and the fields of hard_contact_check_json}], orientation_check ({phi_e,
/// fold_angle_deg, s4_defect, core_radius, turned [{turn_deg, converged, message,
/// fold_angle_deg, energy_relative, s4_defect, chord_up, chord_down, energy_change_core,
/// energy_change_outside, lowest_eigenvalue, turn_free_index, state}]} or null), turned
/// ({start_phi, turn_deg, lowest_phi, highest_phi, lowest_phi_breaking_s4,
/// top_energy_relative, top_s4_defect, top_gamma, largest_energy_below_symmetric,
/// largest_energy_below_symmetric_phi, phi_crit_stability, end} or null), compared_modes
/// [{mode, directory, csv, phi_branch, phi_max, eb_hat_max, phi_first_contact, highest_phi,
/// lowest_energy_above_two_fold, lowest_energy_above_two_fold_phi, completed, end}], wound
/// ({start_branch, start_phi,
/// target, reached, highest_phi, steps, failed_steps, jumps, shapes [{phi_e, shell, contact}],
/// end, seconds} or null), energy_ratio_f [{branch, phi_e, f}], warnings [strings],
/// completed, end, cone_csv, symmetric_csv, skewed_csv, turned_csv (null without the turned
/// branch), wound_csv (null without the winding), events (each branch's events.json), wall_seconds.
/// Unset and non-finite values are null.
std::string econe_contact_results_json(const EconeContactResults& results);

}  // namespace growshell
