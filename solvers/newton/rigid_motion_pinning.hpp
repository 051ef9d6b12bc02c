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

/// How well the six `dofs` (vertex-major layout) hold the rigid motions of the vertex set
/// `positions`: the 2-norm condition number of the 6 x 6 matrix of the dofs' components of
/// the six rigid velocity fields (translations; rotations about the centroid, scaled by the
/// RMS distance from it so that all six are lengths). Near 1-10 for well-spread pins;
/// infinite if the dofs leave a rigid motion free. Throws std::invalid_argument unless there
/// are exactly six dofs, all in range.
double pinned_rigid_motion_condition(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                     const std::vector<Eigen::Index>& dofs);

/// `pins` (six rigid-motion pins as rigid_motion_pinned_dofs returns them) if they hold the
/// rigid motions of `positions` with pinned_rigid_motion_condition <= max_condition; else new
/// pins chosen on `positions` by rigid_motion_pinned_dofs with the vertex of pins[0] as
/// anchor and `candidate_vertices` for the other two. Pins chosen on a reference shape lose
/// their lever arm when the body deforms far (e.g. a rim vertex carried round next to the
/// axis through the other two); the spin they should stop is then nearly free. Throws as the
/// two functions it calls.
std::vector<Eigen::Index> well_conditioned_pins(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                                const std::vector<Eigen::Index>& pins,
                                                const std::vector<int>& candidate_vertices,
                                                double max_condition);

/// Rigid-motion pins (as rigid_motion_pinned_dofs) on three vertices chosen among
/// `sheet_vertices` so that they respect a mirror symmetry about the x-axis through `center`:
/// the vertex nearest `center` and the vertices farthest along +x and along +y from it, which
/// on the library's disc and annulus meshes lie on mirror axes (0 and 90 degrees). States that
/// are mirror-symmetric stay so under Newton's method with these pins.
std::vector<Eigen::Index> mirror_axis_pinned_dofs(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                                  const std::vector<int>& sheet_vertices,
                                                  const Eigen::Vector3d& center);

}  // namespace growshell
