#pragma once
/// \file
/// The lowest eigenpairs of the generalised problem H v = lambda M v with a diagonal (lumped)
/// mass M: eigenvalues that are a property of the continuum, not of the mesh.
///
/// The eigenvalues of H alone are Rayleigh quotients v^T H v / v^T v over the Euclidean norm of
/// the control vector, which counts every control point alike: refining the mesh adds points,
/// so they fall like 1 / (number of unknowns) for the same deformation. With M the lumped
/// reference area of every control point (ReferenceQuadrature::vertex_areas, repeated for its
/// three coordinates), v^T M v approximates the integral of |dx|^2 over the reference sheet, and
/// lambda = d2E / integral |dx|^2 dA (N/m^3 for an energy in J and positions in m) converges
/// under refinement. It is what the h -> 0 cone's eigenvalues are compared with.
///
/// Method: with D = M^(-1/2), the eigenpairs (lambda, w) of D H D (lowest_eigenpairs_of_matrix,
/// shift-and-invert with an inertia check) give v = D w; Sylvester's law of inertia holds for
/// the congruent D H D, so the count of negative eigenvalues is H's.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/sparse_objective.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace growshell {

/// The options.count eigenpairs of H v = lambda M v nearest options.shift (the lowest when it
/// is NaN), M = diag(dof_mass), with the dofs `fixed_dofs` removed; `upper` is H's upper
/// triangle. values: the generalised eigenvalues (units of H per unit mass); vectors:
/// M-orthonormal (v_k^T M v_l = delta_kl), zero at the fixed dofs; residuals: those of the
/// scaled problem D H D, relative to its norm. Throws std::invalid_argument if dof_mass has the
/// wrong size or a free dof's mass is not finite and > 0, and as lowest_eigenpairs_of_matrix.
Eigenpairs lowest_mass_normalized_eigenpairs_of_matrix(const Eigen::SparseMatrix<double>& upper,
                                                       const Eigen::VectorXd& dof_mass,
                                                       const std::vector<Eigen::Index>& fixed_dofs,
                                                       const EigenpairOptions& options = {});

/// The same for the Hessian of `objective` at x.
Eigenpairs lowest_mass_normalized_eigenpairs(SparseObjective& objective,
                                             const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Eigen::VectorXd& dof_mass,
                                             const std::vector<Eigen::Index>& fixed_dofs,
                                             const EigenpairOptions& options = {});

}  // namespace growshell
