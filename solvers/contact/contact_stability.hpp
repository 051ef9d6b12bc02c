#pragma once
/// \file
/// Stability of a contact equilibrium: the second-order test of a KKT point of
/// min E(x) subject to c(x) >= 0 (minimize_with_constraints, solve_contact_equilibrium).
///
/// Sign convention (that of constrained_minimizer.hpp): L(x, mu) = E(x) - sum_k mu_k c_k(x),
/// mu_k >= 0 the contact forces (N for gaps in metres), so the Hessian of the Lagrangian is
///   H_L = d2E/dx2 - sum_k mu_k d2c_k/dx2,
/// the same matrix Ipopt's Newton steps used. The constraint term is the curvature of the
/// contact: pressing on a convex obstacle (d2c/dx2 positive in the tangent directions)
/// destabilises, and it can make H_L indefinite on the tangent space although d2E/dx2 is
/// positive definite.
///
/// Second-order condition with strict complementarity: a KKT point is a strict local minimum
/// if Z^T H_L Z is positive definite, Z a basis of the directions tangent to the strongly
/// active constraints (mu_k > 0), and a point with a negative eigenvalue of Z^T H_L Z is not a
/// local minimum. Weakly active constraints (c_k = 0 with mu_k = 0) would need the cone of
/// directions with dc_k >= 0, a copositivity question without an exact inertia count; they
/// are treated as inactive here. That is exact when complementarity is strict (the generic
/// case) and otherwise conservative: the directions counted are a superset of the admissible
/// ones, so negative == 0 and zero == 0 still proves a strict local minimum, while a positive
/// count may include a direction that a weakly active contact blocks (an over-count, never an
/// under-count). Ipopt's interior point never returns
/// exact zeros, so "strongly active" means mu_k above a threshold the caller chooses (e.g. a
/// small fraction of the largest contact force, well above Ipopt's barrier remnants).

#include <vector>

#include <Eigen/Core>

#include "core/inequality_constraints.hpp"
#include "core/sparse_objective.hpp"
#include "solvers/stability/reduced_hessian_inertia.hpp"
#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {

/// Inertia of the Hessian of the Lagrangian E - sum mu_k c_k at x (see the file comment)
/// reduced to the directions that move only free dofs and keep every strongly active
/// constraint (multipliers(k) > active_force_threshold) at first order; see
/// reduced_hessian_inertia for the method and ReducedInertia for the fields
/// (constraints = number of strongly active constraints).
///
/// `constraints` is typically a ContactGapConstraints (any InequalityConstraints works: the
/// evaluation methods are non-const in that interface, hence the non-const reference);
/// `multipliers` are its KKT multipliers in the convention above (ConstrainedResult::
/// multipliers, ContactSolveResult::forces), size constraints.count(), finite and >= 0. ALL
/// multipliers enter H_L, including those below the threshold: the threshold only decides
/// which constraints restrict the directions. `active_force_threshold` in the units of the
/// multipliers (N for gaps), finite and >= 0. `fixed_dofs` as in minimize_with_constraints;
/// `options` are passed to the factorisation of the bordered matrix.
///
/// x need not be an equilibrium (the counts are of H_L at x whatever x is), but they mean
/// stability only at a KKT point. Throws std::invalid_argument naming the problem if the
/// dimensions of energy, constraints, x and multipliers disagree, a multiplier is negative or
/// not finite, the threshold is out of range, a Hessian is not finite at x, or (from
/// reduced_hessian_inertia) a fixed dof is out of range; std::runtime_error if the strongly
/// active constraints have a rank deficient Jacobian on the free dofs (e.g. two pairs that
/// describe the same contact) or MUMPS fails; rethrows what energy or constraints throw.
ReducedInertia contact_constrained_inertia(SparseObjective& energy,
                                           InequalityConstraints& constraints,
                                           const Eigen::Ref<const Eigen::VectorXd>& x,
                                           const Eigen::Ref<const Eigen::VectorXd>& multipliers,
                                           double active_force_threshold,
                                           const std::vector<Eigen::Index>& fixed_dofs,
                                           const SymmetricIndefiniteOptions& options = {});

}  // namespace growshell
