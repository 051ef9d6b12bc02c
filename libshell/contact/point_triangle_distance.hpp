#pragma once
/// \file
/// Narrow phase of self-contact: the distance between a point and a triangle, which feature of
/// the triangle is closest, and the exact gradient and Hessian of the squared distance with
/// that feature held fixed.
///
/// Why "region held fixed": the squared distance to a triangle is a different smooth function
/// in each Voronoi region of the triangle (plane, one of three lines, one of three points). It
/// is C1 across region boundaries but its Hessian jumps there, so a Newton or interior-point
/// solver differentiates the function of the region the classification picked, as IPC does
/// (Li et al. 2020, "Incremental Potential Contact").
///
/// Local degree-of-freedom order of every 12-entry gradient and 12x12 Hessian here:
///   (p, a, b, c) = (p_x, p_y, p_z, a_x, ..., c_z), all coordinates in metres,
/// so gradients are in m (d of m^2 per m) and Hessians dimensionless.
/// The 9-entry point-line derivatives use (p, x0, x1) in the same way.
///
/// Degenerate input: every function throws std::invalid_argument for a non-finite coordinate,
/// and the triangle functions for a zero-area triangle, defined as
///   |(b - a) x (c - a)| <= kDegenerateTriangleTolerance * (longest edge)^2,
/// i.e. twice the area below 1e-12 of the longest edge squared. Rounding alone gives
/// |n| ~ 1e-16 L^2 for a collinear triangle, so the threshold catches every triangle that is
/// numerically a segment, while slivers above it are classified and differentiated normally:
/// their face Hessian grows like (L^2 / |n|)^2, large but finite, and the face value carries a
/// relative rounding error ~ 1e-16 L^2 / |n| from forming n (inherent to double precision).

#include <Eigen/Core>
#include <string>
#include <array>

namespace growshell {

/// "(x, y, z)" at full precision, for error messages of the distance primitives.
std::string format_point(const Eigen::Ref<const Eigen::Vector3d>& x);


using Vector9d = Eigen::Matrix<double, 9, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// Value, gradient and Hessian of a scalar function of N coordinates (units per function).
template <int N>
struct ValueGradientHessian {
  double value = 0.0;
  Eigen::Matrix<double, N, 1> gradient = Eigen::Matrix<double, N, 1>::Zero();
  Eigen::Matrix<double, N, N> hessian = Eigen::Matrix<double, N, N>::Zero();
};

/// Relative threshold for a zero-area triangle (see the file comment).
inline constexpr double kDegenerateTriangleTolerance = 1e-12;

/// Feature of triangle (a, b, c) closest to a point. Edge regions mean the closest point lies
/// strictly inside that edge; vertex regions mean it is the vertex; Face means the orthogonal
/// projection of the point onto the triangle's plane lies in the closed triangle.
enum class PointTriangleRegion { Face, EdgeAB, EdgeBC, EdgeCA, VertexA, VertexB, VertexC };

/// Name of a region ("Face", "EdgeAB", ...), for messages and test output.
const char* to_string(PointTriangleRegion region);

/// Everything the classification finds about one point-triangle pair.
struct PointTriangleResult {
  double distance_squared = 0.0;  ///< squared Euclidean distance (m^2)
  PointTriangleRegion region = PointTriangleRegion::Face;
  Eigen::Vector3d closest_point = Eigen::Vector3d::Zero();  ///< on the triangle (m)
  /// Barycentric coordinates (weights of a, b, c; non-negative, sum 1) of closest_point.
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
};

/// Closest point of triangle (a, b, c) to p, its region, barycentric coordinates and the
/// squared distance (m^2). Ties between regions (the point equidistant from two features) are
/// broken in the order Face, EdgeAB, EdgeBC, EdgeCA; a point whose projection lies on the
/// triangle's boundary is classified Face. Throws std::invalid_argument for degenerate input.
PointTriangleResult point_triangle_closest(const Eigen::Ref<const Eigen::Vector3d>& p,
                                           const Eigen::Ref<const Eigen::Vector3d>& a,
                                           const Eigen::Ref<const Eigen::Vector3d>& b,
                                           const Eigen::Ref<const Eigen::Vector3d>& c);

/// Region of the closest feature (as in point_triangle_closest).
PointTriangleRegion classify_point_triangle(const Eigen::Ref<const Eigen::Vector3d>& p,
                                            const Eigen::Ref<const Eigen::Vector3d>& a,
                                            const Eigen::Ref<const Eigen::Vector3d>& b,
                                            const Eigen::Ref<const Eigen::Vector3d>& c);

/// Squared distance (m^2) from p to the triangle (a, b, c).
double point_triangle_distance_squared(const Eigen::Ref<const Eigen::Vector3d>& p,
                                       const Eigen::Ref<const Eigen::Vector3d>& a,
                                       const Eigen::Ref<const Eigen::Vector3d>& b,
                                       const Eigen::Ref<const Eigen::Vector3d>& c);

/// Squared distance (m^2) of the region's smooth function: to the plane of (a, b, c) for Face,
/// to the infinite line through the edge for an edge region, to the vertex for a vertex
/// region. Equals point_triangle_distance_squared when region is the classified one.
double point_triangle_distance_squared(const Eigen::Ref<const Eigen::Vector3d>& p,
                                       const Eigen::Ref<const Eigen::Vector3d>& a,
                                       const Eigen::Ref<const Eigen::Vector3d>& b,
                                       const Eigen::Ref<const Eigen::Vector3d>& c,
                                       PointTriangleRegion region);

/// Gradient (m) of the region's squared distance with respect to (p, a, b, c).
Vector12d point_triangle_distance_squared_gradient(const Eigen::Ref<const Eigen::Vector3d>& p,
                                                   const Eigen::Ref<const Eigen::Vector3d>& a,
                                                   const Eigen::Ref<const Eigen::Vector3d>& b,
                                                   const Eigen::Ref<const Eigen::Vector3d>& c,
                                                   PointTriangleRegion region);

/// Hessian (dimensionless, symmetric) of the region's squared distance w.r.t. (p, a, b, c).
Matrix12d point_triangle_distance_squared_hessian(const Eigen::Ref<const Eigen::Vector3d>& p,
                                                  const Eigen::Ref<const Eigen::Vector3d>& a,
                                                  const Eigen::Ref<const Eigen::Vector3d>& b,
                                                  const Eigen::Ref<const Eigen::Vector3d>& c,
                                                  PointTriangleRegion region);

/// Value (m^2), gradient (m) and Hessian of the region's squared distance in one evaluation
/// (the three functions above each compute all of it, so an assembly loop should call this).
ValueGradientHessian<12> point_triangle_distance_squared_derivatives(
    const Eigen::Ref<const Eigen::Vector3d>& p, const Eigen::Ref<const Eigen::Vector3d>& a,
    const Eigen::Ref<const Eigen::Vector3d>& b, const Eigen::Ref<const Eigen::Vector3d>& c,
    PointTriangleRegion region);

// ---- Building blocks, also used by the edge-edge distance ----------------------------------

/// Derivatives of g(x) = f(u) where u is a constant linear map of x applied to whole points:
/// u_k = sum_m map(k, m) x_m for 3-vectors u_k (k < K) and x_m (m < M). Returns g's value,
/// gradient J^T grad f and Hessian J^T (Hess f) J with J = map (x) I_3.
template <int K, int M>
ValueGradientHessian<3 * M> pull_back_blockwise(const ValueGradientHessian<3 * K>& f,
                                                const Eigen::Matrix<double, K, M>& map) {
  Eigen::Matrix<double, 3 * K, 3 * M> jacobian = Eigen::Matrix<double, 3 * K, 3 * M>::Zero();
  for (int k = 0; k < K; ++k) {
    for (int m = 0; m < M; ++m) {
      jacobian.template block<3, 3>(3 * k, 3 * m).diagonal().setConstant(map(k, m));
    }
  }
  ValueGradientHessian<3 * M> g;
  g.value = f.value;
  g.gradient = jacobian.transpose() * f.gradient;
  g.hessian = jacobian.transpose() * f.hessian * jacobian;
  return g;
}

/// Selection map for pull_back_blockwise: local point k is point indices[k] of the four points
/// of a primitive pair ((p, a, b, c) or (p0, p1, q0, q1)).
template <int K>
Eigen::Matrix<double, K, 4> select_of_four(const std::array<int, K>& indices) {
  Eigen::Matrix<double, K, 4> map = Eigen::Matrix<double, K, 4>::Zero();
  for (int k = 0; k < K; ++k) map(k, indices[k]) = 1.0;
  return map;
}

/// Closest point x0 + t (x1 - x0), t in [0, 1], of a segment to x.
struct SegmentClosestPoint {
  double distance_squared;  ///< m^2
  double t;                 ///< exactly 0 or 1 when clamped to an endpoint
};

/// The closest point of the segment [x0, x1] to x. Requires x0 != x1 (not checked: callers
/// validate their primitives first). The perpendicular part is formed directly, not as
/// |r|^2 - (r.e)^2/|e|^2, which cancels when x is close to the line but far along it.
SegmentClosestPoint closest_point_on_segment(const Eigen::Ref<const Eigen::Vector3d>& x,
                                             const Eigen::Ref<const Eigen::Vector3d>& x0,
                                             const Eigen::Ref<const Eigen::Vector3d>& x1);

/// |x - y|^2 (m^2) with gradient and Hessian w.r.t. (x, y).
ValueGradientHessian<6> point_point_distance_squared_derivatives(
    const Eigen::Ref<const Eigen::Vector3d>& x, const Eigen::Ref<const Eigen::Vector3d>& y);

/// Squared distance (m^2) from p to the infinite line through x0 and x1, with derivatives
/// w.r.t. (p, x0, x1). Throws std::invalid_argument if x0 == x1 or a coordinate is not finite.
ValueGradientHessian<9> point_line_distance_squared_derivatives(
    const Eigen::Ref<const Eigen::Vector3d>& p, const Eigen::Ref<const Eigen::Vector3d>& x0,
    const Eigen::Ref<const Eigen::Vector3d>& x1);

/// Squared distance ((u x v) . w)^2 / |u x v|^2 (m^2) of the point w from the plane through the
/// origin spanned by u and v, with derivatives w.r.t. (w, u, v). The point-plane distance
/// (w = p - a, u = b - a, v = c - a) and the line-line distance (w = q0 - p0, u = p1 - p0,
/// v = q1 - q0) are this function composed with a constant linear map. Finite whenever
/// u x v != 0; throws std::invalid_argument if u x v = 0 exactly or a coordinate is not finite.
ValueGradientHessian<9> plane_distance_squared_derivatives(
    const Eigen::Ref<const Eigen::Vector3d>& w, const Eigen::Ref<const Eigen::Vector3d>& u,
    const Eigen::Ref<const Eigen::Vector3d>& v);

/// |u x v|^2 (m^4) with gradient (m^3) and Hessian (m^2) w.r.t. (u, v). The IPC edge-edge
/// mollifier is a function of it.
ValueGradientHessian<6> cross_norm_squared_derivatives(const Eigen::Ref<const Eigen::Vector3d>& u,
                                                       const Eigen::Ref<const Eigen::Vector3d>& v);

}  // namespace growshell
