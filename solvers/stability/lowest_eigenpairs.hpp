#pragma once
/// \file
/// A few eigenpairs of a sparse symmetric Hessian with pinned dofs removed: the lowest ones
/// (the unstable directions and softest modes of an equilibrium) or those nearest a shift.
///
/// Method: shift-and-invert block (subspace) iteration with Rayleigh-Ritz, on the free dofs
/// only, using the MUMPS LDL^T factorisation of H - sigma I (SymmetricIndefiniteFactorization).
/// A block iteration converges a whole invariant subspace, so a multiple eigenvalue (generic
/// for symmetric sheets: the n-fold modes of a disc come in pairs) is returned with a full
/// orthonormal basis of its eigenspace, not one arbitrary vector of it.
///
/// Fixed dofs: their rows and columns are removed (FixedDofElimination), and in every shifted
/// matrix their diagonal holds the positive artificial pivot, so they neither appear among the
/// eigenvalues nor disturb the inertia count; the iteration vectors live on the free dofs.
///
/// Lowest eigenvalues (shift = NaN, the default): by Sylvester's law of inertia, the number
/// nu(sigma) of negative pivots of H - sigma I is the number of eigenvalues below sigma. A
/// bisection on sigma (logarithmic in |sigma|, starting from 0 and the Gershgorin bounds)
/// finds sigma_lo < lambda_1 with lambda_1 - sigma_lo at most 1% of |lambda_1| (or of
/// 1e-10 ||H||). Shifting there, the eigenvalues nearest the shift are the lowest ones, and
/// eigenvalue lambda_k converges at the rate (lambda_k - sigma)/(lambda_{b+1} - sigma) per
/// iteration for a block of b vectors. Every result is checked by inertia at the end: the
/// number of eigenvalues up to the largest reported one must equal the number of Ritz values
/// there, so an eigenvalue the iteration missed is reported (converged = false).

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/sparse_objective.hpp"

namespace growshell {

/// Options of lowest_eigenpairs.
struct EigenpairOptions {
  /// Number of eigenpairs wanted (1 .. number of free dofs).
  int count = 4;
  /// Target: the `count` eigenvalues nearest this value (units of the Hessian). NaN (the
  /// default) means the `count` lowest (most negative first). Must not be infinite.
  double shift = std::numeric_limits<double>::quiet_NaN();
  /// Block size b of the subspace iteration; 0 means count + max(4, count / 2). A larger
  /// block converges faster when eigenvalue count + 1 is close to eigenvalue count. Clamped to
  /// the number of free dofs; must be 0 or >= count.
  int block_size = 0;
  /// Maximum number of block iterations (each one solve per block vector); >= 1.
  int max_iterations = 200;
  /// Convergence test on every wanted pair: ||H v - lambda v||_2 <= tolerance * ||H||_inf,
  /// with ||H||_inf the largest absolute row sum of the free block (>= ||H||_2). The
  /// eigenvalue error is then below tolerance * ||H||_inf as well. Must be finite and > 0.
  double tolerance = 1e-10;
};

/// Eigenpairs of the Hessian with the fixed dofs removed.
struct Eigenpairs {
  /// Eigenvalues, ascending (units of the Hessian, e.g. N/m for a shell energy in J and
  /// coordinates in m).
  Eigen::VectorXd values;
  /// Eigenvectors as columns, in the order of `values`, in the full dof basis (n rows):
  /// orthonormal in the 2-norm, exactly zero at the fixed dofs.
  Eigen::MatrixXd vectors;
  /// ||H v - lambda v||_2 / ||H||_inf of each pair.
  Eigen::VectorXd residuals;
  /// Number of eigenvalues strictly below the lowest reported one, from the inertia check
  /// (0 in lowest mode when converged). Eigenvalues are counted with multiplicity.
  int eigenvalues_below = 0;
  /// The shift sigma actually factorised for the iteration.
  double shift = 0.0;
  /// Block iterations performed.
  int iterations = 0;
  /// LDL^T factorisations performed (bisection, iteration and inertia check).
  int factorizations = 0;
  /// True when every pair met the tolerance and the inertia check found no missed eigenvalue.
  bool converged = false;
  /// What happened, for the log.
  std::string message;
};

/// The options.count eigenpairs of the Hessian of `objective` at x (dofs `fixed_dofs`
/// removed) nearest options.shift, or the lowest ones when the shift is NaN; see the file
/// comment for the method. Throws std::invalid_argument for x of the wrong size, bad options
/// (naming the option and its allowed range), bad fixed dofs (as FixedDofElimination) or a
/// non-finite Hessian; std::runtime_error if MUMPS fails.
Eigenpairs lowest_eigenpairs(SparseObjective& objective, const Eigen::Ref<const Eigen::VectorXd>& x,
                             const std::vector<Eigen::Index>& fixed_dofs,
                             const EigenpairOptions& options = {});

/// The same for a given symmetric matrix, passed as its upper triangle (square, column-major,
/// entries with row <= column only). Diagonal entries missing from the pattern are zeros.
Eigenpairs lowest_eigenpairs_of_matrix(const Eigen::SparseMatrix<double>& upper,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const EigenpairOptions& options = {});

}  // namespace growshell
