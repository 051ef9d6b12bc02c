#pragma once
/// \file
/// Isotropic elastic material of a Kirchhoff-Love shell: moduli and the law of its stretching
/// energy. Both laws share the small-strain limit nu (tr eps)^2 + (1 - nu) tr(eps^2); they
/// differ at finite strain (docs/shell_energy.md, "Stretching law").

namespace growshell {

/// Stretching energy density as a function of the mixed metric tensor M = abar^-1 a.
enum class StretchingLaw {
  /// Quadratic in the Green strain eps = (M - I)/2 (Saint Venant-Kirchhoff, the form of
  /// ../shared/docs/physics.md). Loses ellipticity under large compression (below a stretch
  /// of about 0.65 at nu = 0.3, with the other stretch 1).
  kSaintVenantKirchhoff,
  /// Compressible neo-Hookean membrane, (1 - nu)/2 (tr M - 2 - ln det M) + nu/4 (ln det M)^2:
  /// the same moduli at small strain, elliptic under any compression, infinite energy as
  /// det M -> 0.
  kNeoHookean,
};

/// Young's modulus Y (Pa), Poisson ratio nu and stretching law of an isotropic sheet (the
/// default law is physics.md's).
struct Material {
  double youngs_modulus = 1e4;
  double poisson_ratio = 0.3;
  StretchingLaw stretching_law = StretchingLaw::kSaintVenantKirchhoff;
};

/// Throws std::invalid_argument naming the field unless Y > 0 is finite and -1 < nu < 0.5.
void validate_material(const Material& material);

/// Stretching modulus Y h / (2 (1 - nu^2)) (N/m) for thickness h (m): the factor of U_s.
double stretching_modulus(const Material& material, double thickness);

/// Bending modulus Y h^3 / (24 (1 - nu^2)) (N m) for thickness h (m): the factor of U_b.
double bending_modulus(const Material& material, double thickness);

}  // namespace growshell
