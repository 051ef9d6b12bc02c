#include "libshell/contact/point_triangle_distance.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace growshell {

std::string format_point(const Eigen::Ref<const Eigen::Vector3d>& x) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return s.str();
}

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

/// Skew matrix [x]_x with [x]_x y = x cross y.
Matrix3d skew(const Vector3d& x) {
  Matrix3d s;
  s << 0.0, -x.z(), x.y(), x.z(), 0.0, -x.x(), -x.y(), x.x(), 0.0;
  return s;
}

void require_finite(const Vector3d& x, const char* function, const char* name) {
  if (!x.allFinite()) {
    throw std::invalid_argument(std::string(function) + ": point " + name +
                                " has a non-finite coordinate " + format_point(x));
  }
}

void require_valid_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                            const Vector3d& c, const char* function) {
  require_finite(p, function, "p");
  require_finite(a, function, "a");
  require_finite(b, function, "b");
  require_finite(c, function, "c");
  const double twice_area = (b - a).cross(c - a).norm();
  const double longest_squared =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  // Written as !(x > y) so that a NaN from overflow also counts as degenerate.
  if (!(twice_area > kDegenerateTriangleTolerance * longest_squared)) {
    std::ostringstream s;
    s << function << ": triangle (a, b, c) = (" << format_point(a) << ", " << format_point(b)
      << ", " << format_point(c) << ") has zero area: |(b - a) x (c - a)| = " << twice_area
      << " <= " << kDegenerateTriangleTolerance
      << " * (longest edge)^2 = " << kDegenerateTriangleTolerance * longest_squared;
    throw std::invalid_argument(s.str());
  }
}

ValueGradientHessian<12> region_derivatives(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                            const Vector3d& c, PointTriangleRegion region) {
  using R = PointTriangleRegion;
  switch (region) {
    case R::Face: {
      // (w, u, v) = (p - a, b - a, c - a) from (p, a, b, c).
      Eigen::Matrix<double, 3, 4> map;
      map << 1, -1, 0, 0,  //
          0, -1, 1, 0,     //
          0, -1, 0, 1;
      return pull_back_blockwise<3, 4>(plane_distance_squared_derivatives(p - a, b - a, c - a),
                                       map);
    }
    case R::EdgeAB:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(p, a, b),
                                       select_of_four<3>({0, 1, 2}));
    case R::EdgeBC:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(p, b, c),
                                       select_of_four<3>({0, 2, 3}));
    case R::EdgeCA:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(p, c, a),
                                       select_of_four<3>({0, 3, 1}));
    case R::VertexA:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p, a), select_of_four<2>({0, 1}));
    case R::VertexB:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p, b), select_of_four<2>({0, 2}));
    case R::VertexC:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p, c), select_of_four<2>({0, 3}));
  }
  throw std::invalid_argument("point_triangle: region value " +
                              std::to_string(static_cast<int>(region)) +
                              " is not a PointTriangleRegion (allowed 0..6)");
}

}  // namespace

const char* to_string(PointTriangleRegion region) {
  switch (region) {
    case PointTriangleRegion::Face:
      return "Face";
    case PointTriangleRegion::EdgeAB:
      return "EdgeAB";
    case PointTriangleRegion::EdgeBC:
      return "EdgeBC";
    case PointTriangleRegion::EdgeCA:
      return "EdgeCA";
    case PointTriangleRegion::VertexA:
      return "VertexA";
    case PointTriangleRegion::VertexB:
      return "VertexB";
    case PointTriangleRegion::VertexC:
      return "VertexC";
  }
  return "invalid PointTriangleRegion";
}

PointTriangleResult point_triangle_closest(const Eigen::Ref<const Vector3d>& p_in,
                                           const Eigen::Ref<const Vector3d>& a_in,
                                           const Eigen::Ref<const Vector3d>& b_in,
                                           const Eigen::Ref<const Vector3d>& c_in) {
  const Vector3d p = p_in, a = a_in, b = b_in, c = c_in;
  require_valid_triangle(p, a, b, c, "point_triangle_closest");
  const Vector3d n = (b - a).cross(c - a);
  const double m = n.squaredNorm();

  // Barycentric coordinates of the projection, times |n|^2: signed areas of the sub-triangles
  // opposite each vertex. Their signs decide inside/outside without dividing by a small |n|^2,
  // which keeps slivers robust; a projection on the boundary counts as Face.
  const double wa = (c - b).cross(p - b).dot(n);
  const double wb = (a - c).cross(p - c).dot(n);
  const double wc = (b - a).cross(p - a).dot(n);
  PointTriangleResult result;
  if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) {
    const double h = n.dot(p - a);
    result.region = PointTriangleRegion::Face;
    result.distance_squared = h * h / m;
    result.closest_point = p - (h / m) * n;
    result.barycentric = Vector3d(wa, wb, wc) / (wa + wb + wc);
    return result;
  }

  // Projection outside: the closest point of a convex set lies on its boundary, i.e. on the
  // nearest of the three edge segments.
  using R = PointTriangleRegion;
  struct Edge {
    const Vector3d* x0;
    const Vector3d* x1;
    int i0, i1;  // barycentric slots of x0, x1
    R interior, start, end;
  };
  const Edge edges[3] = {{&a, &b, 0, 1, R::EdgeAB, R::VertexA, R::VertexB},
                         {&b, &c, 1, 2, R::EdgeBC, R::VertexB, R::VertexC},
                         {&c, &a, 2, 0, R::EdgeCA, R::VertexC, R::VertexA}};
  result.distance_squared = std::numeric_limits<double>::infinity();
  for (const Edge& edge : edges) {
    const SegmentClosestPoint hit = closest_point_on_segment(p, *edge.x0, *edge.x1);
    if (!(hit.distance_squared < result.distance_squared)) continue;
    result.distance_squared = hit.distance_squared;
    result.region = hit.t == 0.0 ? edge.start : (hit.t == 1.0 ? edge.end : edge.interior);
    result.barycentric.setZero();
    result.barycentric(edge.i0) = 1.0 - hit.t;
    result.barycentric(edge.i1) = hit.t;
    result.closest_point = *edge.x0 + hit.t * (*edge.x1 - *edge.x0);
  }
  return result;
}

PointTriangleRegion classify_point_triangle(const Eigen::Ref<const Vector3d>& p,
                                            const Eigen::Ref<const Vector3d>& a,
                                            const Eigen::Ref<const Vector3d>& b,
                                            const Eigen::Ref<const Vector3d>& c) {
  return point_triangle_closest(p, a, b, c).region;
}

double point_triangle_distance_squared(const Eigen::Ref<const Vector3d>& p,
                                       const Eigen::Ref<const Vector3d>& a,
                                       const Eigen::Ref<const Vector3d>& b,
                                       const Eigen::Ref<const Vector3d>& c) {
  return point_triangle_closest(p, a, b, c).distance_squared;
}

double point_triangle_distance_squared(const Eigen::Ref<const Vector3d>& p,
                                       const Eigen::Ref<const Vector3d>& a,
                                       const Eigen::Ref<const Vector3d>& b,
                                       const Eigen::Ref<const Vector3d>& c,
                                       PointTriangleRegion region) {
  require_valid_triangle(p, a, b, c, "point_triangle_distance_squared");
  return region_derivatives(p, a, b, c, region).value;
}

Vector12d point_triangle_distance_squared_gradient(const Eigen::Ref<const Vector3d>& p,
                                                   const Eigen::Ref<const Vector3d>& a,
                                                   const Eigen::Ref<const Vector3d>& b,
                                                   const Eigen::Ref<const Vector3d>& c,
                                                   PointTriangleRegion region) {
  require_valid_triangle(p, a, b, c, "point_triangle_distance_squared_gradient");
  return region_derivatives(p, a, b, c, region).gradient;
}

Matrix12d point_triangle_distance_squared_hessian(const Eigen::Ref<const Vector3d>& p,
                                                  const Eigen::Ref<const Vector3d>& a,
                                                  const Eigen::Ref<const Vector3d>& b,
                                                  const Eigen::Ref<const Vector3d>& c,
                                                  PointTriangleRegion region) {
  require_valid_triangle(p, a, b, c, "point_triangle_distance_squared_hessian");
  return region_derivatives(p, a, b, c, region).hessian;
}

ValueGradientHessian<12> point_triangle_distance_squared_derivatives(
    const Eigen::Ref<const Vector3d>& p, const Eigen::Ref<const Vector3d>& a,
    const Eigen::Ref<const Vector3d>& b, const Eigen::Ref<const Vector3d>& c,
    PointTriangleRegion region) {
  require_valid_triangle(p, a, b, c, "point_triangle_distance_squared_derivatives");
  return region_derivatives(p, a, b, c, region);
}

ValueGradientHessian<9> point_line_distance_squared_derivatives(
    const Eigen::Ref<const Vector3d>& p, const Eigen::Ref<const Vector3d>& x0,
    const Eigen::Ref<const Vector3d>& x1) {
  const char* function = "point_line_distance_squared_derivatives";
  require_finite(p, function, "p");
  require_finite(x0, function, "x0");
  require_finite(x1, function, "x1");
  // In (r, e) = (p - x0, x1 - x0) with t = r.e / e.e, r_perp = r - t e, P = I - e e^T / e.e:
  //   f = |r_perp|^2,  df/dr = 2 r_perp,  df/de = -2 t r_perp,
  //   d2f/dr2 = 2 P,   d2f/dr de = -2 t P - 2 e r_perp^T / e.e,
  //   d2f/de2 = 2 t^2 P + 2 t (r_perp e^T + e r_perp^T) / e.e - 2 r_perp r_perp^T / e.e.
  const Vector3d e = x1 - x0;
  const double q = e.squaredNorm();
  if (!(q > 0.0)) {
    throw std::invalid_argument(std::string(function) + ": line points x0 and x1 coincide at " +
                                format_point(x0) + ", so the line is undefined");
  }
  const Vector3d r = p - x0;
  const double t = r.dot(e) / q;
  const Vector3d r_perp = r - t * e;
  const Matrix3d P = Matrix3d::Identity() - e * e.transpose() / q;

  ValueGradientHessian<6> f;
  f.value = r_perp.squaredNorm();
  f.gradient << 2.0 * r_perp, -2.0 * t * r_perp;
  const Matrix3d h_re = -2.0 * t * P - 2.0 * e * r_perp.transpose() / q;
  const Matrix3d h_ee = 2.0 * t * t * P +
                        2.0 * t * (r_perp * e.transpose() + e * r_perp.transpose()) / q -
                        2.0 * r_perp * r_perp.transpose() / q;
  f.hessian << 2.0 * P, h_re, h_re.transpose(), h_ee;

  Eigen::Matrix<double, 2, 3> map;  // (r, e) from (p, x0, x1)
  map << 1, -1, 0,                  //
      0, -1, 1;
  return pull_back_blockwise<2, 3>(f, map);
}

ValueGradientHessian<6> cross_norm_squared_derivatives(const Eigen::Ref<const Vector3d>& u,
                                                       const Eigen::Ref<const Vector3d>& v) {
  // n = u x v, dn/du = -[v]_x, dn/dv = [u]_x, d2 n_k / du_i dv_j = eps_kij.
  //   d|n|^2/du = 2 v x n, d|n|^2/dv = 2 n x u,
  //   d2/du2 = 2 (|v|^2 I - v v^T), d2/dv2 = 2 (|u|^2 I - u u^T),
  //   d2/du dv = 2 [v]_x [u]_x - 2 [n]_x = 2 (u v^T - (u.v) I) - 2 [n]_x.
  const Vector3d n = u.cross(v);
  ValueGradientHessian<6> f;
  f.value = n.squaredNorm();
  f.gradient << 2.0 * v.cross(n), 2.0 * n.cross(u);
  const Matrix3d I = Matrix3d::Identity();
  const Matrix3d h_uv = 2.0 * (u * v.transpose() - u.dot(v) * I) - 2.0 * skew(n);
  f.hessian << 2.0 * (v.squaredNorm() * I - v * v.transpose()), h_uv, h_uv.transpose(),
      2.0 * (u.squaredNorm() * I - u * u.transpose());
  return f;
}

ValueGradientHessian<9> plane_distance_squared_derivatives(const Eigen::Ref<const Vector3d>& w,
                                                           const Eigen::Ref<const Vector3d>& u,
                                                           const Eigen::Ref<const Vector3d>& v) {
  const char* function = "plane_distance_squared_derivatives";
  require_finite(w, function, "w");
  require_finite(u, function, "u");
  require_finite(v, function, "v");
  // f = h^2 / m with h = (u x v) . w and m = |u x v|^2. With k = h / m and
  // s = grad h - k grad m:
  //   grad f = 2 k grad h - k^2 grad m,
  //   Hess f = 2 s s^T / m + 2 k Hess h - k^2 Hess m,
  // which is the quotient rule regrouped around s.
  const Vector3d n = u.cross(v);
  const double m = n.squaredNorm();
  if (!(m > 0.0)) {
    throw std::invalid_argument(std::string(function) + ": spanning vectors u " + format_point(u) +
                                " and v " + format_point(v) +
                                " are parallel, so the plane is undefined");
  }
  const double h = n.dot(w);
  const double k = h / m;

  Vector9d grad_h;
  grad_h << n, v.cross(w), w.cross(u);
  Matrix9d hess_h = Matrix9d::Zero();  // h is linear in each of w, u, v separately
  hess_h.block<3, 3>(0, 3) = -skew(v);
  hess_h.block<3, 3>(0, 6) = skew(u);
  hess_h.block<3, 3>(3, 6) = -skew(w);
  hess_h.block<3, 3>(3, 0) = hess_h.block<3, 3>(0, 3).transpose();
  hess_h.block<3, 3>(6, 0) = hess_h.block<3, 3>(0, 6).transpose();
  hess_h.block<3, 3>(6, 3) = hess_h.block<3, 3>(3, 6).transpose();

  const ValueGradientHessian<6> cross = cross_norm_squared_derivatives(u, v);
  Vector9d grad_m = Vector9d::Zero();
  grad_m.tail<6>() = cross.gradient;
  Matrix9d hess_m = Matrix9d::Zero();
  hess_m.bottomRightCorner<6, 6>() = cross.hessian;

  ValueGradientHessian<9> f;
  f.value = h * k;
  f.gradient = 2.0 * k * grad_h - k * k * grad_m;
  const Vector9d s = grad_h - k * grad_m;
  f.hessian = 2.0 * s * s.transpose() / m + 2.0 * k * hess_h - k * k * hess_m;
  return f;
}

SegmentClosestPoint closest_point_on_segment(const Eigen::Ref<const Eigen::Vector3d>& x,
                                             const Eigen::Ref<const Eigen::Vector3d>& x0,
                                             const Eigen::Ref<const Eigen::Vector3d>& x1) {
  const Vector3d e = x1 - x0;
  const Vector3d r = x - x0;
  const double t = r.dot(e) / e.squaredNorm();
  if (t <= 0.0) return {r.squaredNorm(), 0.0};
  if (t >= 1.0) return {(x - x1).squaredNorm(), 1.0};
  return {(r - t * e).squaredNorm(), t};
}

ValueGradientHessian<6> point_point_distance_squared_derivatives(
    const Eigen::Ref<const Eigen::Vector3d>& x, const Eigen::Ref<const Eigen::Vector3d>& y) {
  ValueGradientHessian<6> f;
  const Vector3d r = x - y;
  f.value = r.squaredNorm();
  f.gradient << 2.0 * r, -2.0 * r;
  const Matrix3d I = 2.0 * Matrix3d::Identity();
  f.hessian << I, -I, -I, I;
  return f;
}

}  // namespace growshell
