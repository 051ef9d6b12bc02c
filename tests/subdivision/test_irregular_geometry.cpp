// Limit surfaces of control meshes WITH extraordinary vertices, sampled from exact surfaces
// (sphere by the geodesic polar map, cylinder by the isometric wrap): position, normal and
// mean-curvature errors under refinement, as the maximum over all elements, the maximum
// away from the centre and the area-weighted RMS (docs/verification.md records the numbers).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/element_patches.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "libshell/subdivision/triangle_quadrature.hpp"
#include "tests/support/convergence_rate.hpp"
#include "tests/support/polygon_disc.hpp"

namespace growshell {
namespace {

using test_support::convergence_rate;
using test_support::polygon_disc;

/// Closest-point data of an exact surface at x: signed distance, unit normal, mean curvature.
using ExactSurface =
    std::function<std::tuple<double, Eigen::Vector3d, double>(const Eigen::Vector3d&)>;

/// Per element: the maximum errors over its quadrature points, the area-weighted sums of the
/// squared errors, its area, and where it lies in the planar reference.
struct ElementErrors {
  double max_position = 0, max_normal = 0, max_H = 0;
  double sq_position = 0, sq_normal = 0, sq_H = 0, area = 0;
  double centroid_radius = 0;  // |planar centroid|
  bool irregular = false;      // has an extraordinary corner
  bool at_rim = false;         // a corner is a boundary vertex of the sheet (next to the ghosts)
};

/// Errors over a set of elements: maxima and area-weighted RMS.
struct Errors {
  double position = 0, normal = 0, H = 0;              // max
  double rms_position = 0, rms_normal = 0, rms_H = 0;  // sqrt(int e^2 dA / A)
  int elements = 0;
};

Errors collect(const std::vector<ElementErrors>& elements,
               const std::function<bool(const ElementErrors&)>& keep) {
  Errors e;
  double area = 0;
  for (const ElementErrors& x : elements) {
    if (!keep(x)) continue;
    ++e.elements;
    e.position = std::max(e.position, x.max_position);
    e.normal = std::max(e.normal, x.max_normal);
    e.H = std::max(e.H, x.max_H);
    e.rms_position += x.sq_position;
    e.rms_normal += x.sq_normal;
    e.rms_H += x.sq_H;
    area += x.area;
  }
  if (area > 0) {
    e.rms_position = std::sqrt(e.rms_position / area);
    e.rms_normal = std::sqrt(e.rms_normal / area);
    e.rms_H = std::sqrt(e.rms_H / area);
  }
  return e;
}

/// Per-element errors (degree-4 quadrature points) of the limit surface of `mesh` against
/// `exact`; `planar` is the same control mesh before the map onto the surface, and the
/// vertices [0, num_sheet_vertices) are the sheet (the rest is the ghost layer).
std::vector<ElementErrors> measure_element_errors(const TriangleMesh& planar,
                                                  const TriangleMesh& mesh,
                                                  const ExactSurface& exact) {
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  const auto rule = triangle_quadrature(4);
  std::vector<ElementErrors> result;
  result.reserve(patches.patch.size());
  for (const LoopPatch& patch : patches.patch) {
    ElementErrors el;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const int c : patch.corners) {
      const int v = patch.control[static_cast<std::size_t>(c)];
      centroid += planar.vertices.row(v).transpose() / 3.0;
      el.irregular = el.irregular || topology.valence(v) != 6;
      // A corner with a ghost neighbour lies on the sheet's rim.
      for (const int u : topology.one_ring(v))
        el.at_rim = el.at_rim || topology.is_boundary_vertex(u);
    }
    el.centroid_radius = centroid.head<2>().norm();
    for (const auto& q : rule) {
      const LimitSurfacePoint p = evaluate_limit_surface(mesh.vertices, patch, q.v, q.w);
      const auto [distance, normal, H] = exact(p.position);
      const double dA = q.weight * p.tangents.col(0).cross(p.tangents.col(1)).norm();
      const double ep = std::abs(distance), en = (p.normal - normal).norm(),
                   eh = std::abs(p.mean_curvature - H);
      el.max_position = std::max(el.max_position, ep);
      el.max_normal = std::max(el.max_normal, en);
      el.max_H = std::max(el.max_H, eh);
      el.sq_position += dA * ep * ep;
      el.sq_normal += dA * en * en;
      el.sq_H += dA * eh * eh;
      el.area += dA;
    }
    result.push_back(el);
  }
  return result;
}

// The two exact surfaces, each with the map of the planar control mesh onto it.
// Sphere of radius rho about the origin, its pole (0, 0, rho) over the planar origin: geodesic
// polar map (X, Y) -> rho (sin(r / rho) X / r, sin(r / rho) Y / r, cos(r / rho)); the limit
// normal points outwards, H = -1 / rho.
TriangleMesh on_sphere(const TriangleMesh& planar, double rho) {
  TriangleMesh mesh = planar;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const double X = planar.vertices(v, 0), Y = planar.vertices(v, 1);
    const double r = std::hypot(X, Y);
    const double s = r > 0 ? rho * std::sin(r / rho) / r : 1.0;
    mesh.vertices.row(v) << s * X, s * Y, rho * std::cos(r / rho);
  }
  return mesh;
}
ExactSurface sphere(double rho) {
  return [rho](const Eigen::Vector3d& x) {
    const double r = x.norm();
    return std::make_tuple(r - rho, Eigen::Vector3d(x / r), -1.0 / rho);
  };
}
// Cylinder of radius rho with axis along x through (*, 0, rho): isometric wrap
// (X, Y) -> (X, rho sin(Y / rho), rho (1 - cos(Y / rho))); the limit normal points towards the
// axis, H = +1 / (2 rho).
TriangleMesh on_cylinder(const TriangleMesh& planar, double rho) {
  TriangleMesh mesh = planar;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    const double X = planar.vertices(v, 0), Y = planar.vertices(v, 1);
    mesh.vertices.row(v) << X, rho * std::sin(Y / rho), rho * (1.0 - std::cos(Y / rho));
  }
  return mesh;
}
ExactSurface cylinder(double rho) {
  return [rho](const Eigen::Vector3d& x) {
    const Eigen::Vector3d radial(0.0, x.y(), x.z() - rho);
    const double r = radial.norm();
    return std::make_tuple(rho - r, Eigen::Vector3d(-radial / r), 0.5 / rho);
  };
}

constexpr double kSphereRadius = 2.0;    // the unit disc covers 0.5 rad of it
constexpr double kCylinderRadius = 1.0;  // the unit disc wraps 2 rad round it
constexpr double kCore = 0.2;            // "away from the centre": planar centroid |X| >= kCore

enum class Surface { Sphere, Cylinder };
const char* name(Surface s) { return s == Surface::Sphere ? "sphere" : "cylinder"; }

/// The errors of one control mesh (planar layout `planar`) mapped onto `surface`: over all
/// elements, over those whose planar centroid is at least kCore from the centre, and over the
/// elements without an extraordinary corner.
struct Level {
  double h;
  Errors all, away, regular, inner;
};
Level measure_level(const TriangleMesh& planar, Surface surface, double h) {
  const bool on_s = surface == Surface::Sphere;
  const std::vector<ElementErrors> el = measure_element_errors(
      planar, on_s ? on_sphere(planar, kSphereRadius) : on_cylinder(planar, kCylinderRadius),
      on_s ? sphere(kSphereRadius) : cylinder(kCylinderRadius));
  Level l;
  l.h = h;
  l.all = collect(el, [](const ElementErrors&) { return true; });
  l.away = collect(el, [](const ElementErrors& e) { return e.centroid_radius >= kCore; });
  l.regular = collect(el, [](const ElementErrors& e) { return !e.irregular; });
  l.inner = collect(el, [](const ElementErrors& e) { return !e.at_rim; });
  return l;
}

void print(const std::string& family, const std::vector<Level>& levels) {
  std::printf(
      "%s: h | all: position max rms | normal max rms | H max rms | "
      ">= %.1f from centre: position normal H max, H rms | regular elements: H max | no rim "
      "corner: position normal H max, pos nrm H rms\n",
      family.c_str(), kCore);
  for (const Level& l : levels)
    std::printf(
        "  %.4f (%d elements, %d regular) | %.2e %.2e | %.2e %.2e | %.2e %.2e | %.2e %.2e %.2e "
        "%.2e | %.2e | %.2e %.2e %.2e %.2e %.2e %.2e\n",
        l.h, l.all.elements, l.regular.elements, l.all.position, l.all.rms_position, l.all.normal,
        l.all.rms_normal, l.all.H, l.all.rms_H, l.away.position, l.away.normal, l.away.H,
        l.away.rms_H, l.regular.H, l.inner.position, l.inner.normal, l.inner.H,
        l.inner.rms_position, l.inner.rms_normal, l.inner.rms_H);
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    const Level &a = levels[k], &b = levels[k + 1];
    std::printf("  rate | %.2f %.2f | %.2f %.2f | %.2f %.2f | %.2f %.2f %.2f %.2f | %.2f\n",
                convergence_rate(a.all.position, b.all.position),
                convergence_rate(a.all.rms_position, b.all.rms_position),
                convergence_rate(a.all.normal, b.all.normal),
                convergence_rate(a.all.rms_normal, b.all.rms_normal),
                convergence_rate(a.all.H, b.all.H), convergence_rate(a.all.rms_H, b.all.rms_H),
                convergence_rate(a.away.position, b.away.position),
                convergence_rate(a.away.normal, b.away.normal),
                convergence_rate(a.away.H, b.away.H), convergence_rate(a.away.rms_H, b.away.rms_H),
                convergence_rate(a.regular.H, b.regular.H));
  }
}

// polygon_disc(n, m + 1, 1/m): a centre of valence n, every other vertex of valence 6, the
// layout (r, theta) -> (r, 6 theta / n) of the lattice, smooth away from the centre but with
// derivatives growing like 1/r towards it. Sheet rings m = 8, 16, 32, 64 (ghost ring m + 1),
// so the sheet reaches |X| = 1 at the lattice corners at every level; h = 1/m. The elements
// next to the ghost layer are ordinary lattice elements here and are kept.
//
// Measured (docs/verification.md has the tables), for every n in {4, 5, 7, 8} on both surfaces:
//  - position: max and RMS fall as h^2 (rates 1.99..2.00) over all elements, the n elements at
//    the centre included.
//  - normal: max over all elements falls as h (rate 1.00..1.01: the worst point is a quadrature
//  point
//    of an element at the centre), RMS as h^2 (sphere 1.99..2.01, cylinder 1.75..1.88, the
//    slow part of the layout near the centre); away from the centre as h^2 (last rate 1.98..2.06).
//  - H: the max over all elements is the same at every level (rates -0.01..0.01): the n
//    elements at the centre see the same configuration, scaled, at every level, so their error
//    is O(1) (Loop's curvature at an extraordinary vertex is not the sampled surface's:
//    sphere 0.42, 0.098, 0.041, 0.062 and cylinder 0.42, 0.14, 0.13, 0.22 for n = 4, 5, 7, 8,
//    against |H| = 0.5). The elements of the next rings share that (regular elements'
//    max 0.010 .. 0.080, constant as well). The RMS therefore falls as h (rate 0.99..1.00: an O(1)
//    error on an area ~h^2). Outside 0.2 the max falls at rate 2 once 0.2 is several lattice
//    steps from the centre: rates 0.89..1.56, 1.64..1.88, 1.99..2.15 for the three steps
//    (average 1.54..1.81); the RMS there 1.63..1.87, 1.93..2.03, 2.02..2.03.
struct PolygonCase {
  int valence;
  Surface surface;
  double max_H;  // measured max |H error| over all elements at h = 1/64 (Loop's rules)
};
class IrregularGeometryPolygonDisc : public ::testing::TestWithParam<PolygonCase> {};

TEST_P(IrregularGeometryPolygonDisc, ErrorsFallAtMeasuredRates) {
  const auto [n, surface, max_H] = GetParam();
  std::vector<Level> levels;
  for (int m : {8, 16, 32, 64})
    levels.push_back(measure_level(polygon_disc(n, m + 1, 1.0 / m), surface, 1.0 / m));
  print("polygon disc n = " + std::to_string(n) + ", " + name(surface), levels);
  const Level &coarse = levels.front(), &fine = levels.back();
  const double steps = static_cast<double>(levels.size() - 1);
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    const Level &a = levels[k], &b = levels[k + 1];
    SCOPED_TRACE("h = " + std::to_string(a.h) + " -> " + std::to_string(b.h));
    EXPECT_GT(convergence_rate(a.all.position, b.all.position), 1.9);
    EXPECT_GT(convergence_rate(a.all.rms_position, b.all.rms_position), 1.9);
    EXPECT_GT(convergence_rate(a.all.normal, b.all.normal), 0.9);
    EXPECT_GT(convergence_rate(a.all.rms_normal, b.all.rms_normal), 1.6);
    EXPECT_GT(convergence_rate(a.all.rms_H, b.all.rms_H), 0.9);
    EXPECT_GT(convergence_rate(a.away.H, b.away.H), 0.8);
    EXPECT_GT(convergence_rate(a.away.rms_H, b.away.rms_H), 1.5);
  }
  const Level& before = levels[levels.size() - 2];
  EXPECT_GT(convergence_rate(before.away.normal, fine.away.normal), 1.8);
  EXPECT_GT(convergence_rate(before.away.H, fine.away.H), 1.8);
  EXPECT_GT(convergence_rate(before.away.rms_H, fine.away.rms_H), 1.9);
  EXPECT_GT(convergence_rate(coarse.away.normal, fine.away.normal) / steps, 1.75);
  EXPECT_GT(convergence_rate(coarse.away.H, fine.away.H) / steps, 1.45);
  // Near the centre the max does not converge: it is the same O(1) value at every level,
  // asserted to 5 % of the value measured at h = 1/64 (the levels differ by < 1.5 %). The
  // band is two-sided on purpose: the rates above hold for any stationary C1 scheme, and
  // with a wrong extraordinary-vertex rule (tried in a scratch build: Loop's beta times 1.2,
  // or Warren's 3 / (8 n)) every rate assertion above still passes, but this value moves by
  // 23 % to 170 % (for n = 4, 5 with beta times 1.2 it even falls, 0.42 -> 0.16 and
  // 0.098 -> 0.048).
  for (const Level& l : levels) EXPECT_NEAR(l.all.H, max_H, 0.05 * max_H) << "h = " << l.h;
}

INSTANTIATE_TEST_SUITE_P(IrregularGeometry, IrregularGeometryPolygonDisc,
                         ::testing::Values(PolygonCase{4, Surface::Sphere, 0.421},
                                           PolygonCase{5, Surface::Sphere, 0.0983},
                                           PolygonCase{7, Surface::Sphere, 0.0414},
                                           PolygonCase{8, Surface::Sphere, 0.0622},
                                           PolygonCase{4, Surface::Cylinder, 0.421},
                                           PolygonCase{5, Surface::Cylinder, 0.137},
                                           PolygonCase{7, Surface::Cylinder, 0.131},
                                           PolygonCase{8, Surface::Cylinder, 0.216}),
                         [](const auto& info) {
                           return std::string(name(info.param.surface)) + "_valence" +
                                  std::to_string(info.param.valence);
                         });

// Quasi-uniform Gmsh discs (Frontal-Delaunay, size s everywhere), s = 0.2, 0.1, 0.05: valence
// 5 and 7 vertices everywhere, so "away from the centre" is no different from "all"; the
// elements with an extraordinary corner are 56 %, 30 %, 13 % of all : 116, 229, 385,
// growing about like 1/s, not like 1/s^2 as the total does (presumably they line the seams
// between the lattice-like patches that Gmsh's fronts make; not checked). The elements next to the
// ghost layer are kept: leaving them out changes the maxima by at most 6 % and the RMS values by at
// most 10 %. Measured:
//  - position: rates 1.91, 1.94 (sphere) and 1.87, 1.76 (cylinder) for the max, 1.89..1.97 RMS.
//  - normal: max 1.15, 0.94 and 0.81, 0.83; RMS 1.49, 1.59 and 1.46, 1.57.
//  - H: the max does not fall (0.18, 0.21, 0.18 sphere; 0.24, 0.36, 0.30 cylinder; |H| = 0.5):
//    the layout is not a smooth image of the lattice, and Loop reproduces only linear functions
//    on it, so every element with an irregular neighbourhood keeps an O(1) error.
//    The RMS falls as about s^(1/2) (rates 0.49, 0.63 and 0.39, 0.66; 0.39 and 0.40 to s =
//    0.025), the square root of the area fraction of those elements.
class IrregularGeometryGmshDisc : public ::testing::TestWithParam<Surface> {};

TEST_P(IrregularGeometryGmshDisc, ErrorsFallAtMeasuredRates) {
  const Surface surface = GetParam();
  std::vector<Level> levels;
  for (double s : {0.2, 0.1, 0.05}) {
    GmshDiscMeshOptions o;
    o.radius = 1.0;
    o.size_slope = 1e3;  // s(r) = s for r >= s / 1000: quasi-uniform
    o.size_floor = s;
    o.size_max = s;
    levels.push_back(measure_level(make_gmsh_disc_mesh(o), surface, s));
  }
  print(std::string("gmsh disc, ") + name(surface), levels);
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    const Level &a = levels[k], &b = levels[k + 1];
    SCOPED_TRACE("s = " + std::to_string(a.h) + " -> " + std::to_string(b.h));
    EXPECT_GT(convergence_rate(a.all.position, b.all.position), 1.6);
    EXPECT_GT(convergence_rate(a.all.rms_position, b.all.rms_position), 1.8);
    EXPECT_GT(convergence_rate(a.all.normal, b.all.normal), 0.6);
    EXPECT_GT(convergence_rate(a.all.rms_normal, b.all.rms_normal), 1.3);
    EXPECT_GT(convergence_rate(a.all.rms_H, b.all.rms_H), 0.25);
  }
  const Level &coarse = levels.front(), &fine = levels.back();
  EXPECT_GT(convergence_rate(coarse.all.position, fine.all.position) / 2.0, 1.75);
  EXPECT_GT(convergence_rate(coarse.all.rms_H, fine.all.rms_H) / 2.0, 0.4);
  // Bounded, not converging: max |H error| at every size below 0.3 (sphere), 0.45 (cylinder).
  for (const Level& l : levels) EXPECT_LT(l.all.H, surface == Surface::Sphere ? 0.3 : 0.45);
}

INSTANTIATE_TEST_SUITE_P(IrregularGeometry, IrregularGeometryGmshDisc,
                         ::testing::Values(Surface::Sphere, Surface::Cylinder),
                         [](const auto& info) { return std::string(name(info.param)); });

}  // namespace
}  // namespace growshell
