#pragma once
/// \file
/// dE/dphi_e of a shell's elastic energy at a fixed state: along a branch of equilibria (with or
/// without contact constraints, which do not depend on phi_e) it is the derivative of the energy
/// along the branch, which branch_crossing.hpp interpolates with.

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// partial (E_stretch + E_bend) / partial phi_e at state x and excess angle phi (J per radian),
/// by central differences of half-width delta (radians, > 0): the truncation error is
/// delta^2 E''' / 6, about 1e-9 E, and the round-off eps E / delta about 1e-12 E for
/// delta = 1e-4.
double elastic_energy_slope(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                            double phi, double delta = 1e-4);

}  // namespace growshell
