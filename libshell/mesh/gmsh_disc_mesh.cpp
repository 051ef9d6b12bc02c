#include "libshell/mesh/gmsh_disc_mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "libshell/mesh/ghost_layer.hpp"
#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/radial_size.hpp"

namespace growshell {

namespace {

const std::string kCaller = "make_gmsh_disc_mesh";

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

// gmsh::initialize on construction, gmsh::finalize on destruction (also when unwinding).
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
    // Throw (not exit) on errors; the API converts them to exceptions.
    gmsh::option::setNumber("General.AbortOnError", 3);
  }
  ~GmshSession() {
    try {
      gmsh::finalize();
    } catch (...) {  // a destructor must not throw; nothing left to clean up
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

std::string gmsh_last_error() {
  std::string error;
  try {
    gmsh::logger::getLastError(error);
  } catch (...) {
  }
  return error.empty() ? "no message" : error;
}

void check_options(const GmshDiscMeshOptions& o) {
  if (!(std::isfinite(o.radius) && o.radius > 0.0))
    throw MeshError(kCaller + ": radius must be finite and > 0, got " + std::to_string(o.radius));
  if (!(o.inner_radius >= 0.0 && o.inner_radius < o.radius))
    throw MeshError(kCaller + ": inner_radius must be in [0, radius), got " +
                    std::to_string(o.inner_radius));
  check_radial_size({o.size_slope, o.size_floor, o.size_max}, kCaller);
  if (o.msh_file_version != 4.1 && o.msh_file_version != 2.2)
    throw MeshError(kCaller + ": msh_file_version must be 4.1 or 2.2, got " +
                    std::to_string(o.msh_file_version));
  if (o.inner_radius > 0.0) {
    const double edges = 2.0 * std::numbers::pi * o.inner_radius /
                         radial_size({o.size_slope, o.size_floor, o.size_max}, o.inner_radius);
    if (edges < 12.0)
      throw MeshError(kCaller + ": the inner circle would get only " + std::to_string(edges) +
                      " edges of size s(inner_radius) (at least 12 are needed for its ghost "
                      "layer); decrease size_floor or size_max");
  }
  // Triangles ~ (4 / sqrt 3) * integral of dA / s(r)^2 over the region.
  const RadialSize size{o.size_slope, o.size_floor, o.size_max};
  double estimate = 0.0;
  const int steps = 2000;
  for (int k = 0; k < steps; ++k) {
    const double r = o.inner_radius + (o.radius - o.inner_radius) * (k + 0.5) / steps;
    const double s = radial_size(size, r);
    estimate += 2.0 * std::numbers::pi * r * (o.radius - o.inner_radius) / steps / (s * s);
  }
  estimate *= 4.0 / std::sqrt(3.0);
  if (!(estimate <= 1e7))
    throw MeshError(kCaller + ": the size field would give about " + std::to_string(estimate) +
                    " triangles (more than 1e7); increase size_floor or size_slope");
}

// Four quarter arcs of the circle of radius r about the centre point, counter-clockwise.
std::vector<int> add_circle(double r, int center) {
  std::vector<int> points;
  for (int k = 0; k < 4; ++k) {
    const double x = k == 0 ? r : (k == 2 ? -r : 0.0);
    const double y = k == 1 ? r : (k == 3 ? -r : 0.0);
    points.push_back(gmsh::model::geo::addPoint(x, y, 0.0));
  }
  std::vector<int> arcs;
  for (int k = 0; k < 4; ++k)
    arcs.push_back(gmsh::model::geo::addCircleArc(points[static_cast<std::size_t>(k)], center,
                                                  points[static_cast<std::size_t>((k + 1) % 4)]));
  return arcs;
}

// The boundary of the sector 0 <= theta <= pi/4 (of the annulus if inner_radius > 0),
// counter-clockwise: along the x-axis, the outer arc, back along the diagonal x = y, and the
// inner arc. The diagonal's end points have x = y exactly, so that Gmsh's points on it do too.
std::vector<int> add_sector(const GmshDiscMeshOptions& o, int center) {
  const double c = o.radius / std::numbers::sqrt2;
  const int outer_x = gmsh::model::geo::addPoint(o.radius, 0.0, 0.0);
  const int outer_d = gmsh::model::geo::addPoint(c, c, 0.0);
  const int outer_arc = gmsh::model::geo::addCircleArc(outer_x, center, outer_d);
  if (o.inner_radius == 0.0)
    return {gmsh::model::geo::addLine(center, outer_x), outer_arc,
            gmsh::model::geo::addLine(outer_d, center)};
  const double ci = o.inner_radius / std::numbers::sqrt2;
  const int inner_x = gmsh::model::geo::addPoint(o.inner_radius, 0.0, 0.0);
  const int inner_d = gmsh::model::geo::addPoint(ci, ci, 0.0);
  return {gmsh::model::geo::addLine(inner_x, outer_x), outer_arc,
          gmsh::model::geo::addLine(outer_d, inner_d),
          gmsh::model::geo::addCircleArc(inner_d, center, inner_x)};
}

TriangleMesh run_gmsh(const GmshDiscMeshOptions& o) {
  const RadialSize size{o.size_slope, o.size_floor, o.size_max};
  gmsh::model::add("growshell_disc");
  gmsh::option::setNumber("General.NumThreads", 1);
  gmsh::option::setNumber("Mesh.MaxNumThreads2D", 1);
  gmsh::option::setNumber("Mesh.RandomSeed", o.random_seed);
  gmsh::option::setNumber("Mesh.Algorithm", o.algorithm == GmshAlgorithm::Delaunay ? 5 : 6);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
  gmsh::option::setNumber("Mesh.MeshSizeMax", std::isfinite(o.size_max) ? o.size_max : 1e22);
  gmsh::option::setNumber("Mesh.ElementOrder", 1);
  gmsh::option::setNumber("Mesh.Binary", 0);

  const int center = gmsh::model::geo::addPoint(0.0, 0.0, 0.0);
  std::vector<int> loops;
  if (o.dihedral_symmetry) {
    loops.push_back(gmsh::model::geo::addCurveLoop(add_sector(o, center)));
  } else {
    loops.push_back(gmsh::model::geo::addCurveLoop(add_circle(o.radius, center)));
    if (o.inner_radius > 0.0)
      loops.push_back(gmsh::model::geo::addCurveLoop(add_circle(o.inner_radius, center)));
  }
  const int surface = gmsh::model::geo::addPlaneSurface(loops);
  gmsh::model::geo::synchronize();
  if (o.inner_radius == 0.0 && o.center_vertex && !o.dihedral_symmetry)
    gmsh::model::mesh::embed(0, {center}, 2, surface);
  gmsh::model::mesh::setSizeCallback(
      [size](int, int, double x, double y, double) { return radial_size(size, std::hypot(x, y)); });
  gmsh::model::mesh::generate(2);
  if (!o.msh_file.empty()) {
    gmsh::option::setNumber("Mesh.MshFileVersion", o.msh_file_version);
    gmsh::option::setNumber("Mesh.SaveAll", 0);
    gmsh::write(o.msh_file);
  }

  std::vector<std::size_t> node_tags;
  std::vector<double> coords;
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  std::vector<std::size_t> element_tags;
  std::vector<std::size_t> element_nodes;
  gmsh::model::mesh::getElementsByType(2, element_tags, element_nodes, surface);
  gmsh::model::mesh::removeSizeCallback();

  std::map<std::size_t, std::size_t> node_slot;  // tag -> position in node_tags
  for (std::size_t k = 0; k < node_tags.size(); ++k) node_slot[node_tags[k]] = k;
  std::map<std::size_t, int> index;  // used tag -> vertex index, in increasing tag
  for (const std::size_t t : element_nodes) {
    if (!node_slot.count(t)) throw MeshError(kCaller + ": Gmsh returned a triangle with an unknown node");
    index[t] = 0;
  }
  TriangleMesh sheet;
  sheet.vertices.resize(static_cast<Eigen::Index>(index.size()), 3);
  int next = 0;
  for (auto& [tag, v] : index) {
    v = next++;
    const std::size_t k = node_slot[tag];
    sheet.vertices.row(v) << coords[3 * k], coords[3 * k + 1], 0.0;
  }
  sheet.faces.resize(static_cast<Eigen::Index>(element_tags.size()), 3);
  for (std::size_t f = 0; f < element_tags.size(); ++f) {
    int t[3];
    for (int k = 0; k < 3; ++k) t[k] = index[element_nodes[3 * f + static_cast<std::size_t>(k)]];
    const Eigen::Vector2d a = sheet.vertices.row(t[0]).head<2>();
    const Eigen::Vector2d b = sheet.vertices.row(t[1]).head<2>();
    const Eigen::Vector2d c = sheet.vertices.row(t[2]).head<2>();
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (area2 < 0.0) std::swap(t[1], t[2]);
    sheet.faces.row(static_cast<Eigen::Index>(f)) << t[0], t[1], t[2];
  }
  return sheet;
}

// Puts the sector's vertices exactly onto the lines of its straight edges (y = 0 and x = y;
// Gmsh places them there up to rounding), so that the mirrors across them map them onto
// themselves exactly.
void snap_to_sector_edges(TriangleMesh& sector, double radius) {
  const double tolerance = 1e-12 * radius;
  for (Eigen::Index v = 0; v < sector.vertices.rows(); ++v) {
    double& x = sector.vertices(v, 0);
    double& y = sector.vertices(v, 1);
    if (std::abs(y) <= tolerance) y = 0.0;
    if (std::abs(x - y) <= tolerance) x = y = 0.5 * (x + y);
    if (y < 0.0 || y > x)
      throw MeshError(kCaller + ": Gmsh put sector vertex " + std::to_string(v) +
                      " outside the sector 0 <= theta <= pi/4");
  }
}

// The sector's images under the eight elements of D4 (quarter turns k = 0..3, each with and
// without the mirror y -> -y), vertices on shared edges merged by their exact positions.
TriangleMesh reflect_sector_to_disc(const TriangleMesh& sector) {
  TriangleMesh disc;
  std::vector<Eigen::Vector3d> points;
  std::map<std::pair<double, double>, int> index_of;
  std::vector<Eigen::Vector3i> faces;
  for (int mirrored = 0; mirrored < 2; ++mirrored) {
    for (int turn = 0; turn < 4; ++turn) {
      std::vector<int> image(static_cast<std::size_t>(sector.vertices.rows()));
      for (Eigen::Index v = 0; v < sector.vertices.rows(); ++v) {
        double x = sector.vertices(v, 0);
        double y = mirrored ? -sector.vertices(v, 1) : sector.vertices(v, 1);
        for (int k = 0; k < turn; ++k) {  // (x, y) -> (-y, x), exact in floating point
          const double t = x;
          x = -y;
          y = t;
        }
        // -0.0 and 0.0 are one position.
        const std::pair<double, double> key(x == 0.0 ? 0.0 : x, y == 0.0 ? 0.0 : y);
        const auto [it, added] = index_of.emplace(key, static_cast<int>(points.size()));
        if (added) points.emplace_back(key.first, key.second, 0.0);
        image[static_cast<std::size_t>(v)] = it->second;
      }
      for (Eigen::Index f = 0; f < sector.faces.rows(); ++f) {
        Eigen::Vector3i t;
        for (int k = 0; k < 3; ++k) t(k) = image[static_cast<std::size_t>(sector.faces(f, k))];
        if (mirrored) std::swap(t(1), t(2));  // a mirror reverses the orientation
        faces.push_back(t);
      }
    }
  }
  disc.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    disc.vertices.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
  disc.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    disc.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return disc;
}

// Puts the vertices on the boundary circles exactly onto them (Gmsh places them there up to
// rounding); with `all_on_circles`, every boundary vertex must be on one of them.
void project_onto_circles(TriangleMesh& sheet, const GmshDiscMeshOptions& options,
                          bool all_on_circles) {
  const MeshTopology topo(sheet);
  for (int v = 0; v < topo.num_vertices(); ++v) {
    if (!topo.is_boundary_vertex(v)) continue;
    const double r = sheet.vertices.row(v).norm();
    const double target = options.inner_radius > 0.0 &&
                                  std::abs(r - options.inner_radius) < std::abs(r - options.radius)
                              ? options.inner_radius
                              : options.radius;
    if (!(std::abs(r - target) <= 1e-6 * options.radius)) {
      if (!all_on_circles) continue;  // a vertex on a straight edge of the sector
      throw MeshError(kCaller + ": Gmsh boundary vertex " + std::to_string(v) +
                      " is not on a boundary circle (radius " + std::to_string(r) + ")");
    }
    sheet.vertices.row(v) *= target / r;
  }
}

}  // namespace

TriangleMesh make_gmsh_disc_sheet(const GmshDiscMeshOptions& options) {
  check_options(options);
  TriangleMesh sheet;
  {
    const std::lock_guard<std::mutex> lock(gmsh_mutex());
    const GmshSession session;
    try {
      sheet = run_gmsh(options);
    } catch (const MeshError&) {
      throw;
    } catch (const std::exception& e) {
      throw MeshError(kCaller + ": Gmsh failed: " + e.what() + " (" + gmsh_last_error() + ")");
    } catch (...) {
      throw MeshError(kCaller + ": Gmsh failed: " + gmsh_last_error());
    }
  }
  if (sheet.faces.rows() == 0) throw MeshError(kCaller + ": Gmsh generated no triangles");
  if (!options.dihedral_symmetry) {
    project_onto_circles(sheet, options, true);
    return sheet;
  }
  project_onto_circles(sheet, options, false);
  snap_to_sector_edges(sheet, options.radius);
  TriangleMesh disc = reflect_sector_to_disc(sheet);
  // The reflected sectors must close up: a sheet (MeshTopology throws otherwise) whose only
  // boundary is the circles, i.e. no sector edge left unmerged.
  const MeshTopology topo(disc);
  for (int v = 0; v < topo.num_vertices(); ++v) {
    const double r = disc.vertices.row(v).norm();
    if (topo.is_boundary_vertex(v) && std::abs(r - options.radius) > 1e-9 * options.radius &&
        std::abs(r - options.inner_radius) > 1e-9 * options.radius)
      throw MeshError(kCaller + ": the reflected sectors leave vertex " + std::to_string(v) +
                      " (radius " + std::to_string(r) + ") on a boundary inside the disc");
  }
  return disc;
}

TriangleMesh make_gmsh_disc_mesh(const GmshDiscMeshOptions& options) {
  return add_ghost_layer(make_gmsh_disc_sheet(options));
}

}  // namespace growshell
