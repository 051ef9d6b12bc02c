#include "libshell/mesh/mesh_validation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/mesh_topology.hpp"

namespace growshell {

namespace {

Eigen::Vector3d face_normal(const TriangleMesh& mesh, int a, int b, int c) {
  const Eigen::Vector3d pa = mesh.vertices.row(a).transpose();
  const Eigen::Vector3d pb = mesh.vertices.row(b).transpose();
  const Eigen::Vector3d pc = mesh.vertices.row(c).transpose();
  return (pb - pa).cross(pc - pa);
}

void check_finite(const TriangleMesh& mesh) {
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(mesh.vertices(v, k))) {
        std::ostringstream msg;
        msg << "vertex " << v << " has a non-finite coordinate "
            << "xyz"[k] << " = " << mesh.vertices(v, k);
        throw MeshError(msg.str());
      }
    }
  }
}

void check_degenerate(const TriangleMesh& mesh, const MeshTopology& topo) {
  double sum_length = 0.0;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    for (int k = 0; k < 3; ++k) {
      sum_length += (mesh.vertices.row(t[k]) - mesh.vertices.row(t[(k + 1) % 3])).norm();
    }
  }
  const double mean_length = sum_length / (3.0 * topo.num_faces());
  const double min_area = 1e-12 * mean_length * mean_length;
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    const double area = 0.5 * face_normal(mesh, t[0], t[1], t[2]).norm();
    if (!(area > min_area)) {
      std::ostringstream msg;
      msg << "face " << f << " (" << t[0] << ", " << t[1] << ", " << t[2]
          << ") is degenerate: area " << area << " <= 1e-12 * (mean edge length)^2 = " << min_area;
      throw MeshError(msg.str());
    }
  }
}

void check_inverted(const TriangleMesh& mesh, const MeshTopology& topo) {
  const Eigen::Vector3d lo = mesh.vertices.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = mesh.vertices.colwise().maxCoeff().transpose();
  const bool planar_xy = (hi.z() - lo.z()) <= 1e-12 * (hi - lo).head<2>().norm();
  if (planar_xy) {
    // In a plane the folds are the faces whose signed area disagrees with the majority; naming
    // those is more useful than naming every fold edge.
    int num_positive = 0;
    for (int f = 0; f < topo.num_faces(); ++f) {
      const auto& t = topo.face(f);
      if (face_normal(mesh, t[0], t[1], t[2]).z() > 0.0) ++num_positive;
    }
    const double majority = 2 * num_positive >= topo.num_faces() ? 1.0 : -1.0;
    for (int f = 0; f < topo.num_faces(); ++f) {
      const auto& t = topo.face(f);
      const double signed_area = 0.5 * face_normal(mesh, t[0], t[1], t[2]).z();
      if (signed_area * majority <= 0.0) {
        std::ostringstream msg;
        msg << "face " << f << " (" << t[0] << ", " << t[1] << ", " << t[2]
            << ") is inverted: its signed area in the xy-plane is " << signed_area
            << ", opposite to the majority of faces";
        throw MeshError(msg.str());
      }
    }
    return;
  }
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    const Eigen::Vector3d nf = face_normal(mesh, t[0], t[1], t[2]);
    for (int k = 0; k < 3; ++k) {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      const int g = topo.face_with_edge(b, a);
      if (g < f) continue;  // boundary edge (g = -1) or pair already checked
      const int c = topo.opposite_vertex(b, a);
      const Eigen::Vector3d ng = face_normal(mesh, b, a, c);
      const double cos_angle = nf.dot(ng) / (nf.norm() * ng.norm());
      if (cos_angle < 0.0) {
        std::ostringstream msg;
        msg << "faces " << f << " and " << g << " are folded over their shared edge (" << a << ", "
            << b << "): their normals are "
            << std::acos(std::max(-1.0, cos_angle)) * 180.0 / 3.14159265358979323846
            << " degrees apart (at most 90 allowed)";
        throw MeshError(msg.str());
      }
    }
  }
}

}  // namespace

void validate_control_mesh(const TriangleMesh& mesh) {
  const MeshTopology topo(mesh);
  if (topo.num_faces() == 0) throw MeshError("the mesh has no faces");
  check_finite(mesh);
  check_degenerate(mesh, topo);
  check_inverted(mesh, topo);
  for (int v = 0; v < topo.num_vertices(); ++v) {
    const int valence = topo.valence(v);
    if (!topo.is_boundary_vertex(v) &&
        (valence < kMinInteriorValence || valence > kMaxInteriorValence)) {
      throw MeshError("interior vertex " + std::to_string(v) + " has valence " +
                      std::to_string(valence) + "; growshell's Loop elements support interior "
                      "valences " + std::to_string(kMinInteriorValence) + " to " +
                      std::to_string(kMaxInteriorValence));
    }
  }
  for (int f = 0; f < topo.num_faces(); ++f) {
    const auto& t = topo.face(f);
    if (!topo.is_boundary_vertex(t[0]) && !topo.is_boundary_vertex(t[1]) &&
        !topo.is_boundary_vertex(t[2])) {
      return;
    }
  }
  throw MeshError(
      "the mesh has no element: no face has three interior vertices (the outermost layer of "
      "the control mesh is a ghost layer, so the mesh needs at least two layers of faces)");
}

}  // namespace growshell
