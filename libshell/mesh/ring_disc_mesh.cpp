#include "libshell/mesh/ring_disc_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "libshell/mesh/ghost_layer.hpp"
#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/radial_size.hpp"

namespace growshell {

namespace {

// (cos, sin) of 2 pi m / D for D divisible by 8, evaluated in the first octant and carried to
// the others by exact reflections and quarter turns, so that the point set {m = 0..D-1} is
// mapped onto itself bit for bit by the symmetries of the square.
Eigen::Vector2d circle_point(long m, long D) {
  m = ((m % D) + D) % D;
  const long q = D / 4;
  const long quadrant = m / q;
  const long r = m % q;
  double c = 0.0;
  double s = 0.0;
  if (2 * r == q) {
    c = s = std::sqrt(0.5);
  } else if (2 * r < q) {
    const double a = 2.0 * std::numbers::pi * static_cast<double>(r) / static_cast<double>(D);
    c = std::cos(a);
    s = std::sin(a);
  } else {
    const double a = 2.0 * std::numbers::pi * static_cast<double>(q - r) / static_cast<double>(D);
    c = std::sin(a);
    s = std::cos(a);
  }
  for (long k = 0; k < quadrant; ++k) {
    const double t = c;
    c = -s;
    s = t;
  }
  return {c, s};
}

RadialSize size_of(const RingDiscMeshOptions& o) {
  return {o.size_slope, o.size_floor, o.size_max};
}

}  // namespace

RingDiscRings ring_disc_rings(const RingDiscMeshOptions& o) {
  const std::string caller = "make_ring_disc_mesh";
  if (!(std::isfinite(o.radius) && o.radius > 0.0))
    throw MeshError(caller + ": radius must be finite and > 0, got " + std::to_string(o.radius));
  const RadialSize size = size_of(o);
  check_radial_size(size, caller);
  if (o.center_valence != 4 && o.center_valence != 8 && o.center_valence != 12)
    throw MeshError(caller + ": center_valence must be 4, 8 or 12, got " +
                    std::to_string(o.center_valence));
  const bool annulus = o.inner_radius > 0.0;
  if (!(std::isfinite(o.inner_radius) && o.inner_radius >= 0.0 && o.inner_radius < o.radius))
    throw MeshError(caller + ": inner_radius must be finite, >= 0 and < radius, got " +
                    std::to_string(o.inner_radius));
  const double uR = radial_size_coordinate(size, o.radius);
  const double u0 = annulus ? radial_size_coordinate(size, o.inner_radius) : 0.0;
  if (!(uR - u0 <= 1e6))
    throw MeshError(caller + ": the size field gives " + std::to_string(uR - u0) +
                    " rings (more than 1e6); increase size_floor or size_slope");
  const int M = std::max(1, static_cast<int>(std::lround(uR - u0)));
  RingDiscRings out;
  out.radii.resize(static_cast<std::size_t>(M) + 1);
  out.counts.resize(out.radii.size());
  out.first_vertex.resize(out.radii.size());
  out.half_offset.resize(out.radii.size());
  out.radii[0] = o.inner_radius;
  out.counts[0] = 1;
  if (annulus) {
    // The inner rim's count: center_valence 2^k, the first whose spacing is at most sqrt 2 s.
    const double ideal =
        2.0 * std::numbers::pi * o.inner_radius / radial_size(size, o.inner_radius);
    out.counts[0] = o.center_valence;
    while (std::numbers::sqrt2 * out.counts[0] < ideal) out.counts[0] *= 2;
  }
  out.first_vertex[0] = 0;
  out.half_offset[0] = 0;
  long total = out.counts[0];
  for (int j = 1; j <= M; ++j) {
    const auto J = static_cast<std::size_t>(j);
    out.radii[J] =
        j == M ? o.radius
               : radius_at_size_coordinate(size, u0 + (uR - u0) * static_cast<double>(j) / M);
    if (j == 1 && !annulus) {
      out.counts[J] = o.center_valence;
      out.half_offset[J] = 0;
    } else {
      const double ideal = 2.0 * std::numbers::pi * out.radii[J] / radial_size(size, out.radii[J]);
      const bool doubled = ideal > std::numbers::sqrt2 * out.counts[J - 1];
      out.counts[J] = doubled ? 2 * out.counts[J - 1] : out.counts[J - 1];
      out.half_offset[J] = doubled ? 0 : !out.half_offset[J - 1];
    }
    out.first_vertex[J] = static_cast<int>(total);
    total += out.counts[J];
    if (total > 10'000'000)
      throw MeshError(caller +
                      ": the mesh would have more than 1e7 vertices; increase "
                      "size_floor, size_slope or size_max");
  }
  return out;
}

TriangleMesh make_ring_disc_sheet(const RingDiscMeshOptions& o) {
  const RingDiscRings rings = ring_disc_rings(o);
  const int M = static_cast<int>(rings.radii.size()) - 1;
  const int nv = rings.first_vertex[static_cast<std::size_t>(M)] + rings.counts.back();
  TriangleMesh mesh;
  const bool annulus = rings.radii[0] > 0.0;
  mesh.vertices.setZero(nv, 3);
  for (int j = annulus ? 0 : 1; j <= M; ++j) {
    const auto J = static_cast<std::size_t>(j);
    const long N = rings.counts[J];
    for (long i = 0; i < N; ++i) {
      const Eigen::Vector2d p = circle_point(2 * i + (rings.half_offset[J] ? 1 : 0), 2 * N);
      mesh.vertices.row(rings.first_vertex[J] + i) << rings.radii[J] * p.x(),
          rings.radii[J] * p.y(), 0.0;
    }
  }
  std::vector<Eigen::Vector3i> faces;
  const auto vertex = [&](int j, long i) {
    const long N = rings.counts[static_cast<std::size_t>(j)];
    return rings.first_vertex[static_cast<std::size_t>(j)] + static_cast<int>(((i % N) + N) % N);
  };
  if (!annulus)
    for (long i = 0; i < rings.counts[1]; ++i)
      faces.emplace_back(0, vertex(1, i), vertex(1, i + 1));
  for (int j = annulus ? 1 : 2; j <= M; ++j) {
    const auto J = static_cast<std::size_t>(j);
    const long N = rings.counts[J - 1];
    if (rings.counts[J] == N) {
      // Outer vertex between a_i and a_{i+1}: b_i if the inner ring is unshifted, else b_{i+1}.
      const long s = rings.half_offset[J - 1] ? 1 : 0;
      for (long i = 0; i < N; ++i) {
        faces.emplace_back(vertex(j - 1, i), vertex(j, i + s), vertex(j - 1, i + 1));
        faces.emplace_back(vertex(j - 1, i + 1), vertex(j, i + s), vertex(j, i + s + 1));
      }
    } else {
      // Doubling: a_i is aligned with b_{2i + t}, t = 1 for a shifted inner ring.
      const long t = rings.half_offset[J - 1] ? 1 : 0;
      for (long i = 0; i < N; ++i) {
        const long k = 2 * i + t;
        faces.emplace_back(vertex(j - 1, i), vertex(j, k), vertex(j, k + 1));
        faces.emplace_back(vertex(j - 1, i), vertex(j, k + 1), vertex(j - 1, i + 1));
        faces.emplace_back(vertex(j - 1, i + 1), vertex(j, k + 1), vertex(j, k + 2));
      }
    }
  }
  mesh.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    mesh.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return mesh;
}

TriangleMesh make_ring_disc_mesh(const RingDiscMeshOptions& options) {
  return add_ghost_layer(make_ring_disc_sheet(options));
}

}  // namespace growshell
