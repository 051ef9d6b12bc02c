#pragma once
/// \file
/// Choice of six dofs whose pinning removes the rigid motions of a free-floating body
/// without constraining its deformation.

#include <vector>

#include <Eigen/Core>

namespace growshell {

/// Returns six dof indices (vertex-major layout: dof 3*v + c, c = 0, 1, 2 for x, y, z) that,
/// held fixed, remove the six infinitesimal rigid motions (3 translations, 3 rotations) of
/// the vertex set `positions` (one row per vertex, any length unit) and nothing else.
///
/// Three well-separated vertices are taken from `candidate_vertices`: A = the first
/// candidate, B = the candidate farthest from A, C = the candidate maximising the area of the
/// triangle ABC. The dofs are all of A; the two coordinates of B other than the dominant
/// component of B - A; the coordinate of C along the dominant component of the normal
/// (B - A) x (C - A). Since these are exactly six independent conditions on a rigid velocity
/// field, pinning them fixes the gauge of a rigid-motion-invariant energy without biasing its
/// equilibrium (the reactions at the pinned dofs vanish there). Order: A's x, y, z, then B's
/// two, then C's one.
///
/// Throws std::invalid_argument if fewer than 3 candidates are given, a candidate is out of
/// range, or the candidates are (nearly) collinear: the largest triangle area is below 1e-6
/// times |B - A|^2 / 2.
std::vector<Eigen::Index> rigid_motion_pinned_dofs(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions,
    const std::vector<int>& candidate_vertices);

}  // namespace growshell

namespace growshell {

/// Rigid-motion pins (as rigid_motion_pinned_dofs) on three vertices chosen among
/// `sheet_vertices` so that they respect a mirror symmetry about the x-axis through `center`:
/// the vertex nearest `center` and the vertices farthest along +x and along +y from it, which
/// on the library's disc and annulus meshes lie on mirror axes (0 and 90 degrees). States that
/// are mirror-symmetric stay so under Newton's method with these pins.
std::vector<Eigen::Index> mirror_axis_pinned_dofs(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                                  const std::vector<int>& sheet_vertices,
                                                  const Eigen::Vector3d& center);

}  // namespace growshell
