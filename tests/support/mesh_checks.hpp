#pragma once
// Helpers of the mesh tests: the message of a MeshError, element counts, valence histograms and
// element shape statistics against a radial size field.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/radial_size.hpp"
#include "libshell/mesh/triangle_mesh.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell::test_support {

/// The message of the MeshError that `f` throws, or "<no MeshError thrown>".
template <class F>
std::string mesh_error_message(F&& f) {
  try {
    f();
  } catch (const MeshError& e) {
    return e.what();
  }
  return "<no MeshError thrown>";
}

/// Number of faces with three interior vertices: the elements of a control mesh.
inline int count_elements(const MeshTopology& topo) {
  int count = 0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    count += std::none_of(t.begin(), t.end(), [&](int v) { return topo.is_boundary_vertex(v); });
  }
  return count;
}

/// How many interior vertices have each valence.
inline std::map<int, int> interior_valence_histogram(const TriangleMesh& mesh) {
  const MeshTopology topo(mesh);
  std::map<int, int> h;
  for (int v = 0; v < topo.num_vertices(); ++v)
    if (!topo.is_boundary_vertex(v)) ++h[topo.valence(v)];
  return h;
}

/// Shape statistics of faces 0..num_faces-1 of a planar mesh.
struct ElementStats {
  double min_angle_deg = 180.0;
  double min_size_ratio = 1e300;  ///< longest edge / s(r at the centroid)
  double max_size_ratio = 0.0;
  double mean_size_ratio = 0.0;
};

inline ElementStats element_stats(const TriangleMesh& mesh, Eigen::Index num_faces,
                                  const RadialSize& size) {
  ElementStats st;
  for (Eigen::Index f = 0; f < num_faces; ++f) {
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k) p[k] = mesh.vertices.row(mesh.faces(f, k)).head<2>();
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = p[(k + 1) % 3] - p[k];
      const Eigen::Vector2d b = p[(k + 2) % 3] - p[k];
      const double angle = std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b));
      st.min_angle_deg = std::min(st.min_angle_deg, angle * 180.0 / std::numbers::pi);
      longest = std::max(longest, a.norm());
    }
    const double ratio = longest / radial_size(size, ((p[0] + p[1] + p[2]) / 3.0).norm());
    st.min_size_ratio = std::min(st.min_size_ratio, ratio);
    st.max_size_ratio = std::max(st.max_size_ratio, ratio);
    st.mean_size_ratio += ratio / static_cast<double>(num_faces);
  }
  return st;
}

/// Expects the two-fold cone's symmetry group of the mesh, bit for bit on the vertices (ghosts
/// included) and as a map of faces onto faces: the mirrors x -> -x and y -> -y and the quarter
/// turn about z. Returns the quarter turn's vertex map.
inline LinearVertexSymmetry expect_cone_symmetry_group(const TriangleMesh& mesh) {
  const MeshTopology topo(mesh);
  for (const int axis : {0, 1}) {
    const VertexSymmetry m = mirror_symmetry(mesh.vertices, axis, 1e-12);
    EXPECT_EQ(symmetry_defect(mesh.vertices, m), 0.0) << "mirror normal to axis " << axis;
    EXPECT_NO_THROW(check_maps_faces_onto_faces(topo, m)) << "mirror normal to axis " << axis;
  }
  const LinearVertexSymmetry q = quarter_turn_symmetry(mesh.vertices, 1e-12);
  EXPECT_EQ(symmetry_defect(mesh.vertices, q), 0.0);
  EXPECT_NO_THROW(check_maps_faces_onto_faces(topo, q));
  return q;
}

}  // namespace growshell::test_support

/// EXPECT that `text` contains `part`, printing the text otherwise.
#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)
