#pragma once
/// \file
/// The limit surface of a shell state as a triangle surface with energy densities, for
/// viewing (write it with write_vtu).

#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/vtk_writer.hpp"

namespace growshell {

/// Samples the limit surface of state x at the excess angle phi_e (radians; the energy
/// densities are the state's at that growth, so pass the state's own). With `refinement` = 1
/// the points are the limit positions of the element corners (shared between elements); with r > 1 each element is
/// evaluated on an r x r sub-triangulation (points not shared). Cell data: "bending_density"
/// U_b (1/m^2), "stretching_density" U_s (1), "element" (index), each constant per element.
SurfaceSnapshot shell_snapshot(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                               double excess_angle, int refinement);

}  // namespace growshell
