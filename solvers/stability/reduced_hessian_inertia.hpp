#pragma once
/// \file
/// Second-order stability of a constrained equilibrium: the inertia of the Hessian of the
/// Lagrangian reduced to the tangent space of the active constraints, Z^T H Z with Z a basis
/// of null(J), computed exactly without forming Z.
///
/// Why the bordered matrix. Z is dense for a sparse J, so Z^T H Z cannot be formed at shell
/// sizes. The inertia theorem for bordered matrices (Gould 1985, "On practical conditions for
/// the existence and uniqueness of solutions to the general equality quadratic programming
/// problem", Math. Prog. 32; Chabrillac & Crouzeix 1984) gives it from the sparse KKT matrix
///   K = [ H  J^T ]
///       [ J   0  ]
/// instead: if J (m x n) has full row rank m, then
///   In(K) = In(Z^T H Z) + (m, m, 0)   (positive, negative, zero counts),
/// so neg(Z^T H Z) = neg(K) - m, and K is singular exactly when Z^T H Z is. One sparse LDL^T
/// factorisation of K (SymmetricIndefiniteFactorization, MUMPS) gives neg(K) exactly.
///
/// Rank deficient J. With rank r < m the same congruence gives In(K) = In(Z^T H Z) +
/// (r, r, m - r): the dependent rows show up as extra zero eigenvalues of K that no count of
/// K alone can tell from a singular Z^T H Z. Contact sets are prone to this (duplicated or
/// coinciding pairs), so the rank of J is checked separately and a deficient J is an error,
/// never a silently wrong count.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {

/// Inertia of a reduced Hessian Z^T H Z (see reduced_hessian_inertia). The positive count is
/// free_dofs - constraints - negative - zero.
struct ReducedInertia {
  /// Number of negative eigenvalues of Z^T H Z: independent directions, tangent to the active
  /// constraints and moving only free dofs, along which the energy (Lagrangian) decreases to
  /// second order. 0 (with zero == 0) is a strict local minimum.
  int negative = 0;
  /// Number of zero eigenvalues of Z^T H Z, up to the null-pivot threshold of
  /// SymmetricIndefiniteOptions (round-off level by default): neutral directions, e.g. a
  /// symmetry of the problem not removed by fixed dofs or constraints.
  int zero = 0;
  /// Number m of active constraints (rows of J), each removing one direction.
  int constraints = 0;
  /// Number of free dofs (n minus the distinct fixed dofs); Z^T H Z has order
  /// free_dofs - constraints.
  int free_dofs = 0;
};

/// Inertia of the Hessian `hessian_upper` reduced to the null space of `constraint_jacobian`,
/// both restricted to the dofs not in `fixed_dofs`: with H_f, J_f the free rows/columns and Z
/// a basis of null(J_f), the counts of negative and zero eigenvalues of Z^T H_f Z.
///
/// Inputs: `hessian_upper` the upper triangle (row <= column) of the symmetric n x n Hessian
/// of the Lagrangian, column-major and compressed (e.g. from SparseObjective::evaluate); units
/// arbitrary (J/m^2 for a shell). `constraint_jacobian` the m x n Jacobian of the active
/// constraints, one row per constraint (m = 0: the plain inertia of H_f); its row scaling is
/// irrelevant (null(J) and the counts do not depend on it). `fixed_dofs` indices in [0, n);
/// repeats are harmless. Fixed dofs are removed from H and J before K is built: holding a dof
/// is itself a constraint, and removing it keeps K smaller than bordering with it.
///
/// Method (see the file comment): the rows of J_f are normalised and scaled to the largest
/// |entry| of H_f (a congruence of K, so its inertia theory holds unchanged, while K's blocks
/// get comparable magnitudes for pivoting and the null-pivot test); the rank of J_f is checked
/// with an LDL^T factorisation of its normalised Gram matrix J_f J_f^T, rows within about 1e-6
/// (relative) of linear dependence counting as dependent; then K = [H_f J_f^T; J_f 0] (order
/// free_dofs + m) is assembled directly in compressed form and factorised with `options`
/// (ordering, null-pivot threshold), and negative = neg(K) - m, zero = zero_pivots(K). Cost:
/// one factorisation of K plus one of the m x m Gram matrix.
///
/// Throws std::invalid_argument naming the problem if hessian_upper is not square, not
/// compressed or has an entry below the diagonal, if constraint_jacobian does not have n
/// columns, if a fixed dof is outside [0, n), or if an entry of H or J is not finite;
/// std::runtime_error if J_f is rank deficient (a row vanishing on the free dofs, dependent
/// rows, or more constraints than free dofs; the message says which and suggests dropping
/// dependent constraints), or if MUMPS fails.
ReducedInertia reduced_hessian_inertia(const Eigen::SparseMatrix<double>& hessian_upper,
                                       const Eigen::SparseMatrix<double>& constraint_jacobian,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const SymmetricIndefiniteOptions& options = {});

}  // namespace growshell
