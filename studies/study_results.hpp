#pragma once
/// \file
/// DIR/results.json: the key values of a finished study under named keys, the one file a
/// table or a figure of the paper reads (docs/guide/cone_branch.md lists the keys). Written
/// atomically at the study's end; numbers in their shortest round-trip form; null where a
/// value does not apply (e.g. no mid-surface contact within the traced range).

#include <optional>
#include <string>

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
  /// The first branch point on the flat branch.
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
/// phi_symmetry_lost, phi_last, completed, end, branch_csv ("branch.csv"), events
/// ("events.json"), wall_seconds. Unset and non-finite values are null.
std::string cone_branch_results_json(const ConeBranchResults& results);

/// Writes cone_branch_results_json to DIR/results.json atomically (write_file_atomically).
/// Throws std::runtime_error naming the file if it cannot be written.
void write_cone_branch_results(const std::string& directory, const ConeBranchResults& results);

}  // namespace growshell
