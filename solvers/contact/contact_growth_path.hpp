#pragma once
/// \file
/// Following stable states of a growing shell with self-contact in natural steps of the excess
/// angle: every step minimises shell + contact penalty from the previous state, with the pair
/// set rebuilt until it settles, and a state that is not a minimum (a saddle) is pushed along
/// its lowest mode and minimised again. Where a stable branch ends at a fold the path drops onto
/// whatever stable state lies below, as a slowly grown sheet would; this is how the wound-up
/// shapes beyond the skewed cone's fold are reached.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// The pairs near y that the penalty of `options` acts on: within contact_distance +
/// candidate_margin, chosen by options.selection (as a trace's segment builds them).
ContactCandidates near_penalty_pairs(const ContactProxy& proxy,
                                     const Eigen::Ref<const Eigen::VectorXd>& y,
                                     const ContactBranchOptions& options);

/// Shell + contact penalty (stiffness, contact distance of `options`) on a fixed pair set: the
/// objective that relaxations minimise. Owns the pair set and the penalty that `energy` (the
/// PenalizedEnergy adaptor) refers to, so it is not copyable or movable.
struct PenalizedShell {
  ContactCandidates pairs;
  ContactPenalty penalty;
  PenalizedEnergy energy;
  PenalizedShell(const ShellModel& model, const ContactProxy& proxy, ContactCandidates pair_set,
                 const ContactBranchOptions& options)
      : pairs(std::move(pair_set)),
        penalty(proxy, pairs, options.contact_distance, options.stiffness, model.dimension(),
                options.gap),
        energy(model, penalty) {}
  PenalizedShell(const PenalizedShell&) = delete;
  PenalizedShell& operator=(const PenalizedShell&) = delete;
};

/// Outcome of relax_with_contact, with what it cost.
struct ContactRelaxation {
  /// True if y is the minimiser: Newton converged and the pair set settled.
  bool relaxed = false;
  /// E + P at y (J), on success.
  double energy = 0.0;
  /// Why not, on failure: Newton's failure, the step budget used up, or max_rounds passed.
  std::string message;
  /// Newton solves run (one per round, or per bounded stretch of motion), their accepted
  /// iterations and their numeric factorisations (failed indefinite attempts included). Each
  /// solve starts with a search for the pairs near its state.
  int solves = 0;
  int newton_iterations = 0;
  int factorizations = 0;
};

/// Minimises shell + penalty (pairs of options: near y within contact_distance +
/// candidate_margin, stiffness, selection) at the excess angle phi_e from y, with
/// `fixed_dofs` held. The result must also be an equilibrium, to newton.gradient_tolerance, of
/// the penalty on the pairs near the result itself (the energy a trace from it continues), or
/// the set it was minimised with must contain every pair near the result (then no contact is
/// missed; a vertex between two layers keeps a triangle on each side). Otherwise it is
/// minimised again with the union of the old and the new pairs (the set only grows, so nearest
/// triangles that flip back and forth cannot cycle).
///
/// With a finite newton.max_step_inf_norm b, each solve stops once a dof has moved
/// candidate_margin / 4 (steps capped at that too) and goes on with the pairs near the new
/// state, so no two primitives approach by candidate_margin unseen and no vertex is pushed
/// through a layer whose triangles are not in the set; newton.max_iterations then counts the
/// steps of all solves (without a bound it applies to each round).
///
/// y ends as the minimiser on success, otherwise as the last iterate.
ContactRelaxation relax_with_contact(const ShellModel& model, double excess_angle,
                                     const ContactProxy& proxy, Eigen::VectorXd& y,
                                     const std::vector<Eigen::Index>& fixed_dofs,
                                     const ContactBranchOptions& options,
                                     const NewtonOptions& newton, int max_rounds = 10);

/// Settings of grow_with_contact.
struct ContactGrowthOptions {
  ContactBranchOptions contact;  ///< distances, stiffness and pair selection (step fields unused)
  NewtonOptions newton;          ///< the minimisation of every step
  double max_step = 0.05;        ///< largest step in phi_e (rad)
  /// The first step tried (0: max_step). A path resumed from one of its points passes that
  /// point's sample.sample.next_step here, and its pins as fixed_dofs, to go on exactly as the
  /// path would have.
  double initial_step = 0.0;
  double min_step = 1e-3;        ///< a step failing below this ends the path
  /// Pushes along the lowest mode (h/2 at its largest entry) before a saddle counts as a
  /// failed step.
  int max_saddle_escapes = 3;
  /// Start each step's minimisation from the secant extrapolation of the path's last two
  /// accepted states (x + (x - x_before) dphi / (phi - phi_before), the pins held), instead of
  /// from x. The extrapolation is tried only if it moves no dof farther than
  /// contact.candidate_margin (after a longer step, a slide onto another state, it is no part
  /// of a smooth path), and only if no proxy vertex passes through a proxy triangle on the
  /// straight way there (first_vertex_triangle_crossing); its result is kept only
  /// if it is a strict minimum that lies within |extrapolation|_inf of the extrapolated state
  /// (the same stable state, not one the extrapolation overshot into); otherwise the step is
  /// taken from x as without it, so where a stable state ends the path drops from the last
  /// state as before.
  bool secant_predictor = true;
};

/// What finding one accepted point of grow_with_contact cost, summed over every try: the
/// prediction (discarded or not), the minimisations from the last state, the pushes off saddles
/// and the step sizes that failed before the accepted one.
struct ContactStepWork {
  int tries = 0;                ///< minimisations started (prediction, last state, each push)
  int halvings = 0;             ///< step sizes that failed before the accepted one
  int solves = 0;               ///< Newton solves (ContactRelaxation::solves)
  int newton_iterations = 0;    ///< accepted Newton iterations
  int factorizations = 0;       ///< Newton's factorisations plus one per stability test
  int stability_tests = 0;      ///< Cholesky tests of a relaxed state
  int eigen_solves = 0;         ///< lowest eigenpairs computed (at saddles)
  bool prediction_discarded = false;  ///< the secant prediction was tried and not kept
};

/// One accepted (stable) state of the path.
struct ContactGrowthPoint {
  /// State, energies, forces, pairs (negative count 0); sample.next_step is the step the path
  /// tries next.
  ContactBranchSample sample;
  /// The rigid-motion pins this point was found with (the path's next step starts from them).
  std::vector<Eigen::Index> pins;
  int saddle_escapes = 0;
  /// The minimisation from the previous state ended on a saddle and had to be pushed off it:
  /// the previous stable branch ended, and the path jumped to another stable state.
  bool jumped = false;
  /// The minimisation started from the secant prediction (ContactGrowthOptions).
  bool from_prediction = false;
  /// What finding this point cost.
  ContactStepWork work;
};

/// Outcome of grow_with_contact; `last` always holds the last accepted point.
struct ContactGrowthResult {
  bool reached_target = false;
  std::string message;
  ContactGrowthPoint last;
  /// The accepted state before `last` (x and parameter; x empty if there is none): passed as
  /// `previous` to a path continued from `last`, it gives that path the same predictor.
  BranchSample before_last;
  int steps = 0;
  int failed_steps = 0;
  /// Steps accepted from the secant predictor, and predictions discarded (a passage through a
  /// layer on the way, a relaxation that failed, a saddle, or a minimum away from the
  /// prediction), whose step was then taken from the last state.
  int predicted_steps = 0;
  int discarded_predictions = 0;
};

/// Grows from the equilibrium (or any state) x0 at phi0 towards phi_target in natural steps,
/// accepting only strict minima of shell + penalty; each accepted point goes to on_point as
/// soon as it is found. A strict minimum is a Hessian of shell + penalty (pins held) whose
/// Cholesky factorisation succeeds; only a saddle's lowest mode is computed, to push off it.
/// The path carries from one step to the next only the state, the step, the pins and (for the
/// secant predictor) the accepted state before: started again from a point with its step
/// (options.initial_step), pins (fixed_dofs) and the state before it (`previous`, e.g. the
/// result's before_last; nullptr: the first step is taken from x0 alone), it goes on as it
/// would have. Throws std::invalid_argument for bad options or a `previous` state of the wrong
/// size.
ContactGrowthResult grow_with_contact(
    const ShellModel& model, const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    double phi0, double phi_target, const std::vector<Eigen::Index>& fixed_dofs,
    const ContactGrowthOptions& options,
    const std::function<void(const ContactGrowthPoint&)>& on_point = {},
    const BranchSample* previous = nullptr);

}  // namespace growshell
