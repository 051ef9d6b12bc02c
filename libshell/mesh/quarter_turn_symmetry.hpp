#pragma once
/// \file
/// The quarter turn of a vertex set about an axis parallel to z: (X, Y) -> (-Y, X) about a
/// centre. VertexSymmetry (vertex_symmetry.hpp) covers the diagonal sign maps only (mirrors
/// about coordinate planes, half turns); the quarter turn is what the improper symmetry S4 of
/// the two-fold e-cone acts as on the reference disc (libshell/analysis/cone_symmetry.hpp).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "libshell/mesh/mesh_topology.hpp"

namespace growshell {

/// The map of a vertex set onto itself by the counter-clockwise quarter turn about the line
/// through `center` parallel to z: p_{image[v]} = center + Rq (p_v - center) with
/// Rq (x, y, z) = (-y, x, z).
struct QuarterTurnSymmetry {
  std::vector<int> image;                             ///< vertex v goes to vertex image[v]
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< a point of the axis (m)
};

/// The quarter turn of `positions` (one row per vertex, m) about `center` (only its x and y
/// count; z of the vertices is kept), if the vertex set has it within `tolerance` (m) and it
/// maps every face of `topology` onto a face (a vertex set can have a symmetry that its
/// triangulation lacks; the subdivision surface then lacks it too). Otherwise an empty
/// optional and, if `reason` is given, a sentence naming the first vertex without an image or
/// the first face whose image is not a face. Throws std::invalid_argument for a tolerance that
/// is not finite and > 0, or a topology with another vertex count. O(n log n).
std::optional<QuarterTurnSymmetry> find_quarter_turn_symmetry(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions, const MeshTopology& topology,
    const Eigen::Vector3d& center, double tolerance, std::string* reason = nullptr);

/// As find_quarter_turn_symmetry, but throws std::invalid_argument with the reason when the
/// mesh lacks the quarter turn.
QuarterTurnSymmetry quarter_turn_symmetry(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                          const MeshTopology& topology,
                                          const Eigen::Vector3d& center, double tolerance);

}  // namespace growshell
