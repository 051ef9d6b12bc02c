#pragma once
/// \file
/// Core radius of an e-cone: the size of the region about the apex where the sheet stretches.
/// For h -> 0 the cone is unstretched except at its apex; with finite thickness the apex
/// flattens into a core of radius R_c ∝ h that carries the stretching energy.

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// Result of stretching_core_radius (metres, reference radii about the given centre).
struct CoreRadius {
  /// Reference radius r such that the elements whose reference centroid lies within r hold
  /// the requested fraction of the stretching energy (linear interpolation of the cumulative
  /// stretching energy between consecutive element radii).
  double radius = 0.0;
  /// Total stretching energy of the sheet (J).
  double stretching_energy = 0.0;
};

/// Distance (metres, in the reference plane: x and y only) of element e's reference centroid
/// (the mean of its three corner control points) from `center`. 0 <= e < num_elements(), not
/// range-checked.
double element_reference_radius(const ShellModel& model, Eigen::Index e, const Eigen::Vector3d& center);

/// R_c of the state x (control points, vertex-major like ShellModel, metres) at the excess
/// angle phi_e (radians): the radius about `center` (reference plane; only its x and y count)
/// that encloses `fraction` of the stretching energy, element by element. Definition chosen
/// because it needs no threshold on a density: for a flat disc relaxed under uniform
/// circumferential growth (a wedge disclination in linear elasticity) the enclosed fraction
/// is F(rho) = rho^2 (1 + 2 (1 - nu) ln^2 rho), rho = r / R (median 0.6105 R for nu = 0.3); for
/// an e-cone nearly all stretching sits in the core, and R_c(fraction 0.5) ∝ h
/// (docs/validation.md). Resolution: an element's energy is placed at its reference centroid,
/// so the result carries an error of about half an element size at R_c.
/// Throws std::invalid_argument naming the argument if fraction is not in (0, 1), x does
/// not have model.dimension() entries, or the stretching energy is zero (no core to measure).
CoreRadius stretching_core_radius(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                  double excess_angle, double fraction = 0.5,
                                  const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

}  // namespace growshell
