#pragma once
/// \file
/// Whether a stationary point is a strict local minimum: a Cholesky test of the Hessian.

#include <Eigen/Core>
#include <vector>

#include "core/sparse_objective.hpp"

namespace growshell {

/// True when the Hessian of `objective` at x, with `fixed_dofs` held fixed (e.g. the pinned
/// rigid-body dofs), is positive definite, i.e. an unshifted sparse Cholesky factorisation
/// succeeds. At a converged Newton point this separates stable equilibria from saddles,
/// which a Newton iteration started on a symmetric state can converge to. Curvatures above
/// -zero_tolerance * mean|diagonal| count as zero (see NewtonOptions::shift_initial_factor):
/// the factorisation is of H + zero_tolerance * mean|diagonal| * I.
bool hessian_is_positive_definite(SparseObjective& objective,
                                  const Eigen::Ref<const Eigen::VectorXd>& x,
                                  const std::vector<Eigen::Index>& fixed_dofs,
                                  double zero_tolerance = 1e-10);

}  // namespace growshell
