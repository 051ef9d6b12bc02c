#pragma once
// A thickness given on a planar sheet triangulation, per vertex (linear on each triangle) or
// per face (constant on each), as the ThicknessField the shell model samples at reference
// points: the Python package's model_from_arrays takes thickness this way.

#include <Eigen/Core>

#include "libshell/assembly/reference_quadrature.hpp"

namespace growshell {

/// The field of `values` on the sheet (`vertices` V x 3 with z = 0, `faces` F x 3): per face
/// (F values) if `per_face`, else per vertex (V values). A point is located in the triangle that contains it
/// (barycentric coordinates all >= -1e-9) or, outside every triangle (the
/// limit surface of a boundary element reaches a little beyond its control triangle's
/// neighbours), in the triangle it lies least outside of, with its barycentric coordinates
/// clamped. Throws std::invalid_argument naming a wrong size or a value that is not finite and
/// > 0.
ThicknessField sheet_thickness_field(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                     const Eigen::VectorXd& values, bool per_face);

}  // namespace growshell
