#pragma once
// The group of the mirrors x -> -x and y -> -y of a point set (the two-fold cone's symmetry),
// each found to 1e-9.

#include <Eigen/Core>

#include "libshell/mesh/vertex_symmetry.hpp"
#include "solvers/stability/vertex_symmetry_group.hpp"

namespace growshell::test_support {

inline VertexSymmetryGroup two_mirrors(const Eigen::MatrixX3d& P) {
  return VertexSymmetryGroup(P.rows(), {mirror_symmetry(P, 0, 1e-9), mirror_symmetry(P, 1, 1e-9)});
}

}  // namespace growshell::test_support
