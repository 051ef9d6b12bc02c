#pragma once
// A disc whose centre vertex has any valence n: n lattice wedges of the triangular lattice glued
// round it (n = 6 is the hexagonal disc). Every other interior vertex has valence 6, so each
// element next to the centre has exactly one extraordinary corner.

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <numbers>

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell::test_support {

/// Index of vertex j (0 <= j < k, or j = k for the next sector's first) of sector s on ring k.
inline int polygon_disc_vertex(int n, int k, int s, int j) {
  if (k == 0) return 0;
  const int m = (s * k + j) % (n * k);
  return 1 + n * k * (k - 1) / 2 + m;
}

/// The disc with `rings` rings round a centre of valence `n`; the outermost ring is the ghost
/// layer. The lattice point z = (k - j) e1 + j e2 of wedge s (e1 = 1, e2 = e^{i pi / 3}) goes to
/// spacing |z| e^{i (2 pi s / n + (6 / n) arg z)}: polar coordinates (r, theta) -> (r, 6 theta / n),
/// smooth away from the centre.
inline TriangleMesh polygon_disc(int n, int rings, double spacing = 1.0) {
  TriangleMesh mesh;
  const int num_vertices = 1 + n * rings * (rings + 1) / 2;
  mesh.vertices = Eigen::MatrixX3d::Zero(num_vertices, 3);
  const std::complex<double> e1(1.0, 0.0), e2 = std::polar(1.0, std::numbers::pi / 3.0);
  for (int k = 1; k <= rings; ++k)
    for (int s = 0; s < n; ++s)
      for (int j = 0; j < k; ++j) {
        const std::complex<double> z = static_cast<double>(k - j) * e1 + static_cast<double>(j) * e2;
        const double r = std::abs(z), angle = std::arg(z) * 6.0 / n + 2.0 * std::numbers::pi * s / n;
        const std::complex<double> p = std::polar(spacing * r, angle);
        mesh.vertices.row(polygon_disc_vertex(n, k, s, j)) << p.real(), p.imag(), 0.0;
      }
  mesh.faces.resize(n * rings * rings, 3);
  int f = 0;
  for (int k = 1; k <= rings; ++k)
    for (int s = 0; s < n; ++s)
      for (int j = 0; j < k; ++j) {
        const int inner = polygon_disc_vertex(n, k - 1, s, j);
        mesh.faces.row(f++) << inner, polygon_disc_vertex(n, k, s, j), polygon_disc_vertex(n, k, s, j + 1);
        if (j + 1 < k)
          mesh.faces.row(f++) << inner, polygon_disc_vertex(n, k, s, j + 1),
              polygon_disc_vertex(n, k - 1, s, j + 1);
      }
  mesh.faces.conservativeResize(f, 3);
  return mesh;
}

}  // namespace growshell::test_support
