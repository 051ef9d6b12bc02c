#pragma once
/// \file
/// The conformal map from the regular hexagon onto the unit disc.
///
/// Why: a hexagonal lattice (all interior valences 6) whose hexagonal rings are placed on
/// circles is only piecewise smooth (kinks along the six spokes through the corners), and a
/// Loop surface over such a lattice has O(1) curvature errors along those spokes. The
/// conformal map is analytic inside the hexagon, so the lattice it carries onto the disc is
/// smooth everywhere except at the six rim corners, and curvature errors fall as O(l^2).

#include <complex>

namespace growshell {

/// Maps z in the regular hexagon with corners exp(i k pi / 3), k = 0..5 (circumradius 1),
/// conformally onto the unit disc, with g(0) = 0, g(corner_k) = corner_k and g(conj z) =
/// conj g(z). Points just outside a side (up to one lattice layer) are mapped by Schwarz
/// reflection across that side, which continues the map analytically. Accuracy ~1e-12 away
/// from the corners; the map inverts the Schwarz-Christoffel map
///   f(w) = C int_0^w (1 - t^6)^(-1/3) dt   by Newton's method.
std::complex<double> hexagon_to_disc(std::complex<double> z);

/// The Schwarz-Christoffel map f from the unit disc onto the hexagon (inverse of the above).
std::complex<double> disc_to_hexagon(std::complex<double> w);

}  // namespace growshell
