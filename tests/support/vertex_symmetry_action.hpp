#pragma once
// A vertex symmetry acting on a vertex-major state: (T_g x)_{image[v]} = S_g x_v, the action
// the library's symmetry groups and classes are defined by (solvers/stability/
// vertex_symmetry_group.hpp), written out for tests to check against.

#include <Eigen/Core>

#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell::test_support {

inline Eigen::VectorXd apply(const VertexSymmetry& g, const Eigen::VectorXd& x) {
  Eigen::VectorXd out(x.size());
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    out.segment<3>(3 * g.image[static_cast<std::size_t>(v)]) =
        g.signs.cwiseProduct(x.segment<3>(3 * v));
  return out;
}

}  // namespace growshell::test_support
