#pragma once
// A vertex-major state (x, y, z of vertex 0, then of vertex 1, ...) as one row per vertex.

#include <Eigen/Core>

namespace growshell::test_support {

inline Eigen::MatrixX3d vertex_rows(const Eigen::VectorXd& x) {
  Eigen::MatrixX3d p(x.size() / 3, 3);
  for (Eigen::Index v = 0; v < p.rows(); ++v) p.row(v) = x.segment<3>(3 * v).transpose();
  return p;
}

}  // namespace growshell::test_support
