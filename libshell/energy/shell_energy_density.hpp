#pragma once
/// \file
/// Kirchhoff-Love energy density with growth at one quadrature point, with its exact gradient
/// and Hessian with respect to the surface jet. Derivation: docs/shell_energy.md.
///
/// Chain: control points --(linear, basis)--> surface jet s --> fundamental forms (a, b)
///        --> strains (eps = 1/2 abar^-1 (a - abar), kappa = abar^-1 b) --> energy density.
/// This file does the last three arrows; the assembly does the first.
///
/// Surface-jet order (15 entries, 5 blocks of xyz): a_1, a_2, a_11, a_22, a_12, where
/// a_a = dx/dtheta^a and a_ab = d2x/dtheta^a dtheta^b of the current limit surface.

#include <Eigen/Core>

#include "libshell/energy/material.hpp"

namespace growshell {

/// Derivatives of the current surface position at one parameter point (metres).
struct SurfaceJet {
  Eigen::Vector3d a1, a2, a11, a22, a12;
};

/// Index of the first entry of each block in the 15-vector surface jet.
enum SurfaceJetBlock : int { kJetA1 = 0, kJetA2 = 3, kJetA11 = 6, kJetA22 = 9, kJetA12 = 12 };

using JetVector = Eigen::Matrix<double, 15, 1>;
using JetMatrix = Eigen::Matrix<double, 15, 15>;

/// Rest data of one quadrature point. `target_metric` abar is covariant in the parameter
/// basis (m^2); `weight` is the quadrature weight in the parameter triangle (area 1/2), so the
/// point contributes weight * sqrt(det abar) of grown reference area; thickness in metres.
struct ShellPointRest {
  Eigen::Matrix2d target_metric;
  double weight;
  double thickness;
};

/// Energy (J) contributed by one quadrature point, split into its two parts.
struct ShellPointEnergy {
  double stretching = 0.0;
  double bending = 0.0;
  /// Integral weight of U_b alone: U_b * weight * sqrt(det abar) (dimensionless, for E_b-hat).
  double bending_density_integral = 0.0;
  /// Current area weight * sqrt(det a) (m^2).
  double current_area = 0.0;
  double total() const { return stretching + bending; }
};

/// Energy of one quadrature point. Returns NaN parts for a degenerate surface (a_1 x a_2 = 0).
ShellPointEnergy shell_point_energy(const SurfaceJet& jet, const ShellPointRest& rest,
                                    const Material& material);

/// Energy (J, returned) and its gradient with respect to the surface jet (written to gradient).
double shell_point_gradient(const SurfaceJet& jet, const ShellPointRest& rest,
                            const Material& material, JetVector& gradient);

/// Energy (returned), gradient and Hessian with respect to the surface jet.
double shell_point_hessian(const SurfaceJet& jet, const ShellPointRest& rest,
                           const Material& material, JetVector& gradient, JetMatrix& hessian);

/// d(gradient)/dp for a parameter p on which only the target metric depends, given
/// d(abar)/dp. Used with p = phi_e for continuation.
JetVector shell_point_gradient_parameter_derivative(const SurfaceJet& jet,
                                                    const ShellPointRest& rest,
                                                    const Material& material,
                                                    const Eigen::Matrix2d& target_metric_derivative);

}  // namespace growshell
