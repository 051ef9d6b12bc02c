#include "libshell/mesh/disc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>
#include <string>

#include "libshell/mesh/hexagon_disc_map.hpp"
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

// First vertex index of ring k of the hexagonal ring lattice (ring 0 = centre vertex).
long ring_start(int k) { return k == 0 ? 0 : 1 + 3L * k * (k - 1); }

// Triangles of the hexagonal ring lattice with rings 0..last.
Eigen::MatrixX3i ring_lattice_faces(int last) {
  auto vertex = [](int k, int m) {
    if (k == 0) return 0;
    return static_cast<int>(ring_start(k) + ((m % (6 * k)) + 6 * k) % (6 * k));
  };
  Eigen::MatrixX3i faces(6L * last * last, 3);
  long f = 0;
  // Between rings k-1 and k each of the six sides s holds k triangles pointing outwards and
  // k-1 pointing inwards; this is exactly the triangular lattice, so every vertex strictly
  // inside has valence 6.
  for (int k = 1; k <= last; ++k) {
    for (int s = 0; s < 6; ++s) {
      for (int j = 0; j < k; ++j) {
        const int inner = vertex(k - 1, s * (k - 1) + j);
        faces.row(f++) << inner, vertex(k, s * k + j), vertex(k, s * k + j + 1);
        if (j + 1 < k) {
          faces.row(f++) << inner, vertex(k, s * k + j + 1), vertex(k - 1, s * (k - 1) + j + 1);
        }
      }
    }
  }
  return faces;
}

// Lattice hexagon -> unit disc of make_disc_mesh's conformal layout: w for every lattice
// vertex of rings 0..N+1, in the numbering of ring_lattice_faces.
std::vector<std::complex<double>> conformal_disc_points(int N) {
  using Complex = std::complex<double>;
  std::vector<Complex> w(ring_start(N + 2));
  w[0] = 0.0;
  const Complex c1 = std::polar(1.0, std::numbers::pi / 3.0);
  // Only side 0 is mapped; the other sides are its rotations, which makes the mesh exactly
  // (to rounding) symmetric and costs a sixth of the map evaluations.
  std::vector<Complex> side(N + 2);
  for (int k = 1; k <= N + 1; ++k) {
    for (int j = 0; j < k; ++j) {
      const Complex xi = static_cast<double>(k) + static_cast<double>(j) * (c1 - 1.0);
      Complex g = hexagon_to_disc(xi / static_cast<double>(N));
      // The side maps onto the unit circle; remove the map's last-digit error there.
      if (k == N) g /= std::abs(g);
      side[j] = g;
    }
    if (k == N + 1) {
      // At a rim corner the map opens the 120-degree hexagon angle to 180 degrees
      // (g ~ 1 - (1 - z)^(3/2)), so its continuation wraps the 240 degrees outside the
      // corner onto a full turn: the ghost corner lands on the circle's tangent and both
      // ghost neighbours of the ghost corner on the same point 1 / conj(g((N-1)/N)), which
      // makes the ghost faces at the corner degenerate. These ghost vertices instead continue
      // a lattice line through ring N linearly: ghost = 2 (ring N vertex) - (ring N-1 vertex)
      // along the lattice direction 1 (ghost corner, ghost j = 1) or c1 (ghost j = N, next
      // to the ghost corner c1 (N + 1): the mirror image of side 1's ghost j = 1).
      auto g = [&](Complex lattice) { return hexagon_to_disc(lattice / static_cast<double>(N)); };
      const double n = N;
      side[0] = 2.0 - w[ring_start(N - 1)];
      side[1] = 2.0 * g(n - 1.0 + c1) - g(n - 2.0 + c1);
      side[N] = 2.0 * g(1.0 + (n - 1.0) * c1) - g(1.0 + (n - 2.0) * c1);
    }
    for (int s = 0; s < 6; ++s) {
      const Complex rot = s == 0 ? Complex(1.0) : std::polar(1.0, s * std::numbers::pi / 3.0);
      for (int j = 0; j < k; ++j) w[ring_start(k) + s * k + j] = rot * side[j];
    }
  }
  return w;
}

}  // namespace

TriangleMesh make_disc_mesh(const DiscMeshOptions& options) {
  const double R = options.radius;
  const int N = options.rings;
  const double p = options.grading_exponent;
  if (!(std::isfinite(R) && R > 0.0)) bad_option("disc radius", R, "finite and > 0");
  if (N < 2) bad_option("disc rings", N, ">= 2");
  if (N > 10000) bad_option("disc rings", N, "<= 10000");
  if (!(std::isfinite(p) && p >= 1.0)) bad_option("disc grading_exponent", p, "finite and >= 1");
  if (!(std::isfinite(options.min_spacing) && options.min_spacing >= 0.0)) {
    bad_option("disc min_spacing", options.min_spacing, "finite and >= 0");
  }
  check_center("disc", options.center);

  const double a = p == 1.0 ? 1.0 : std::clamp(options.min_spacing * N / R, 0.0, 1.0);
  auto sigma = [&](double rho) { return a * rho + (1.0 - a) * std::pow(rho, p); };
  TriangleMesh mesh;
  mesh.vertices.resize(ring_start(N + 2), 3);
  const Eigen::Vector2d& c = options.center;
  if (options.layout == DiscLayout::Conformal) {
    const std::vector<std::complex<double>> w = conformal_disc_points(N);
    for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
      const double rho = std::abs(w[v]);
      // sigma(1) = 1 up to rounding; ring N must stay exactly on the circle.
      const double factor = rho == 0.0 ? 0.0 : (rho == 1.0 ? 1.0 : sigma(rho) / rho);
      mesh.vertices.row(v) << c.x() + R * factor * w[v].real(), c.y() + R * factor * w[v].imag(),
          0.0;
    }
  } else {
    std::vector<double> radii(N + 2);
    for (int k = 0; k <= N; ++k) radii[k] = R * sigma(static_cast<double>(k) / N);
    radii[N] = R;  // exact, whatever the rounding of the formula
    radii[N + 1] = R + (radii[N] - radii[N - 1]);
    mesh.vertices.row(0) << c.x(), c.y(), 0.0;
    for (int k = 1; k <= N + 1; ++k) {
      for (int m = 0; m < 6 * k; ++m) {
        const double angle = 2.0 * std::numbers::pi * m / (6 * k);
        mesh.vertices.row(ring_start(k) + m) << c.x() + radii[k] * std::cos(angle),
            c.y() + radii[k] * std::sin(angle), 0.0;
      }
    }
  }
  mesh.faces = ring_lattice_faces(N + 1);
  return mesh;
}

int annulus_vertices_per_ring(const AnnulusMeshOptions& options) {
  const double Ri = options.inner_radius;
  const double R = options.outer_radius;
  if (!(std::isfinite(Ri) && Ri > 0.0)) {
    bad_option("annulus inner_radius", Ri, "finite and in (0, outer_radius)");
  }
  if (!(std::isfinite(R) && R > Ri)) {
    bad_option("annulus outer_radius", R, "finite and > inner_radius");
  }
  if (options.radial_layers < 1) bad_option("annulus radial_layers", options.radial_layers, ">= 1");
  const double dl = std::log(R / Ri) / options.radial_layers;
  const double m = std::round(2.0 * std::numbers::pi / dl);
  if (!(m <= 1e6)) {
    bad_option("annulus radial_layers / ln(outer_radius / inner_radius)", 1.0 / dl,
               "small enough that a ring needs at most 1e6 vertices (2 pi / step <= 1e6)");
  }
  return std::max(6, static_cast<int>(m));
}

TriangleMesh make_annulus_mesh(const AnnulusMeshOptions& options) {
  const int M = annulus_vertices_per_ring(options);
  check_center("annulus", options.center);
  const double Ri = options.inner_radius;
  const double R = options.outer_radius;
  const int L = options.radial_layers;
  const double dl = std::log(R / Ri) / L;
  auto index = [&](int j, int i) { return (j + 1) * M + (i % M); };
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(M) * (L + 3), 3);
  for (int j = -1; j <= L + 1; ++j) {
    // Rings 0 and L exactly at R_i and R, whatever the rounding of exp.
    const double r = j == 0 ? Ri : (j == L ? R : Ri * std::exp(j * dl));
    for (int i = 0; i < M; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / M;
      mesh.vertices.row(index(j, i)) << options.center.x() + r * std::cos(angle),
          options.center.y() + r * std::sin(angle), 0.0;
    }
  }
  // (log r, angle) -> plane is conformal and orientation preserving, so triangles
  // counter-clockwise in the (j, i) grid stay counter-clockwise.
  mesh.faces.resize(2 * static_cast<Eigen::Index>(M) * (L + 2), 3);
  Eigen::Index f = 0;
  for (int j = -1; j <= L; ++j) {
    for (int i = 0; i < M; ++i) {
      mesh.faces.row(f++) << index(j, i), index(j + 1, i), index(j + 1, i + 1);
      mesh.faces.row(f++) << index(j, i), index(j + 1, i + 1), index(j, i + 1);
    }
  }
  return mesh;
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
