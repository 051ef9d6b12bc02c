#include "libshell/mesh/vertex_symmetry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace growshell {

namespace {

void check_axis(int axis, const char* caller) {
  if (axis < 0 || axis > 2)
    throw std::invalid_argument(std::string(caller) + ": axis must be 0, 1 or 2 (x, y, z), got " +
                                std::to_string(axis));
}

}  // namespace

VertexSymmetry find_vertex_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                    const Eigen::Vector3d& signs, double tolerance) {
  for (int c = 0; c < 3; ++c)
    if (signs(c) != 1.0 && signs(c) != -1.0)
      throw std::invalid_argument("find_vertex_symmetry: signs must be +1 or -1, got " +
                                  std::to_string(signs(c)) + " for coordinate " +
                                  std::to_string(c));
  if (!(tolerance > 0.0 && std::isfinite(tolerance)))
    throw std::invalid_argument("find_vertex_symmetry: tolerance must be finite and > 0");
  const Eigen::Index n = positions.rows();
  // Vertices sorted by x; the image of p is searched among those with x within the tolerance
  // of (S p)_x, and among them the nearest is taken.
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return positions(a, 0) < positions(b, 0) || (positions(a, 0) == positions(b, 0) && a < b);
  });
  std::vector<double> sorted_x(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted_x[k] = positions(order[k], 0);
  VertexSymmetry out;
  out.signs = signs;
  out.image.assign(static_cast<std::size_t>(n), -1);
  std::vector<char> taken(static_cast<std::size_t>(n), 0);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::RowVector3d target = positions.row(v).cwiseProduct(signs.transpose());
    auto it = std::lower_bound(sorted_x.begin(), sorted_x.end(), target(0) - tolerance);
    int best = -1;
    double best_distance = tolerance;
    for (; it != sorted_x.end() && *it <= target(0) + tolerance; ++it) {
      const int u = order[static_cast<std::size_t>(it - sorted_x.begin())];
      const double d = (positions.row(u) - target).norm();
      if (d <= best_distance) {
        best_distance = d;
        best = u;
      }
    }
    if (best < 0 || taken[static_cast<std::size_t>(best)]) {
      std::ostringstream m;
      m << "find_vertex_symmetry: vertex " << v << " at (" << positions(v, 0) << ", "
        << positions(v, 1) << ", " << positions(v, 2) << ") has "
        << (best < 0 ? "no image" : "an image taken by another vertex") << " under diag("
        << signs(0) << ", " << signs(1) << ", " << signs(2) << ") within " << tolerance
        << " m: the vertex set does not have this symmetry";
      throw std::invalid_argument(m.str());
    }
    taken[static_cast<std::size_t>(best)] = 1;
    out.image[static_cast<std::size_t>(v)] = best;
  }
  return out;
}

VertexSymmetry mirror_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions, int axis,
                               double tolerance) {
  check_axis(axis, "mirror_symmetry");
  Eigen::Vector3d signs = Eigen::Vector3d::Ones();
  signs(axis) = -1.0;
  return find_vertex_symmetry(positions, signs, tolerance);
}

VertexSymmetry half_turn_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions, int axis,
                                  double tolerance) {
  check_axis(axis, "half_turn_symmetry");
  Eigen::Vector3d signs = -Eigen::Vector3d::Ones();
  signs(axis) = 1.0;
  return find_vertex_symmetry(positions, signs, tolerance);
}

void check_maps_faces_onto_faces(const MeshTopology& topology, const VertexSymmetry& symmetry) {
  if (static_cast<int>(symmetry.image.size()) != topology.num_vertices())
    throw std::invalid_argument("check_maps_faces_onto_faces: the symmetry maps " +
                                std::to_string(symmetry.image.size()) + " vertices, the mesh has " +
                                std::to_string(topology.num_vertices()));
  const auto sorted = [](std::array<int, 3> f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  std::set<std::array<int, 3>> faces;
  for (int f = 0; f < topology.num_faces(); ++f) faces.insert(sorted(topology.face(f)));
  for (int f = 0; f < topology.num_faces(); ++f) {
    const std::array<int, 3>& face = topology.face(f);
    std::array<int, 3> image;
    for (int k = 0; k < 3; ++k)
      image[static_cast<std::size_t>(k)] =
          symmetry.image[static_cast<std::size_t>(face[static_cast<std::size_t>(k)])];
    if (!faces.count(sorted(image))) {
      std::ostringstream m;
      m << "check_maps_faces_onto_faces: face " << f << " (" << face[0] << ", " << face[1] << ", "
        << face[2] << ") maps to (" << image[0] << ", " << image[1] << ", " << image[2]
        << "), which is not a face: the triangulation does not have the symmetry of its vertices";
      throw std::invalid_argument(m.str());
    }
  }
}

double symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const VertexSymmetry& symmetry) {
  if (static_cast<Eigen::Index>(symmetry.image.size()) != positions.rows())
    throw std::invalid_argument("symmetry_defect: the symmetry maps " +
                                std::to_string(symmetry.image.size()) +
                                " vertices, the state has " + std::to_string(positions.rows()));
  double worst = 0.0;
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::RowVector3d mapped = positions.row(v).cwiseProduct(symmetry.signs.transpose());
    worst = std::max(worst,
                     (mapped - positions.row(symmetry.image[static_cast<std::size_t>(v)])).norm());
  }
  return worst;
}

}  // namespace growshell
