#pragma once
/// \file
/// Narrow phase of self-contact: the distance between two segments P = (p0, p1) and
/// Q = (q0, q1), which pair of features is closest, and the exact gradient and Hessian of the
/// squared distance with that pair held fixed (see point_triangle_distance.hpp for why).
///
/// Local degree-of-freedom order of every 12-entry gradient and 12x12 Hessian here:
///   (p0, p1, q0, q1), coordinates in metres; gradients in m, Hessians dimensionless.
///
/// (Nearly) parallel edges. The line-line distance ((q0 - p0) . n)^2 / |n|^2, n = e0 x e1
/// (e0 = p1 - p0, e1 = q1 - q0), is 0/0 for parallel edges and its derivatives grow like
/// 1/|sin angle|. The classification therefore never returns EdgeEdge when
///   |e0 x e1|^2 < kParallelEdgeTolerance * |e0|^2 |e1|^2   (sin^2 angle < 1e-10),
/// and takes the nearest endpoint-edge or endpoint-endpoint pair instead. That is exact for
/// parallel edges (the minimum over the parameter square is then attained on its boundary) and
/// for nearly parallel ones overestimates the squared distance by at most
///   (1/4) sin^2(angle) min(|e0|^2, |e1|^2) < 2.5e-11 min(|e0|^2, |e1|^2):
/// from the interior minimiser, sliding both closest points along the edges towards the
/// nearer end of a segment (at most half its length) raises the squared distance by
/// (slide length)^2 sin^2(angle), because the closest-point difference is normal to both edges.
/// The EdgeEdge functions themselves stay finite for every pair with e0 x e1 != 0 and throw
/// only for exactly parallel edges.
///
/// The switch between EdgeEdge and the endpoint regions at the threshold is a jump of that
/// size in the squared distance (and of O(1) in its Hessian). IPC removes the effect of such
/// near-parallel switches on a barrier with the edge-edge mollifier below (Li et al. 2020,
/// "Incremental Potential Contact"): the edge-edge barrier is multiplied by m(c), c = |e0 x e1|^2,
/// which is ~2e-7 at the classification threshold when the mollifier threshold is the usual
/// 1e-3 |e0_rest|^2 |e1_rest|^2.

#include <Eigen/Core>

#include "libshell/contact/point_triangle_distance.hpp"

namespace growshell {

/// Relative threshold on sin^2 of the angle between the edges below which they are treated as
/// parallel (see the file comment).
inline constexpr double kParallelEdgeTolerance = 1e-10;

/// Factor of the IPC mollifier threshold: eps_x = kEdgeEdgeMollifierScale |e0|^2 |e1|^2 (rest).
inline constexpr double kEdgeEdgeMollifierScale = 1e-3;

/// Pair of features of segments P = (p0, p1) and Q = (q0, q1) that realises their distance.
enum class EdgeEdgeRegion {
  EdgeEdge,  ///< interiors of both edges: the distance between the two infinite lines
  P0EdgeQ,   ///< endpoint p0 and the interior of Q: point-line distance
  P1EdgeQ,   ///< endpoint p1 and the interior of Q
  Q0EdgeP,   ///< endpoint q0 and the interior of P
  Q1EdgeP,   ///< endpoint q1 and the interior of P
  P0Q0,      ///< endpoint to endpoint: point-point distance
  P0Q1,
  P1Q0,
  P1Q1
};

/// Name of a region ("EdgeEdge", "P0EdgeQ", ...), for messages and test output.
const char* to_string(EdgeEdgeRegion region);

/// Everything the classification finds about one edge pair.
struct EdgeEdgeResult {
  double distance_squared = 0.0;  ///< squared Euclidean distance (m^2)
  EdgeEdgeRegion region = EdgeEdgeRegion::EdgeEdge;
  double s = 0.0;  ///< closest point on P is p0 + s (p1 - p0), s in [0, 1]
  double t = 0.0;  ///< closest point on Q is q0 + t (q1 - q0), t in [0, 1]
  Eigen::Vector3d closest_point_p = Eigen::Vector3d::Zero();  ///< (m)
  Eigen::Vector3d closest_point_q = Eigen::Vector3d::Zero();  ///< (m)
};

/// Closest pair of points of the two segments, their region and the squared distance (m^2).
/// Among boundary candidates of equal distance (e.g. overlapping parallel edges) the first in
/// the order p0, p1, q0, q1 wins, so the result is deterministic. Throws
/// std::invalid_argument for a non-finite coordinate or a zero-length edge (p0 == p1 or
/// q0 == q1).
EdgeEdgeResult edge_edge_closest(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                 const Eigen::Ref<const Eigen::Vector3d>& p1,
                                 const Eigen::Ref<const Eigen::Vector3d>& q0,
                                 const Eigen::Ref<const Eigen::Vector3d>& q1);

/// Region of the closest feature pair (as in edge_edge_closest).
EdgeEdgeRegion classify_edge_edge(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                  const Eigen::Ref<const Eigen::Vector3d>& p1,
                                  const Eigen::Ref<const Eigen::Vector3d>& q0,
                                  const Eigen::Ref<const Eigen::Vector3d>& q1);

/// Squared distance (m^2) between the segments.
double edge_edge_distance_squared(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                  const Eigen::Ref<const Eigen::Vector3d>& p1,
                                  const Eigen::Ref<const Eigen::Vector3d>& q0,
                                  const Eigen::Ref<const Eigen::Vector3d>& q1);

/// Squared distance (m^2) of the region's smooth function: line-line for EdgeEdge, point to
/// the infinite line of the other edge for an endpoint-edge region, point-point otherwise.
/// Equals edge_edge_distance_squared when region is the classified one (up to the parallel
/// threshold, see the file comment). EdgeEdge throws std::invalid_argument for exactly
/// parallel edges.
double edge_edge_distance_squared(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                  const Eigen::Ref<const Eigen::Vector3d>& p1,
                                  const Eigen::Ref<const Eigen::Vector3d>& q0,
                                  const Eigen::Ref<const Eigen::Vector3d>& q1,
                                  EdgeEdgeRegion region);

/// Gradient (m) of the region's squared distance w.r.t. (p0, p1, q0, q1).
Vector12d edge_edge_distance_squared_gradient(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                              const Eigen::Ref<const Eigen::Vector3d>& p1,
                                              const Eigen::Ref<const Eigen::Vector3d>& q0,
                                              const Eigen::Ref<const Eigen::Vector3d>& q1,
                                              EdgeEdgeRegion region);

/// Hessian (dimensionless, symmetric) of the region's squared distance w.r.t.
/// (p0, p1, q0, q1).
Matrix12d edge_edge_distance_squared_hessian(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                             const Eigen::Ref<const Eigen::Vector3d>& p1,
                                             const Eigen::Ref<const Eigen::Vector3d>& q0,
                                             const Eigen::Ref<const Eigen::Vector3d>& q1,
                                             EdgeEdgeRegion region);

/// Value (m^2), gradient (m) and Hessian of the region's squared distance in one evaluation
/// (the three functions above each compute all of it, so an assembly loop should call this).
ValueGradientHessian<12> edge_edge_distance_squared_derivatives(
    const Eigen::Ref<const Eigen::Vector3d>& p0, const Eigen::Ref<const Eigen::Vector3d>& p1,
    const Eigen::Ref<const Eigen::Vector3d>& q0, const Eigen::Ref<const Eigen::Vector3d>& q1,
    EdgeEdgeRegion region);

// ---- IPC edge-edge mollifier -----------------------------------------------------------------

/// Mollifier threshold eps_x = kEdgeEdgeMollifierScale |p1 - p0|^2 |q1 - q0|^2 (m^4) from the
/// REST positions of the two edges, so that it stays fixed during a solve.
double edge_edge_mollifier_threshold(const Eigen::Ref<const Eigen::Vector3d>& p0_rest,
                                     const Eigen::Ref<const Eigen::Vector3d>& p1_rest,
                                     const Eigen::Ref<const Eigen::Vector3d>& q0_rest,
                                     const Eigen::Ref<const Eigen::Vector3d>& q1_rest);

/// IPC mollifier (dimensionless, in [0, 1]): with c = |(p1 - p0) x (q1 - q0)|^2,
/// m = (2 - c / eps_x) c / eps_x for c < eps_x and 1 otherwise; C1 in the positions, 0 for
/// parallel edges. Throws std::invalid_argument unless eps_x is finite and > 0.
double edge_edge_mollifier(const Eigen::Ref<const Eigen::Vector3d>& p0,
                           const Eigen::Ref<const Eigen::Vector3d>& p1,
                           const Eigen::Ref<const Eigen::Vector3d>& q0,
                           const Eigen::Ref<const Eigen::Vector3d>& q1, double eps_x);

/// Gradient (1/m) of the mollifier w.r.t. (p0, p1, q0, q1); zero where c >= eps_x.
Vector12d edge_edge_mollifier_gradient(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                       const Eigen::Ref<const Eigen::Vector3d>& p1,
                                       const Eigen::Ref<const Eigen::Vector3d>& q0,
                                       const Eigen::Ref<const Eigen::Vector3d>& q1, double eps_x);

/// Hessian (1/m^2) of the mollifier w.r.t. (p0, p1, q0, q1); zero where c >= eps_x (it jumps
/// at c = eps_x, as in IPC).
Matrix12d edge_edge_mollifier_hessian(const Eigen::Ref<const Eigen::Vector3d>& p0,
                                      const Eigen::Ref<const Eigen::Vector3d>& p1,
                                      const Eigen::Ref<const Eigen::Vector3d>& q0,
                                      const Eigen::Ref<const Eigen::Vector3d>& q1, double eps_x);

}  // namespace growshell
