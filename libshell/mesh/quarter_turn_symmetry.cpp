#include "libshell/mesh/quarter_turn_symmetry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace growshell {

std::optional<QuarterTurnSymmetry> find_quarter_turn_symmetry(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions, const MeshTopology& topology,
    const Eigen::Vector3d& center, double tolerance, std::string* reason) {
  if (!(tolerance > 0.0 && std::isfinite(tolerance)))
    throw std::invalid_argument("find_quarter_turn_symmetry: tolerance must be finite and > 0");
  if (positions.rows() != topology.num_vertices())
    throw std::invalid_argument("find_quarter_turn_symmetry: " + std::to_string(positions.rows()) +
                                " positions for a mesh of " +
                                std::to_string(topology.num_vertices()) + " vertices");
  const auto fail = [&](const std::string& why) -> std::optional<QuarterTurnSymmetry> {
    if (reason) *reason = why;
    return std::nullopt;
  };
  const Eigen::Index n = positions.rows();
  // Vertices sorted by x; the image of p is searched among those with x within the tolerance
  // of (Rq p)_x, and among them the nearest is taken (as find_vertex_symmetry).
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return positions(a, 0) < positions(b, 0) || (positions(a, 0) == positions(b, 0) && a < b);
  });
  std::vector<double> sorted_x(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted_x[k] = positions(order[k], 0);
  QuarterTurnSymmetry out;
  out.center = center;
  out.image.assign(static_cast<std::size_t>(n), -1);
  std::vector<char> taken(static_cast<std::size_t>(n), 0);
  for (Eigen::Index v = 0; v < n; ++v) {
    const double dx = positions(v, 0) - center.x(), dy = positions(v, 1) - center.y();
    const Eigen::RowVector3d target(center.x() - dy, center.y() + dx, positions(v, 2));
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
      m << "vertex " << v << " at (" << positions(v, 0) << ", " << positions(v, 1) << ", "
        << positions(v, 2) << ") has "
        << (best < 0 ? "no image" : "an image taken by another vertex")
        << " under the quarter turn (x, y) -> (-y, x) about (" << center.x() << ", "
        << center.y() << ") within " << tolerance
        << " m: the vertex set does not have the quarter-turn symmetry";
      return fail(m.str());
    }
    taken[static_cast<std::size_t>(best)] = 1;
    out.image[static_cast<std::size_t>(v)] = best;
  }
  const auto sorted = [](std::array<int, 3> f) {
    std::sort(f.begin(), f.end());
    return f;
  };
  std::set<std::array<int, 3>> faces;
  for (int f = 0; f < topology.num_faces(); ++f) faces.insert(sorted(topology.face(f)));
  for (int f = 0; f < topology.num_faces(); ++f) {
    const std::array<int, 3>& face = topology.face(f);
    std::array<int, 3> image;
    for (std::size_t k = 0; k < 3; ++k)
      image[k] = out.image[static_cast<std::size_t>(face[k])];
    if (!faces.count(sorted(image))) {
      std::ostringstream m;
      m << "face " << f << " (" << face[0] << ", " << face[1] << ", " << face[2]
        << ") maps under the quarter turn to (" << image[0] << ", " << image[1] << ", "
        << image[2]
        << "), which is not a face: the triangulation does not have the quarter-turn symmetry "
           "of its vertices";
      return fail(m.str());
    }
  }
  return out;
}

QuarterTurnSymmetry quarter_turn_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                          const MeshTopology& topology,
                                          const Eigen::Vector3d& center, double tolerance) {
  std::string reason;
  std::optional<QuarterTurnSymmetry> s =
      find_quarter_turn_symmetry(positions, topology, center, tolerance, &reason);
  if (!s) throw std::invalid_argument("quarter_turn_symmetry: " + reason);
  return *s;
}

}  // namespace growshell
