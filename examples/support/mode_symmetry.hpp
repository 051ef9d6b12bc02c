#pragma once
// The symmetry of an eigenmode of a symmetric cone, for the programs that class modes
// (branch_eigenvalues, cone_mode_sectors): the reference mesh's mirrors of the folds and its S4
// as linear maps, a mode's parity under one of them, and where on the sheet the mode is largest.

#include <Eigen/Core>
#include <cstddef>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell::examples {

/// The mirror of the reference control points `positions` about x = 0 (axis 0) or y = 0
/// (axis 1), as a linear map. Throws std::invalid_argument as mirror_symmetry when the mesh
/// lacks it.
inline LinearVertexSymmetry reference_mirror(const Eigen::MatrixX3d& positions, int axis) {
  const VertexSymmetry mirror =
      mirror_symmetry(positions, axis, 1e-9 * positions.cwiseAbs().maxCoeff());
  LinearVertexSymmetry linear;
  linear.image = mirror.image;
  linear.matrix = mirror.signs.asDiagonal();
  return linear;
}

/// S4 of the reference control points: the quarter turn about z followed by z -> -z. The flat
/// reference maps as the turn alone, so the vertex map is the turn's. Throws
/// std::invalid_argument as quarter_turn_symmetry when the mesh lacks the quarter turn.
inline LinearVertexSymmetry reference_s4(const Eigen::MatrixX3d& positions) {
  LinearVertexSymmetry s4 = quarter_turn_symmetry(positions, 1e-9 * positions.cwiseAbs().maxCoeff());
  s4.matrix.row(2) *= -1.0;
  return s4;
}

/// <v, T v>_M / <v, v>_M for the displacement field v (3 per control point) and the field T v
/// that has S v_i at S p_i (S the symmetry's matrix), with the lumped masses m of the control
/// points, which the symmetry maps onto each other: +1 for a symmetric mode, -1 for an
/// antisymmetric one.
inline double mode_parity(const Eigen::VectorXd& v, const Eigen::VectorXd& m,
                          const LinearVertexSymmetry& symmetry) {
  double overlap = 0.0, norm = 0.0;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const auto image = static_cast<Eigen::Index>(symmetry.image[static_cast<std::size_t>(i)]);
    overlap += m(i) * v.segment<3>(3 * image).dot(symmetry.matrix * v.segment<3>(3 * i));
    norm += m(i) * v.segment<3>(3 * i).squaredNorm();
  }
  return overlap / norm;
}

/// The reference radius (m, from the growth centre) of the sheet vertex where the mode v is
/// largest: at the apex core or out at the folds.
inline double mode_peak_radius(const ShellModel& model, const Eigen::VectorXd& v) {
  const Eigen::VectorXd& X = model.reference_positions();
  double peak = 0.0, radius = 0.0;
  for (const int vertex : model.sheet_vertices()) {
    const double a = v.segment<3>(3 * vertex).norm();
    if (a > peak) {
      peak = a;
      radius = (X.segment<2>(3 * vertex) - model.settings().growth.center.head<2>()).norm();
    }
  }
  return radius;
}

}  // namespace growshell::examples
