#pragma once
/// \file
/// Pseudo-arclength continuation of equilibria g(x; lambda) = 0 of a parametrised energy,
/// through folds and along unstable branches, with stability (negative eigenvalue count of
/// the Hessian) and located special points. Algorithm: docs/continuation.md.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "libshell/mesh/rigid_motion.hpp"

namespace growshell {

struct BranchSample;

/// Step control and tolerances of trace_branch.
struct ArclengthOptions {
  double initial_step = 0.05;  ///< first arclength step
  double min_step = 1e-7;      ///< a step that fails below this ends the trace
  double max_step = 0.5;
  /// How the corrector solves the bordered system of a step.
  enum class Corrector {
    /// Newton's method: every iteration assembles and factorises the Hessian.
    Newton,
    /// The chord method (modified Newton): the iterations reuse the factorisation of the
    /// last corrected point (the previous sample's, which its tangent and stability index
    /// needed anyway) and assemble only the gradient; the converged point is factorised once,
    /// for its tangent and stability index. Where the chord stops contracting (a residual
    /// not below `chord_contraction` times the previous one) or needs more than
    /// `max_chord_iterations`, the step goes on by Newton from its best iterate, so it
    /// converges to the same tolerance as Newton wherever Newton does.
    Chord,
  };
  Corrector corrector = Corrector::Newton;
  int target_iterations = 4;   ///< Newton iterations the step control aims at
  int max_corrector_iterations = 15;
  /// Iterations the correction of the trace's start may take (0: max_corrector_iterations). A
  /// start is no predictor one step from a converged point: it may lie off the branch by
  /// whatever brought it there (e.g. a contact branch's previous sample on a rebuilt pair set),
  /// and there is no step to halve. Lets max_corrector_iterations be low (a guard against
  /// correctors that converge onto another branch) without failing such starts.
  int start_corrector_iterations = 0;
  /// Newton's corrector gives a step up once this many iterations have left its residual (the
  /// free gradient's inf-norm) above `stall_reduction` times the predictor's, instead of
  /// running on to max_corrector_iterations. On a contact penalty's piecewise Hessian a
  /// corrector that has not converged by then cycles between pieces (the residual repeating
  /// with period 2 or 3) or diverges; one that converges has fallen far below it (the slowest
  /// measured, 7 iterations to a tenth). 0 (default): only max_corrector_iterations.
  int stall_iterations = 0;
  double stall_reduction = 0.1;  ///< in (0, 1]
  /// After a failed step the next this many accepted steps keep their length (the step
  /// control's factor capped at 1) instead of lengthening on a corrector that converged in few
  /// iterations. Where steps fail by leaving the region in which Newton converges, not by
  /// needing many iterations inside it (a contact penalty's pairs entering within a step), the
  /// iteration count of the accepted steps says nothing of that limit, and without this memory
  /// every accepted step doubles the step into a failure. 0 (default): no memory.
  int growth_pause_after_failure = 0;
  /// Accepted steps of such a pause still to come at the start: a trace that continues another
  /// (the next pair-set segment of a contact branch) passes BranchTrace::growth_pause_left.
  int initial_growth_pause = 0;
  /// Chord iterations the step control aims at (Corrector::Chord): a step whose chord
  /// converged in fewer is lengthened, in more shortened, as for Newton's target_iterations.
  int target_chord_iterations = 10;
  int max_chord_iterations = 25;
  double chord_contraction = 0.7;
  /// Safeguard of Newton's corrector: an update that raises the 2-norm of the free gradient
  /// above `residual_growth_limit` times its value is halved, up to this many times, each
  /// trial costing a gradient-only assembly (the update is Newton's on the bordered system,
  /// so it is a descent direction of that norm, and a halved update stays on the corrector's
  /// hyperplane). 0 (default): full updates, as plain Newton. Where the Hessian is only
  /// piecewise smooth (a contact penalty whose pairs enter, or whose nearest triangle
  /// changes, inside a step) a full update can overshoot into a region where Newton diverges.
  int max_residual_backtracks = 0;
  /// The growth of the residual's 2-norm that an update may cause before it is halved (>= 1).
  /// Newton's iterates converge quadratically without decreasing that norm monotonically
  /// (near the contact penalty's stiff pairs the first updates of a converging corrector raise
  /// it by up to 3x), so a strictly monotone test would halve good updates; the divergence it
  /// guards against raises it a hundredfold per update.
  double residual_growth_limit = 10.0;
  double max_tangent_angle = 0.3;  ///< radians between successive tangents
  /// Steps no longer than this skip the tangent-angle test (a converged corrector suffices).
  /// Where the tangent jumps by a finite angle over an arbitrarily short step (a Hessian that
  /// is only piecewise smooth, e.g. a contact penalty entering, or a nearly singular augmented
  /// system next to an imperfect branch point) the test would otherwise reject every step
  /// down to min_step. 0 (default) keeps the test for all steps.
  double angle_test_max_step = 0.0;
  double gradient_tolerance = 1e-8;  ///< absolute, inf-norm of the free gradient
  /// Weight of the state in the arclength norm: |du|^2 = state_weight |dx|^2 / n + dlambda^2.
  double state_weight = 1.0;
  double special_point_tolerance = 1e-6;  ///< |dlambda| to which special points are located
  double parameter_min = -1e300, parameter_max = 1e300;  ///< the trace stops outside
  int max_steps = 10000;
  /// End the trace once this many special points were found (0 = no limit).
  int max_special_points = 0;
  /// A trace meant to end at a fold, whose steps fail next to it (correctors that do not
  /// converge, or that converge onto another branch and are rejected, past a fold where the
  /// branch turns sharply), ends there once the fold is this close in lambda, instead of
  /// halving its step down to min_step. The fold is extrapolated from the last two samples:
  /// dlambda/ds falling linearly to zero puts it at lambda + t^2 / (2 |dt/ds|), t the last
  /// sample's dlambda/ds (a regular fold is a parabola in (s, lambda)). Checked after each
  /// failed step, whatever made the step fail (a tangent that turned too far, too, which steps
  /// next to any fold may do): for traces that end at the fold anyway. The trace ends with
  /// BranchTrace::approached_fold. 0 (default): never.
  double fold_approach_tolerance = 0.0;
  /// If set, the stability index of every corrected point (BranchSample::negative_eigenvalues,
  /// and so where special points lie) is this function of the point (its x and parameter are
  /// set) instead of the negative count of the traced Hessian. Used when tracing in a
  /// symmetric subspace: the traced Hessian there has only the symmetric modes, and the
  /// index that matters is the full Hessian's. It may throw std::runtime_error (e.g. at a
  /// singular point): the point then counts as not converged.
  std::function<int(const BranchSample&)> stability_index;
  /// If set, a step from sample `from` whose corrector converged to `to` counts only if this
  /// accepts it; otherwise it fails, and its step is halved. A test that the corrector stayed
  /// on the branch being traced, where Newton on the step's hyperplane can converge onto a
  /// nearby branch instead (next to a fold), e.g. by a symmetry the traced branch breaks and
  /// the other has. Not applied to the start, nor to the points of a bisection. It may throw
  /// std::runtime_error: the step then fails.
  std::function<bool(const BranchSample& from, const BranchSample& to)> accept_step;
};

/// A converged point of a branch.
struct BranchSample {
  double parameter = 0.0;
  Eigen::VectorXd x;
  double arclength = 0.0;
  int negative_eigenvalues = 0;  ///< of the Hessian with the fixed dofs removed
  /// Iterations of the corrector that converged: Newton's, or, with Corrector::Chord, the
  /// chord iterations plus any Newton iterations after them.
  int corrector_iterations = 0;
  Eigen::VectorXd tangent_state;  ///< dx/ds
  double tangent_parameter = 0.0;  ///< dlambda/ds
  /// The arclength step the trace takes from this sample (0: not known). A trace resumed from
  /// the sample with it as ArclengthOptions::initial_step takes the same steps as the trace
  /// that wrote it.
  double next_step = 0.0;
  /// Set by a trace in reduced coordinates (trace_branch_in_subspace), empty otherwise: the
  /// reduced state y it traced and the rigid motion from the caller's frame into the
  /// subspace's, with x = reduced_frame^-1(Q y) bit for bit. Rebuilding y from x is exact
  /// only to rounding, so a trace resumed from the sample (resume_branch_in_subspace) starts
  /// from these to take the very steps of the trace that wrote it.
  Eigen::VectorXd reduced_x;
  RigidMotion reduced_frame;
};

/// A change of the negative eigenvalue count between two samples, located in lambda.
struct SpecialPoint {
  enum class Kind { Fold, BranchPoint };
  Kind kind = Kind::Fold;
  double parameter = 0.0;
  Eigen::VectorXd x;
  int negative_before = 0;
  int negative_after = 0;
  int multiplicity = 0;  ///< |change of the count|
  double bracket_width = 0.0;  ///< |dlambda| of the final bracket
};

const char* to_string(SpecialPoint::Kind kind);

/// A scalar test function along a branch; an event is where it changes sign between two
/// samples, located by bisection in arclength to |dlambda| <= special_point_tolerance.
struct BranchEvent {
  std::string kind;  ///< e.g. "contact", "eb_max"
  std::function<double(const BranchSample&)> value;
  bool stop = false;  ///< end the trace at this event
  /// The test function reads the sample's tangent (else the points of its bisection come
  /// without one, which spares the chord corrector a factorisation per point).
  bool needs_tangent = false;
};

/// A located event.
struct LocatedEvent {
  std::string kind;
  double parameter = 0.0;
  Eigen::VectorXd x;
  double bracket_width = 0.0;
};

/// Where a trace spent its effort (wall-clock seconds, steady clock). The inertia (stability)
/// comes out of the same LDL^T factorisation that the corrector uses, so it has no separate
/// cost.
struct TraceCost {
  int linearizations = 0;      ///< energy/gradient/Hessian assemblies (each then factorised)
  int factorizations = 0;      ///< LDL^T factorisations that succeeded or failed
  int solves = 0;              ///< triangular solves with the factorisation
  /// Gradient-only assemblies of the chord corrector (ArclengthOptions::Corrector::Chord).
  int gradient_evaluations = 0;
  /// Chord correctors that stopped contracting and went on by Newton.
  int chord_fallbacks = 0;
  /// Halvings of Newton updates (ArclengthOptions::max_residual_backtracks).
  int residual_backtracks = 0;
  /// Newton correctors given up by ArclengthOptions::stall_iterations.
  int stalled_correctors = 0;
  /// Converged steps that ArclengthOptions::accept_step rejected.
  int rejected_steps = 0;
  /// Converged steps whose tangent turned by more than ArclengthOptions::max_tangent_angle.
  /// A trace's failed steps are these, the rejected ones, and correctors that did not
  /// converge.
  int tangent_angle_rejections = 0;
  double assembly_seconds = 0.0;  ///< family.evaluate (the chord's gradients too) + dg/dlambda
  double factorization_seconds = 0.0;  ///< numeric LDL^T factorisation with its inertia
  double solve_seconds = 0.0;
  double event_seconds = 0.0;  ///< the event test functions and ArclengthOptions::accept_step
  /// ArclengthOptions::stability_index: calls and their time (e.g. the full Hessian's
  /// assembly and LDL^T factorisation when tracing in a symmetric subspace).
  int stability_evaluations = 0;
  double stability_seconds = 0.0;
  double callback_seconds = 0.0;  ///< on_sample / on_special / on_event (the caller's output)
  double total_seconds = 0.0;

  /// Adds the counts and times of another trace (e.g. of the next segment or stage).
  TraceCost& operator+=(const TraceCost& other) {
    linearizations += other.linearizations;
    factorizations += other.factorizations;
    solves += other.solves;
    gradient_evaluations += other.gradient_evaluations;
    chord_fallbacks += other.chord_fallbacks;
    residual_backtracks += other.residual_backtracks;
    stalled_correctors += other.stalled_correctors;
    rejected_steps += other.rejected_steps;
    tangent_angle_rejections += other.tangent_angle_rejections;
    assembly_seconds += other.assembly_seconds;
    factorization_seconds += other.factorization_seconds;
    solve_seconds += other.solve_seconds;
    event_seconds += other.event_seconds;
    stability_evaluations += other.stability_evaluations;
    stability_seconds += other.stability_seconds;
    callback_seconds += other.callback_seconds;
    total_seconds += other.total_seconds;
    return *this;
  }
};

struct BranchTrace {
  std::vector<SpecialPoint> special_points;
  std::vector<LocatedEvent> events;
  BranchSample last;       ///< last converged sample (the start if nothing converged)
  bool reached_bound = false;  ///< stopped at parameter_min / parameter_max / max_steps
  std::string message;     ///< why the trace ended
  bool start_converged = false;  ///< the corrector converged at the start (else `last` is it)
  int steps = 0;
  int failed_steps = 0;
  /// Samples that landed just past a special point and were replaced by a step over it.
  int branch_point_steps_over = 0;
  /// Accepted steps of a growth pause (ArclengthOptions::growth_pause_after_failure) still to
  /// come where the trace ended.
  int growth_pause_left = 0;
  /// The trace ended next to a fold (ArclengthOptions::fold_approach_tolerance), extrapolated
  /// to lie at fold_parameter; `last` is the sample before it.
  bool approached_fold = false;
  double fold_parameter = 0.0;
  TraceCost cost;  ///< of this call (the branch-point search and events included)
};

/// Traces the branch through the equilibrium (x0, lambda0) — x0 must satisfy g(x0; lambda0)
/// ~ 0 — starting in the direction of increasing lambda if direction > 0, decreasing
/// otherwise. Each converged sample goes to on_sample as soon as it converges; special points
/// go to on_special. The trace never dies on one bad step: failed steps are halved down to
/// options.min_step, and the result always holds the last converged sample.
BranchTrace trace_branch(const ParametrizedObjective& family, const Eigen::Ref<const Eigen::VectorXd>& x0,
                         double lambda0, int direction, const std::vector<Eigen::Index>& fixed_dofs,
                         const ArclengthOptions& options,
                         const std::function<void(const BranchSample&)>& on_sample = {},
                         const std::function<void(const SpecialPoint&)>& on_special = {});

/// As trace_branch, but the start is corrected on the hyperplane through (x0, lambda0)
/// orthogonal to the direction (direction_state, direction_parameter), and the branch is
/// followed in that direction. Used after branch switching, where the fixed-lambda correction
/// of trace_branch could slide back onto the branch left behind.
BranchTrace trace_branch_along(const ParametrizedObjective& family,
                               const Eigen::Ref<const Eigen::VectorXd>& x0, double lambda0,
                               const Eigen::Ref<const Eigen::VectorXd>& direction_state,
                               double direction_parameter,
                               const std::vector<Eigen::Index>& fixed_dofs,
                               const ArclengthOptions& options,
                               const std::function<void(const BranchSample&)>& on_sample = {},
                               const std::function<void(const SpecialPoint&)>& on_special = {},
                               const std::vector<BranchEvent>& events = {},
                               const std::function<void(const LocatedEvent&)>& on_event = {});

/// Critical mode at a branch point: a null vector of the Hessian at (x, lambda), by inverse
/// iteration started from `hint` (e.g. the out-of-plane field cos(n theta) of the n-fold
/// mode; the iteration stays in the hint's symmetry class, which picks one of a degenerate
/// pair). Returns the mode scaled to unit weighted norm, with fixed dofs zero; throws
/// std::runtime_error if the Hessian cannot be factorised there.
Eigen::VectorXd critical_mode(const ParametrizedObjective& family, const Eigen::Ref<const Eigen::VectorXd>& x,
                              double lambda, const Eigen::Ref<const Eigen::VectorXd>& hint,
                              const std::vector<Eigen::Index>& fixed_dofs,
                              const ArclengthOptions& options, int iterations = 4);

}  // namespace growshell
