#pragma once
/// \file
/// Isotropic linear-elastic material of a Kirchhoff-Love shell.

namespace growshell {

/// Young's modulus Y (Pa) and Poisson ratio nu of an isotropic sheet.
struct Material {
  double youngs_modulus = 1e4;
  double poisson_ratio = 0.3;
};

/// Throws std::invalid_argument naming the field unless Y > 0 is finite and -1 < nu < 0.5.
void validate_material(const Material& material);

/// Stretching modulus Y h / (2 (1 - nu^2)) (N/m) for thickness h (m): the factor of U_s.
double stretching_modulus(const Material& material, double thickness);

/// Bending modulus Y h^3 / (24 (1 - nu^2)) (N m) for thickness h (m): the factor of U_b.
double bending_modulus(const Material& material, double thickness);

}  // namespace growshell
