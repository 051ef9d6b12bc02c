#pragma once
/// \file
/// The principal elastic stretches of a state: at every quadrature point, the square roots of
/// the eigenvalues of abar^-1 a (a the current metric, abar the grown target metric). They
/// tell where the sheet is strained beyond small strain, e.g. at a cone's apex, and so where
/// the two stretching laws (libshell/energy/material.hpp) differ.

#include <Eigen/Core>
#include <vector>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// The stretches at one quadrature point.
struct PointStretches {
  double radius = 0.0;  ///< reference distance from the growth centre (m; x and y only)
  double smaller = 0.0;  ///< smaller principal elastic stretch (1)
  double larger = 0.0;   ///< larger principal elastic stretch (1)
};

/// The principal elastic stretches of the state x (control points, vertex-major like
/// ShellModel, metres) at excess angle `excess_angle`, at every quadrature point whose
/// reference distance from the growth centre is at most `max_radius` (m), in the model's
/// point order (element-major). Throws std::invalid_argument if x does not have
/// model.dimension() entries or max_radius is negative or not a number; a degenerate current
/// metric gives a zero stretch.
std::vector<PointStretches> elastic_stretches(const ShellModel& model,
                                              const Eigen::Ref<const Eigen::VectorXd>& x,
                                              double excess_angle, double max_radius);

}  // namespace growshell
