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

// For every vertex v the vertex within `tolerance` of S p_v (the nearest one). Vertices sorted
// by x; the image of p is searched among those with x within the tolerance of (S p)_x.
std::vector<int> match_images(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                              const Eigen::Matrix3d& S, double tolerance, const char* caller,
                              const std::string& name) {
  const Eigen::Index n = positions.rows();
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return positions(a, 0) < positions(b, 0) || (positions(a, 0) == positions(b, 0) && a < b);
  });
  std::vector<double> sorted_x(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted_x[k] = positions(order[k], 0);
  std::vector<int> image(static_cast<std::size_t>(n), -1);
  std::vector<char> taken(static_cast<std::size_t>(n), 0);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::RowVector3d target = (S * positions.row(v).transpose()).transpose();
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
      m << caller << ": vertex " << v << " at (" << positions(v, 0) << ", " << positions(v, 1)
        << ", " << positions(v, 2) << ") has "
        << (best < 0 ? "no image" : "an image taken by another vertex") << " under " << name
        << " within " << tolerance << " m: the vertex set does not have this symmetry";
      throw std::invalid_argument(m.str());
    }
    taken[static_cast<std::size_t>(best)] = 1;
    image[static_cast<std::size_t>(v)] = best;
  }
  return image;
}

void check_face_images(const MeshTopology& topology, const std::vector<int>& symmetry_image) {
  if (static_cast<int>(symmetry_image.size()) != topology.num_vertices())
    throw std::invalid_argument("check_maps_faces_onto_faces: the symmetry maps " +
                                std::to_string(symmetry_image.size()) + " vertices, the mesh has " +
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
          symmetry_image[static_cast<std::size_t>(face[static_cast<std::size_t>(k)])];
    if (!faces.count(sorted(image))) {
      std::ostringstream m;
      m << "check_maps_faces_onto_faces: face " << f << " (" << face[0] << ", " << face[1] << ", "
        << face[2] << ") maps to (" << image[0] << ", " << image[1] << ", " << image[2]
        << "), which is not a face: the triangulation does not have the symmetry of its vertices";
      throw std::invalid_argument(m.str());
    }
  }
}

double defect(const Eigen::Ref<const Eigen::MatrixX3d>& positions, const Eigen::Matrix3d& S,
              const std::vector<int>& image) {
  if (static_cast<Eigen::Index>(image.size()) != positions.rows())
    throw std::invalid_argument("symmetry_defect: the symmetry maps " +
                                std::to_string(image.size()) + " vertices, the state has " +
                                std::to_string(positions.rows()));
  double worst = 0.0;
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::RowVector3d mapped = (S * positions.row(v).transpose()).transpose();
    worst = std::max(worst, (mapped - positions.row(image[static_cast<std::size_t>(v)])).norm());
  }
  return worst;
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
  std::ostringstream name;
  name << "diag(" << signs(0) << ", " << signs(1) << ", " << signs(2) << ")";
  VertexSymmetry out;
  out.signs = signs;
  out.image = match_images(positions, signs.asDiagonal().toDenseMatrix(), tolerance,
                           "find_vertex_symmetry", name.str());
  return out;
}

LinearVertexSymmetry find_linear_vertex_symmetry(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions, const Eigen::Matrix3d& matrix,
    double tolerance) {
  if (!matrix.allFinite() ||
      !((matrix.transpose() * matrix - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <=
        1e-12))
    throw std::invalid_argument("find_linear_vertex_symmetry: the matrix is not orthogonal");
  if (!(tolerance > 0.0 && std::isfinite(tolerance)))
    throw std::invalid_argument("find_linear_vertex_symmetry: tolerance must be finite and > 0");
  std::ostringstream name;
  name << "the matrix [" << matrix.row(0) << "; " << matrix.row(1) << "; " << matrix.row(2)
       << "]";
  LinearVertexSymmetry out;
  out.matrix = matrix;
  out.image = match_images(positions, matrix, tolerance, "find_linear_vertex_symmetry", name.str());
  return out;
}

LinearVertexSymmetry quarter_turn_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                           double tolerance) {
  Eigen::Matrix3d S;
  S << 0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  return find_linear_vertex_symmetry(positions, S, tolerance);
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
  check_face_images(topology, symmetry.image);
}

void check_maps_faces_onto_faces(const MeshTopology& topology,
                                 const LinearVertexSymmetry& symmetry) {
  check_face_images(topology, symmetry.image);
}

double symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const VertexSymmetry& symmetry) {
  return defect(positions, symmetry.signs.asDiagonal().toDenseMatrix(), symmetry.image);
}

double symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const LinearVertexSymmetry& symmetry) {
  return defect(positions, symmetry.matrix, symmetry.image);
}

}  // namespace growshell
