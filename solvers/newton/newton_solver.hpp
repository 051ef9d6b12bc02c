#pragma once
/// \file
/// Damped Newton minimisation of a SparseObjective: sparse Cholesky (CHOLMOD) of the Hessian
/// with a diagonal shift when it is indefinite, and a backtracking Armijo line search.

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/sparse_objective.hpp"

namespace growshell {

/// Options of NewtonSolver. Tolerances are absolute, in the units of the objective's
/// gradient (energy per unit of x); the caller scales them to its problem.
struct NewtonOptions {
  /// Maximum number of Newton iterations (each = one accepted step); >= 0.
  int max_iterations = 200;
  /// Convergence when the infinity norm of the gradient over free dofs is <= this; > 0.
  double gradient_tolerance = 1e-8;
  /// Second convergence test (J; 0 = off): the Newton decrement g^T H^-1 g / 2, the energy
  /// the quadratic model still expects to gain, is at most this and the Hessian is positive
  /// definite up to the numerical zero shift_initial_factor. Needed where a nearly free mode (e.g.
  /// the orientation of a buckling pattern on a nearly axisymmetric mesh) keeps the gradient at its
  /// rounding floor.
  double decrement_tolerance = 0.0;
  /// Sufficient-decrease constant of the Armijo condition; in (0, 1).
  double armijo_c1 = 1e-4;
  /// Maximum number of trial points per line search (step halved each time); >= 1.
  int max_line_search_steps = 40;
  /// Cap on |dx|_inf of a Newton step, in units of x (the step is scaled down to it); > 0.
  double max_step_inf_norm = std::numeric_limits<double>::infinity();
  /// Stop (status TravelLimit, x the current iterate) once |x - x0|_inf reaches this, in units
  /// of x; > 0. With max_step_inf_norm b the travel stays below max_travel + b. For callers
  /// whose objective is only trusted near x0 (a contact penalty on the pairs near x0).
  double max_travel = std::numeric_limits<double>::infinity();
  /// First non-zero diagonal shift, relative to the mean |diagonal| of the Hessian; > 0.
  /// It is also the numerical zero of curvature: a Hessian that factorises with this shift
  /// counts as positive definite for decrement_tolerance. Negative curvatures this small come
  /// from symmetries the mesh breaks only weakly (the orientation of a buckling pattern on a
  /// disc), not from physical instabilities (measured: 6e-9 vs 4e-4 for the softest physical
  /// mode at a mean diagonal of ~2e2; docs/verification.md).
  double shift_initial_factor = 1e-10;
  /// Factor by which the shift grows after a failed factorisation; > 1.
  double shift_growth = 10.0;
  /// Levenberg-Marquardt-like control of the shift by the line search, for energies whose
  /// quadratic model fails within a Newton step (a contact penalty's kinks): after a full step
  /// the next iteration tries the unshifted Hessian first and, if it is not positive definite,
  /// starts one growth factor below the last shift; after a step the line search cut to
  /// between 1/4 and 1 it starts from the last shift; after one cut below 1/4, from a shift
  /// shift_growth times larger (the model was not trusted that far). An indefinite Hessian
  /// after a positive definite one is shifted from 1e-4 of the mean |diagonal| up. Off: every
  /// iteration starts one growth factor below the last shift, trying the unshifted Hessian only
  /// once that start falls below the numerical zero.
  bool adaptive_shift = false;
};

/// Record of one accepted Newton iteration.
struct NewtonIterate {
  /// 1-based iteration number.
  int iteration = 0;
  /// Energy after the step.
  double energy = 0.0;
  /// Infinity norm of the free-dof gradient after the step.
  double gradient_inf_norm = 0.0;
  /// Largest coordinate change of the accepted step, |alpha * dx|_inf (units of x).
  double step_inf_norm = 0.0;
  /// Accepted line-search step length alpha in (0, 1] (times the capped Newton step).
  double step_length = 0.0;
  /// Diagonal shift (absolute, Hessian units) of the factorisation that gave the step; 0 if
  /// the Hessian itself was positive definite.
  double shift = 0.0;
  /// Number of factorisations tried in this iteration (1 + number of failed shifts).
  int factorization_attempts = 0;
};

/// Why NewtonSolver::minimize stopped.
enum class NewtonStatus {
  Converged,            ///< Free gradient below the tolerance.
  MaxIterations,        ///< Iteration limit reached first.
  LineSearchFailed,     ///< No trial point gave sufficient decrease.
  NonFiniteValue,       ///< Energy, gradient or Hessian not finite where it had to be.
  FactorizationFailed,  ///< No shift up to the cap made the Hessian positive definite.
  TravelLimit           ///< The iterate moved max_travel away from x0 (not a failure).
};

/// Result of NewtonSolver::minimize.
struct NewtonResult {
  NewtonStatus status = NewtonStatus::MaxIterations;
  /// Human-readable account of the outcome (iteration, gradient norm, shift).
  std::string message;
  /// Final point: on convergence the converged iterate, otherwise the lowest-energy finite
  /// iterate seen (never a non-finite state; x0 itself if nothing better was found).
  Eigen::VectorXd x;
  /// Energy at x.
  double energy = 0.0;
  /// Full gradient dE/dx at x, fixed dofs included (the reaction forces there).
  Eigen::VectorXd gradient;
  /// Number of accepted Newton iterations.
  int iterations = 0;
  /// Total number of numeric factorisations, failed (indefinite) attempts included.
  int factorizations = 0;
  /// One entry per accepted iteration.
  std::vector<NewtonIterate> log;
  /// True iff status == Converged.
  bool converged() const { return status == NewtonStatus::Converged; }
};

/// Newton's method with Hessian shifting and backtracking line search for minimising a
/// SparseObjective, optionally with some dofs held at their initial values.
class NewtonSolver {
 public:
  /// Throws std::invalid_argument naming the first option out of its documented range.
  explicit NewtonSolver(NewtonOptions options = {});

  /// Minimises `objective` from x0 (not modified) with the dofs in `fixed_dofs` held at their
  /// x0 values. `on_iterate` (optional) is called after every accepted iteration.
  /// Throws std::invalid_argument if x0 has the wrong size, a fixed dof is out of range or
  /// listed twice, or the Hessian pattern is not n x n upper triangular with a diagonal entry
  /// for every fixed dof; std::runtime_error if CHOLMOD fails (e.g. out of memory) or the
  /// objective's Hessian stops matching its pattern. Numerical failures of the iteration
  /// (indefiniteness, non-finite values, no decrease) are reported in the result, not thrown.
  NewtonResult minimize(SparseObjective& objective, const Eigen::Ref<const Eigen::VectorXd>& x0,
                        const std::vector<Eigen::Index>& fixed_dofs = {},
                        const std::function<void(const NewtonIterate&)>& on_iterate = {});

  /// The options in use.
  const NewtonOptions& options() const { return options_; }

 private:
  NewtonOptions options_;
};

/// Name of a status ("Converged", "MaxIterations", ...).
const char* to_string(NewtonStatus status);

}  // namespace growshell
