#include "libshell/mesh/disc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "libshell/mesh/mesh_error.hpp"

namespace growshell {

namespace {

[[noreturn]] void bad_option(const std::string& name, double value, const std::string& range) {
  std::ostringstream msg;
  msg << name << " = " << value << " is invalid; it must be " << range;
  throw MeshError(msg.str());
}

void check_center(const std::string& generator, const Eigen::Vector2d& center) {
  if (!center.allFinite()) {
    throw MeshError(generator + " center must be finite");
  }
}

// First vertex index of ring k of the full hexagonal ring lattice (ring 0 = centre vertex).
long ring_start(int k) { return k == 0 ? 0 : 1 + 3L * k * (k - 1); }

// Builds rings first..last of the hexagonal ring lattice, ring k at radius radii[k - first]
// (vertex m at angle 2 pi m / 6k), with the triangles between consecutive rings.
TriangleMesh ring_lattice(int first, int last, const std::vector<double>& radii,
                          const Eigen::Vector2d& center) {
  const long base = ring_start(first);
  const long nv = ring_start(last + 1) - base;
  TriangleMesh mesh;
  mesh.vertices.resize(nv, 3);
  for (int k = first; k <= last; ++k) {
    const double r = radii[k - first];
    const int count = k == 0 ? 1 : 6 * k;
    for (int m = 0; m < count; ++m) {
      const double angle = k == 0 ? 0.0 : 2.0 * std::numbers::pi * m / count;
      const long v = ring_start(k) - base + m;
      mesh.vertices.row(v) << center.x() + r * std::cos(angle), center.y() + r * std::sin(angle),
          0.0;
    }
  }
  auto vertex = [&](int k, int m) {
    if (k == 0) return static_cast<int>(-base);
    return static_cast<int>(ring_start(k) - base + ((m % (6 * k)) + 6 * k) % (6 * k));
  };
  long nf = 0;
  for (int k = first + 1; k <= last; ++k) nf += 6L * (2 * k - 1);
  mesh.faces.resize(nf, 3);
  long f = 0;
  // Between rings k-1 and k each of the six sides s holds k triangles pointing outwards and
  // k-1 pointing inwards; this is exactly the triangular lattice, so every vertex strictly
  // inside has valence 6.
  for (int k = first + 1; k <= last; ++k) {
    for (int s = 0; s < 6; ++s) {
      for (int j = 0; j < k; ++j) {
        const int inner = vertex(k - 1, s * (k - 1) + j);
        mesh.faces.row(f++) << inner, vertex(k, s * k + j), vertex(k, s * k + j + 1);
        if (j + 1 < k) {
          mesh.faces.row(f++) << inner, vertex(k, s * k + j + 1),
              vertex(k - 1, s * (k - 1) + j + 1);
        }
      }
    }
  }
  return mesh;
}

}  // namespace

TriangleMesh make_disc_mesh(const DiscMeshOptions& options) {
  const double R = options.radius;
  const int N = options.rings;
  const double p = options.grading_exponent;
  if (!(std::isfinite(R) && R > 0.0)) bad_option("disc radius", R, "finite and > 0");
  if (N < 2) bad_option("disc rings", N, ">= 2");
  if (!(std::isfinite(p) && p >= 1.0)) bad_option("disc grading_exponent", p, "finite and >= 1");
  if (!(std::isfinite(options.min_spacing) && options.min_spacing >= 0.0)) {
    bad_option("disc min_spacing", options.min_spacing, "finite and >= 0");
  }
  check_center("disc", options.center);

  const double a = p == 1.0 ? 1.0 : std::clamp(options.min_spacing * N / R, 0.0, 1.0);
  std::vector<double> radii(N + 2);
  for (int k = 0; k <= N; ++k) {
    const double s = static_cast<double>(k) / N;
    radii[k] = R * (a * s + (1.0 - a) * std::pow(s, p));
  }
  radii[N] = R;  // exact, whatever the rounding of the formula
  radii[N + 1] = R + (radii[N] - radii[N - 1]);
  return ring_lattice(0, N + 1, radii, options.center);
}

int annulus_first_ring(const AnnulusMeshOptions& options) {
  const double Ri = options.inner_radius;
  const double R = options.outer_radius;
  if (!(std::isfinite(Ri) && Ri > 0.0)) {
    bad_option("annulus inner_radius", Ri, "finite and in (0, outer_radius)");
  }
  if (!(std::isfinite(R) && R > Ri)) {
    bad_option("annulus outer_radius", R, "finite and > inner_radius");
  }
  if (options.radial_layers < 1) bad_option("annulus radial_layers", options.radial_layers, ">= 1");
  const double dr = (R - Ri) / options.radial_layers;
  // Tangential spacing 2 pi Ri / (6K) equals dr at K* = pi Ri / (3 dr); the closest of the two
  // integers around K* wins, comparing spacings rather than K.
  const double k_star = std::numbers::pi * Ri / (3.0 * dr);
  if (!(k_star < 1e6)) {
    bad_option("annulus inner_radius / radial spacing", Ri / dr,
               "small enough that the inner ring needs fewer than 6e6 vertices");
  }
  const int lo = std::max(2, static_cast<int>(std::floor(k_star)));
  const int hi = std::max(2, lo + 1);
  auto mismatch = [&](int k) { return std::abs(2.0 * std::numbers::pi * Ri / (6.0 * k) - dr); };
  return mismatch(hi) < mismatch(lo) ? hi : lo;
}

TriangleMesh make_annulus_mesh(const AnnulusMeshOptions& options) {
  const int K = annulus_first_ring(options);
  check_center("annulus", options.center);
  const double Ri = options.inner_radius;
  const double R = options.outer_radius;
  const int L = options.radial_layers;
  const double dr = (R - Ri) / L;
  std::vector<double> radii(L + 3);
  radii[0] = Ri - dr > 0.0 ? Ri - dr : 0.5 * Ri;
  for (int i = 0; i <= L; ++i) radii[i + 1] = Ri + i * dr;
  radii[L + 1] = R;
  radii[L + 2] = R + dr;
  return ring_lattice(K - 1, K + L + 1, radii, options.center);
}

int strip_vertex_index(const StripMeshOptions& options, int i, int j) {
  if (i < -1 || i > options.cells_x + 1) {
    throw MeshError("strip column index i = " + std::to_string(i) + " is outside [-1, " +
                    std::to_string(options.cells_x + 1) + "]");
  }
  if (j < -1 || j > options.cells_y + 1) {
    throw MeshError("strip row index j = " + std::to_string(j) + " is outside [-1, " +
                    std::to_string(options.cells_y + 1) + "]");
  }
  return (i + 1) + (j + 1) * (options.cells_x + 3);
}

std::vector<int> strip_vertices_with_x_index(const StripMeshOptions& options, int i) {
  std::vector<int> column;
  for (int j = -1; j <= options.cells_y + 1; ++j)
    column.push_back(strip_vertex_index(options, i, j));
  return column;
}

TriangleMesh make_strip_mesh(const StripMeshOptions& options) {
  const double L = options.length;
  const double W = options.width;
  if (!(std::isfinite(L) && L > 0.0)) bad_option("strip length", L, "finite and > 0");
  if (!(std::isfinite(W) && W > 0.0)) bad_option("strip width", W, "finite and > 0");
  if (options.cells_x < 1) bad_option("strip cells_x", options.cells_x, ">= 1");
  if (options.cells_y < 1) bad_option("strip cells_y", options.cells_y, ">= 1");
  const int nx = options.cells_x;
  const int ny = options.cells_y;
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(nx + 3) * (ny + 3), 3);
  for (int j = -1; j <= ny + 1; ++j) {
    for (int i = -1; i <= nx + 1; ++i) {
      mesh.vertices.row(strip_vertex_index(options, i, j)) << i * L / nx, j * W / ny - 0.5 * W, 0.0;
    }
  }
  mesh.faces.resize(2 * static_cast<Eigen::Index>(nx + 2) * (ny + 2), 3);
  Eigen::Index f = 0;
  for (int j = -1; j <= ny; ++j) {
    for (int i = -1; i <= nx; ++i) {
      const int v00 = strip_vertex_index(options, i, j);
      const int v10 = strip_vertex_index(options, i + 1, j);
      const int v11 = strip_vertex_index(options, i + 1, j + 1);
      const int v01 = strip_vertex_index(options, i, j + 1);
      mesh.faces.row(f++) << v00, v10, v11;
      mesh.faces.row(f++) << v00, v11, v01;
    }
  }
  return mesh;
}

}  // namespace growshell
