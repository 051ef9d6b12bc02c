#pragma once
/// \file
/// Symmetries of a vertex set that map vertices onto vertices: a mirror about a coordinate
/// plane through the origin, or a half turn about a coordinate axis (VertexSymmetry, a diagonal
/// matrix), or a general linear isometry such as the quarter turn about z
/// (LinearVertexSymmetry). The diagonal ones describe the
/// symmetric subspaces in which a symmetric branch can be traced without its symmetry-breaking
/// bifurcations (solvers/continuation/symmetric_subspace.hpp).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "libshell/mesh/mesh_topology.hpp"

namespace growshell {

/// A linear isometry S = diag(signs) (each sign +1 or -1) that maps the vertex set onto
/// itself: S p_v = p_{image[v]} for every vertex v.
struct VertexSymmetry {
  std::vector<int> image;                           ///< vertex v goes to vertex image[v]
  Eigen::Vector3d signs = Eigen::Vector3d::Ones();  ///< diagonal of S
};

/// The symmetry diag(signs) of the vertex set `positions` (one row per vertex): for every
/// vertex the vertex at S p_v, found within `tolerance` (m). Throws std::invalid_argument
/// naming the first vertex without an image (its index and position), for a sign other than
/// +1 or -1, or for a tolerance that is not > 0. O(n log n).
VertexSymmetry find_vertex_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                    const Eigen::Vector3d& signs, double tolerance);

/// The mirror about the plane through the origin normal to coordinate `axis` (0 = x, 1 = y,
/// 2 = z), e.g. axis 1: (x, y, z) -> (x, -y, z). As find_vertex_symmetry; also throws for an
/// axis outside 0..2.
VertexSymmetry mirror_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions, int axis,
                               double tolerance);

/// The half turn about coordinate `axis`, e.g. axis 2: (x, y, z) -> (-x, -y, z). As
/// mirror_symmetry.
VertexSymmetry half_turn_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions, int axis,
                                  double tolerance);

/// Throws std::invalid_argument naming the first face whose image under `symmetry` is not a
/// face of `topology` (as a vertex set). A vertex set can have a symmetry its triangulation
/// lacks (e.g. a grid whose cells are all split along the same diagonal); the subdivision
/// surface, and so the energy, then does not have it.
void check_maps_faces_onto_faces(const MeshTopology& topology, const VertexSymmetry& symmetry);

/// A linear isometry S (any orthogonal 3x3 matrix, e.g. the quarter turn about z) that maps the
/// vertex set onto itself: S p_v = p_{image[v]} for every vertex v. Kept apart from
/// VertexSymmetry, whose diagonal `signs` the symmetric subspaces of solvers/continuation rely
/// on.
struct LinearVertexSymmetry {
  std::vector<int> image;                             ///< vertex v goes to vertex image[v]
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();  ///< S
};

/// The symmetry S = `matrix` of the vertex set `positions` (one row per vertex): for every
/// vertex the vertex at S p_v, found within `tolerance` (m). Throws std::invalid_argument
/// naming the first vertex without an image, for a matrix that is not orthogonal (|S^T S - I|
/// > 1e-12), or for a tolerance that is not > 0. O(n log n) for vertex sets spread in x.
LinearVertexSymmetry find_linear_vertex_symmetry(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions, const Eigen::Matrix3d& matrix,
    double tolerance);

/// The quarter turn about the z-axis, (x, y, z) -> (-y, x, z) (counter-clockwise by 90 degrees
/// seen from +z). As find_linear_vertex_symmetry.
LinearVertexSymmetry quarter_turn_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                           double tolerance);

/// As check_maps_faces_onto_faces for a VertexSymmetry.
void check_maps_faces_onto_faces(const MeshTopology& topology,
                                 const LinearVertexSymmetry& symmetry);

/// Largest |S p_v - p_{image[v]}| over the vertices of `positions` (m). Throws
/// std::invalid_argument if the symmetry is for another vertex count.
double symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const LinearVertexSymmetry& symmetry);

/// Largest |S p_v - p_{image[v]}| over the vertices of `positions` (m): 0 for a state that has
/// the symmetry. Throws std::invalid_argument if the symmetry is for another vertex count.
double symmetry_defect(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                       const VertexSymmetry& symmetry);

}  // namespace growshell
