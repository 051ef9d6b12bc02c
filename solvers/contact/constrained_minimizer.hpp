#pragma once
/// \file
/// Minimisation of a SparseObjective subject to smooth inequality constraints c(x) >= 0 (the
/// contact gaps) with the interior-point solver Ipopt, exact Hessian of the Lagrangian.
///
/// Sign convention. The Lagrangian is L(x, mu) = E(x) - sum_k mu_k c_k(x), and at a solution
///   dE/dx = sum_k mu_k dc_k/dx,   mu_k >= 0,   c_k >= 0,   mu_k c_k = 0.
/// With E in joules and gaps c_k in metres, mu_k is in newtons: the magnitude of the force with
/// which constraint k pushes the sheet apart along dc_k/dx (for a gap with |dc/dx| = 1 per
/// contact point, exactly the normal contact force). Ipopt's own multipliers have the opposite
/// sign (its Lagrangian is E + sum lambda_k c_k); the conversion happens inside the .cpp.
///
/// Ipopt never appears in this header: it is a private dependency of the library.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/inequality_constraints.hpp"
#include "core/sparse_objective.hpp"

namespace growshell {

/// Options of minimize_with_constraints.
///
/// Scaling. Ipopt solves the problem in the scaled variables x~ = x / length_scale, with
/// objective E~ = E / (force_scale length_scale) and constraints c~ = c / length_scale, so that
/// its multipliers are mu / force_scale and its dual infeasibility is the out-of-balance force
/// divided by force_scale. Ipopt's own gradient-based automatic scaling is switched off, so the
/// dimensionless `tolerance` means exactly: out-of-balance force <= tolerance * force_scale,
/// violation <= tolerance * length_scale, complementarity mu_k c_k <= tolerance * force_scale *
/// length_scale (Ipopt divides the first and last by max(1, mean |mu| / (100 force_scale)) when
/// multipliers are large). For a sheet of thickness h take length_scale = h (tolerances then
/// tighten with h) and force_scale = ShellModel::natural_force_scale() or the expected contact
/// force. The absolute tolerances below must hold as well.
struct ConstrainedMinimizerOptions {
  /// Length (m) in which positions and gaps are measured inside Ipopt; > 0.
  double length_scale = 1.0;
  /// Force (N) in which forces and multipliers are measured inside Ipopt; > 0.
  double force_scale = 1.0;
  /// Ipopt `tol`: relative tolerance of the scaled KKT conditions (see above); > 0.
  double tolerance = 1e-8;
  /// Ipopt `constr_viol_tol`: largest allowed violation max_k(-c_k) at the solution, in the
  /// units of c (metres for gaps); > 0. Ipopt relaxes c >= 0 to c >= -bound_relax_factor and
  /// measures violations against the relaxed bound; the relaxation is set to a tenth of this
  /// tolerance (at most Ipopt's default 1e-8), so a converged result has
  /// max_violation <= 1.1 constraint_violation_tolerance.
  double constraint_violation_tolerance = 1e-8;
  /// Ipopt `compl_inf_tol`: largest allowed mu_k c_k at the solution (J for gaps); > 0.
  double complementarity_tolerance = 1e-8;
  /// Ipopt `dual_inf_tol`: largest allowed out-of-balance force |dE/dx - sum mu_k dc_k/dx|_inf
  /// over free dofs (N); > 0. Ipopt's default 1; the relative `tolerance` is usually stricter.
  double dual_infeasibility_tolerance = 1.0;
  /// Ipopt `acceptable_tol` (relative like `tolerance`, >= tolerance) and `acceptable_iter`
  /// (>= 0; 0 disables): the solve also stops, with status Solved_To_Acceptable_Level, after
  /// this many consecutive iterates that meet acceptable_tolerance and all absolute tolerances
  /// above (the acceptable absolute tolerances are set equal to the strict ones). This ends
  /// solves whose relative error sits at a rounding floor just above `tolerance`.
  double acceptable_tolerance = 1e-6;
  int acceptable_iterations = 15;
  /// Ipopt `max_iter`; >= 0.
  int max_iterations = 3000;
  /// Use the given initial multipliers (if any) for a warm start: Ipopt's
  /// warm_start_init_point with the pushes and barrier parameter below. Ignored when
  /// minimize_with_constraints gets no multipliers.
  bool warm_start = true;
  /// Ipopt `bound_push` and `bound_frac` (cold start): how far (relative, scaled units) the
  /// slacks of the constraints are pushed inside c >= 0 at the start; in (0, 0.5].
  double bound_push = 1e-2;
  /// Ipopt `warm_start_bound_push`, `warm_start_bound_frac`, `warm_start_slack_bound_push`,
  /// `warm_start_slack_bound_frac` and `warm_start_mult_bound_push` (warm start): small, so a
  /// warm start stays close to the given point; in (0, 0.5].
  double warm_start_push = 1e-9;
  /// Ipopt `mu_init` for a warm start (scaled complementarity units; > 0). Small, so that the
  /// barrier does not push a converged warm start away from the active set. A cold start uses
  /// Ipopt's default 0.1.
  double warm_start_barrier = 1e-9;
  /// Ipopt `linear_solver` for the KKT systems (Debian's build: "mumps").
  std::string linear_solver = "mumps";
  /// Ipopt `print_level` (0..12). The library never prints by default: with 0 Ipopt gets no
  /// console journal and no output file; > 0 is for debugging only and prints to stdout.
  int print_level = 0;
};

/// Result of minimize_with_constraints.
struct ConstrainedResult {
  /// Final point (metres): Ipopt's final iterate if it is finite and has a finite energy,
  /// otherwise x0. On failure it is whatever Ipopt stopped at (possibly infeasible); a caller
  /// that follows a path keeps its last converged point instead.
  Eigen::VectorXd x;
  /// One per constraint: the KKT multiplier mu_k of c_k >= 0 in E - sum mu_k c_k, i.e. the
  /// force (N for gaps in metres) with which constraint k pushes. >= 0 at a solution (Ipopt's
  /// interior point keeps them strictly positive).
  Eigen::VectorXd multipliers;
  /// E(x) (J).
  double energy = 0.0;
  /// Ipopt iterations performed.
  int iterations = 0;
  /// Ipopt's ApplicationReturnStatus as an int (0 Solve_Succeeded, 1
  /// Solved_To_Acceptable_Level, -1 Maximum_Iterations_Exceeded, ...).
  int status = -199;
  /// Plain-words account of `status` ("Ipopt: converged", "Ipopt: local infeasibility", ...).
  std::string message;
  /// max(0, max_k -c_k(x)) (metres for gaps); 0 if there are no constraints.
  double max_violation = 0.0;
  /// True for Solve_Succeeded and Solved_To_Acceptable_Level: both meet the absolute
  /// tolerances of the options.
  bool converged() const { return status == 0 || status == 1; }
};

/// Minimises `energy` over x subject to constraints.evaluate(x) >= 0, from x0, with the dofs
/// in `fixed_dofs` held exactly at their x0 values (Ipopt's make_parameter: they are removed
/// from the problem). `initial_multipliers` (size count(), >= 0, in the convention of
/// ConstrainedResult::multipliers) warm-starts the duals when options.warm_start is set.
///
/// A non-finite energy or gradient at a trial point makes Ipopt cut its step (the point is
/// treated as outside the domain). Throws std::invalid_argument naming the problem for
/// mismatched dimensions, a fixed dof out of range or listed twice, bad multipliers, an
/// option out of its range or one Ipopt rejects, or patterns that are not upper triangular
/// n x n (Hessians) or m x n (Jacobian); rethrows (after Ipopt has stopped) an exception
/// thrown by energy or constraints, and throws std::runtime_error if a Hessian or Jacobian
/// stops matching its pattern. Numerical failures of the solve are reported in the result.
ConstrainedResult minimize_with_constraints(SparseObjective& energy,
                                            InequalityConstraints& constraints,
                                            const Eigen::Ref<const Eigen::VectorXd>& x0,
                                            const std::vector<Eigen::Index>& fixed_dofs,
                                            const ConstrainedMinimizerOptions& options,
                                            const Eigen::VectorXd* initial_multipliers = nullptr);

/// Plain-words description of an Ipopt ApplicationReturnStatus value (as in
/// ConstrainedResult::message); unknown values give "Ipopt: unknown return status <n>".
std::string ipopt_status_message(int status);

}  // namespace growshell
