#pragma once
/// \file
/// Pseudo-arclength continuation of a growing shell through self-contact. Contact is the
/// quadratic penalty of contact_penalty.hpp on the pairs near the current state; the branch
/// is followed in segments of a few steps, each with a fixed pair set (so that the Hessian
/// pattern, and the LDL^T analysis, stay fixed), and the pair set is rebuilt between segments
/// and whenever a pair outside the set comes closer than allowed. Because the corrector is
/// Newton on the augmented system, the branch is followed also where it is unstable.
///
/// Stability under contact. The penalised Hessian is
///   d2(E + P) = d2E - sum_k f_k d2 d_k + k sum_k grad d_k grad d_k^T,   f_k = k (h - d_k)_+,
/// i.e. the Hessian of the Lagrangian with multipliers f_k (the penalty forces) plus k J^T J
/// over the active pairs. By Debreu's lemma its negative count equals that of the Lagrangian
/// Hessian reduced to the tangent space of the active constraints once k exceeds a finite
/// bound, so the samples' negative_eigenvalues is the stability index under contact
/// (reduced_hessian_inertia computes the reduced count exactly, for checking).

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// Settings of trace_contact_branch. Lengths in metres.
struct ContactBranchOptions {
  /// Step control and tolerances of each segment (parameter bounds, max_steps and
  /// max_special_points apply to the whole trace: a special point at a segment boundary counts).
  ArclengthOptions arclength;
  double contact_distance = 0.0;  ///< mid-surface distance at which the sheets touch, > 0
  double exclusion_radius = 0.0;  ///< neighbours on the sheet within this are never contact, > 0
  /// Pairs closer than contact_distance + candidate_margin at the start of a segment enter its
  /// penalty (> 0). It bounds how far two parts may approach unseen during a segment.
  double candidate_margin = 0.0;
  double stiffness = 0.0;  ///< penalty stiffness k (N/m), > 0
  /// Which near pairs enter (default as the Ipopt solve: vertex-triangle, nearest triangle).
  /// Without nearest_triangle_only a sample's close pairs must be in the set themselves (with
  /// it, any pair of the same vertex covers a vertex-triangle pair).
  NearPairSelection selection{false, true};
  /// In a symmetric subspace with nearest_triangle_only, each segment's set is closed under
  /// the subspace's symmetries (libshell/contact/equivariant_pairs.hpp): where a vertex is
  /// equidistant from two triangles, rounding otherwise picks for it and for its image
  /// independently, and the penalty lacks the symmetry the subspace assumes.
  bool symmetric_pair_sets = true;
  int steps_per_segment = 6;  ///< steps before the pair set is rebuilt, >= 1
  /// If > 0, fixed_dofs must be the six rigid-motion pins (rigid_motion_pinned_dofs): a
  /// segment whose start state holds them with a condition number above this
  /// (pinned_rigid_motion_condition) chooses them again on that state (vertex A of
  /// fixed_dofs[0] kept, B and C among the sheet vertices by their current positions), and
  /// keeps the new ones until they degrade in turn. Pins chosen on the reference can become
  /// nearly collinear as the sheet deforms: on the h = 0.02 symmetric cone at 7.03 the rim
  /// vertex pinned for the spin about AB has come round to within 0.019 of that axis. The
  /// spin is then almost free, the Hessian has a near-zero eigenvalue (8.6e-7 N/m, 99.8 %
  /// rigid), and Newton's corrections run along it far enough to flip pairs in and out of
  /// contact. Pins are changed only where needed because the negative count of a state
  /// next to a special point, off equilibrium by the tolerance, can depend on the gauge.
  double repin_above_condition = 0.0;
  /// A pair outside the segment's set closer than contact_distance - violation_tolerance
  /// ends the segment at the previous sample, which is retried with a rebuilt set (>= 0).
  double violation_tolerance = 0.0;
  ContactGapOptions gap;
  /// A segment's start is the previous segment's last sample, an equilibrium on the previous
  /// pair set. The set keeps one triangle per proxy vertex, the nearest at the set's state;
  /// where a vertex's nearest triangle has changed since, the rebuilt set's force on it jumps
  /// (by 0.26 and 1.2 N on the ctest's coarse mesh, where the tolerance is 6e-7 N), and
  /// Newton's full updates on the penalty's piecewise Hessian can diverge from there. A start
  /// that does not converge, even one sample back, is corrected once more with updates halved
  /// where they raise the residual tenfold (ArclengthOptions::max_residual_backtracks = this)
  /// and twice max_corrector_iterations, for that segment, before the trace ends. 0: the trace
  /// ends at once. Only starts that would otherwise end the trace are retried, so a trace that
  /// never meets one is the same with or without it.
  int start_residual_backtracks = 10;
  /// If set, a segment start that fails even that is relaxed at its phi_e on the
  /// rebuilt pair set by energy minimisation (NewtonSolver with these options, fixed_dofs held,
  /// max_travel at most the candidate margin, so that no pair outside the set can close in)
  /// and the segment starts from the minimum, an equilibrium of the rebuilt set where the
  /// corrector's Newton updates diverged. The set is then built again at the minimum; where a
  /// vertex's nearest triangle differs there (a vertex in a valley of the other layer flips
  /// between its sides), the minimisation is repeated with the union of the sets, up to six
  /// rounds, and the segment goes on with the union once its minimum misses no pair of its
  /// own. In a symmetric subspace the minimisation runs in the full space on sets closed
  /// under the subspace's symmetries (symmetric_pair_sets), and the next segment aligns and
  /// projects its result. Minimisation keeps to a stable branch: a start whose relaxation
  /// does not converge within the travel or settle ends as before, the message saying why.
  /// Unset: the trace ends at once.
  std::optional<NewtonOptions> start_relaxation;
  /// If not empty (one entry per unknown), every segment is traced with the phase condition
  /// c . x = c . x_start held by a multiplier (trace_branch_with_phase_condition), e.g. the fold
  /// pattern's orientation about the axis (studies/pattern_phase.hpp): on a mesh without the
  /// pattern's symmetry the pattern's turn is nearly free once few pairs hold it, and the
  /// corners of the faceted contact surface, not the shell, then decide where the branch folds.
  /// The samples report the force the condition takes up (ContactBranchSample::phase_force).
  /// Not with symmetric_subspace, whose mirrors hold the pattern already.
  Eigen::VectorXd phase_functional;
  /// If set (a subspace of the model's unknowns), the branch is traced in it
  /// (SymmetricSubspaceFamily): the continuation cannot leave the symmetric states, so it
  /// follows a symmetric branch through the branch points where it loses stability to
  /// symmetry-breaking modes, however the steps fall. The pair set is still chosen on the full
  /// state, and the reduced problem is that of the symmetrised penalty. The samples are full
  /// states, and their negative count (stability index, special points) is the full
  /// Hessian's with fixed_dofs held, one extra LDL^T factorisation per corrected point.
  std::shared_ptr<const SymmetricSubspace> symmetric_subspace;
  /// If set, the stability index of the corrected samples (BranchSample::negative_eigenvalues,
  /// and so the special points): called once per segment with the segment's energy (the shell
  /// with the penalty on the segment's pairs, as a function of phi_e, alive while the segment
  /// is traced) and the subspace it is traced in (symmetric_subspace, or null), it returns the
  /// count of each full-space sample of that segment (which carries its reduced_x in a
  /// subspace), e.g. one without the fold pattern's turn
  /// (studies/turn_free_stability_index.hpp); the function may keep work it can reuse over the
  /// segment, such as the analysis of the energy's Hessian pattern. Unset: the negative count
  /// of the penalised Hessian without its rigid motions (class by class in a subspace whose
  /// group splits the space, else with fixed_dofs held).
  std::function<std::function<int(const BranchSample& sample)>(
      const ParametrizedObjective& energy, const SymmetricSubspace* subspace)>
      stability_index_for_segment;
};

/// A converged point of a branch with contact.
struct ContactBranchSample {
  BranchSample sample;             ///< state, excess angle, arclength, negative count, tangent
  double stretching_energy = 0.0;  ///< J
  double bending_energy = 0.0;     ///< J
  double penalty_energy = 0.0;     ///< J, P at the state
  /// d(E_stretch + E_bend + P)/d(phi_e) along the branch (J/rad): the partial derivative at
  /// fixed state, since the gradient vanishes at an equilibrium.
  double energy_slope = 0.0;
  double current_area = 0.0;        ///< m^2
  double normalized_bending = 0.0;  ///< E_bend / area (J/m^2)
  /// The segment's pairs and each pair's penalty force k (h - d)_+ (N), in the order of
  /// ContactGapConstraints.
  ContactCandidates pairs;
  Eigen::VectorXd forces;
  double min_distance = 0.0;  ///< over the segment's pairs (m); +infinity without pairs
  /// |mu| (N), the multiplier of the unit phase functional that holds the state on the phase
  /// condition (ContactBranchOptions::phase_functional): the size of the force the condition
  /// takes up, to be read against the corrector's force tolerance. NaN without a condition.
  double phase_force = std::numeric_limits<double>::quiet_NaN();
  int active_pairs = 0;       ///< pairs with a positive force
  int segment = 0;            ///< which segment produced the sample
};

/// Where a trace with contact spent its effort, on top of the continuation's own TraceCost.
struct ContactBranchCost {
  TraceCost continuation;            ///< summed over segments (assembly includes the penalty)
  double pair_search_seconds = 0.0;  ///< broad + narrow phase of the pair-set builds and checks
  double sample_seconds = 0.0;       ///< energies, slopes and forces of the samples
  int segments = 0;
  int rebuilds_after_violation = 0;
  int repinnings = 0;  ///< segments that chose new rigid-motion pins (repin_above_condition)
  /// Segment starts corrected again with halved updates (start_residual_backtracks).
  int safeguarded_starts = 0;
  /// Segment starts relaxed by energy minimisation (start_relaxation) after that failed.
  int relaxed_starts = 0;

  /// Adds the counts and times of another trace with contact (e.g. the other direction).
  ContactBranchCost& operator+=(const ContactBranchCost& other) {
    continuation += other.continuation;
    pair_search_seconds += other.pair_search_seconds;
    sample_seconds += other.sample_seconds;
    segments += other.segments;
    rebuilds_after_violation += other.rebuilds_after_violation;
    repinnings += other.repinnings;
    safeguarded_starts += other.safeguarded_starts;
    relaxed_starts += other.relaxed_starts;
    return *this;
  }
};

/// Result of trace_contact_branch. `last` is always the last converged sample (the start if
/// none converged), so no result is lost when the trace ends early.
struct ContactBranchTrace {
  std::vector<SpecialPoint> special_points;
  std::vector<LocatedEvent> events;
  ContactBranchSample last;
  bool reached_bound = false;
  std::string message;  ///< why the trace ended
  int steps = 0;
  int failed_steps = 0;
  /// The trace ended next to a fold (ArclengthOptions::fold_approach_tolerance), extrapolated
  /// to lie at fold_parameter.
  bool approached_fold = false;
  double fold_parameter = 0.0;
  ContactBranchCost cost;
};

/// Traces the branch through the equilibrium (or nearby state) (x0, phi0) of `model` with
/// self-contact on `proxy`, in the direction (direction_state, direction_parameter) (e.g. the
/// tangent of a saved sample, or (0, +1) for increasing phi_e), holding `fixed_dofs`. Each
/// converged sample (the corrected start first) goes to on_sample as soon as it converges;
/// special points (changes of the negative count) and events as in trace_branch_along. Throws std::invalid_argument for bad
/// options (naming the field).
ContactBranchTrace trace_contact_branch(
    const ShellModel& model, const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    double phi0, const Eigen::Ref<const Eigen::VectorXd>& direction_state,
    double direction_parameter, const std::vector<Eigen::Index>& fixed_dofs,
    const ContactBranchOptions& options,
    const std::function<void(const ContactBranchSample&)>& on_sample = {},
    const std::function<void(const SpecialPoint&)>& on_special = {},
    const std::vector<BranchEvent>& events = {},
    const std::function<void(const LocatedEvent&)>& on_event = {});

/// The rigid-motion pins to hold at state x (vertex-major): `pins` if
/// options.repin_above_condition is 0 or they hold the rigid motions of x with
/// pinned_rigid_motion_condition at most that, else pins chosen again on x
/// (well_conditioned_pins: the vertex of pins[0] kept, the others among the model's sheet
/// vertices). Shared by trace_contact_branch, the skewed search and grow_with_contact. Throws
/// std::invalid_argument if re-pinning is on and `pins` are not six dofs.
std::vector<Eigen::Index> rigid_pins_for_state(const ShellModel& model,
                                               const Eigen::Ref<const Eigen::VectorXd>& x,
                                               const std::vector<Eigen::Index>& pins,
                                               const ContactBranchOptions& options);

/// The energies, slope, area and penalty forces of `sample` on the pair set `pairs` (as
/// trace_contact_branch reports them), at the sample's excess angle.
ContactBranchSample describe_contact_sample(const ShellModel& model, const ContactProxy& proxy,
                                            const BranchSample& sample,
                                            const ContactCandidates& pairs,
                                            const ContactBranchOptions& options);

}  // namespace growshell
