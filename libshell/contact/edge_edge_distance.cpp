#include "libshell/contact/edge_edge_distance.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace growshell {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void require_valid_edges(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                         const Vector3d& q1, const char* function) {
  const std::array<const Vector3d*, 4> points = {&p0, &p1, &q0, &q1};
  const std::array<const char*, 4> names = {"p0", "p1", "q0", "q1"};
  for (int i = 0; i < 4; ++i) {
    if (!points[i]->allFinite()) {
      throw std::invalid_argument(std::string(function) + ": point " + names[i] +
                                  " has a non-finite coordinate " + format_point(*points[i]));
    }
  }
  // Subtraction of distinct doubles is never exactly zero, so == is the exact test here.
  if (p0 == p1) {
    throw std::invalid_argument(std::string(function) +
                                ": edge (p0, p1) has zero length (both at " + format_point(p0) +
                                ")");
  }
  if (q0 == q1) {
    throw std::invalid_argument(std::string(function) +
                                ": edge (q0, q1) has zero length (both at " + format_point(q0) +
                                ")");
  }
}

ValueGradientHessian<12> region_derivatives(const Vector3d& p0, const Vector3d& p1,
                                            const Vector3d& q0, const Vector3d& q1,
                                            EdgeEdgeRegion region, const char* function) {
  using R = EdgeEdgeRegion;
  switch (region) {
    case R::EdgeEdge: {
      if ((p1 - p0).cross(q1 - q0).squaredNorm() == 0.0) {
        throw std::invalid_argument(
            std::string(function) +
            ": edges (p0, p1) and (q0, q1) are exactly parallel, so the line-line distance "
            "(region EdgeEdge) is undefined; classify_edge_edge never returns it for them");
      }
      // (w, u, v) = (q0 - p0, p1 - p0, q1 - q0) from (p0, p1, q0, q1).
      Eigen::Matrix<double, 3, 4> map;
      map << -1, 0, 1, 0,  //
          -1, 1, 0, 0,     //
          0, 0, -1, 1;
      return pull_back_blockwise<3, 4>(
          plane_distance_squared_derivatives(q0 - p0, p1 - p0, q1 - q0), map);
    }
    case R::P0EdgeQ:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(p0, q0, q1),
                                       select_of_four<3>({0, 2, 3}));
    case R::P1EdgeQ:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(p1, q0, q1),
                                       select_of_four<3>({1, 2, 3}));
    case R::Q0EdgeP:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(q0, p0, p1),
                                       select_of_four<3>({2, 0, 1}));
    case R::Q1EdgeP:
      return pull_back_blockwise<3, 4>(point_line_distance_squared_derivatives(q1, p0, p1),
                                       select_of_four<3>({3, 0, 1}));
    case R::P0Q0:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p0, q0), select_of_four<2>({0, 2}));
    case R::P0Q1:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p0, q1), select_of_four<2>({0, 3}));
    case R::P1Q0:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p1, q0), select_of_four<2>({1, 2}));
    case R::P1Q1:
      return pull_back_blockwise<2, 4>(point_point_distance_squared_derivatives(p1, q1), select_of_four<2>({1, 3}));
  }
  throw std::invalid_argument(std::string(function) + ": region value " +
                              std::to_string(static_cast<int>(region)) +
                              " is not an EdgeEdgeRegion (allowed 0..8)");
}

/// Mollifier m(c) and its first two derivatives in c.
struct MollifierPoint {
  bool active;  ///< c < eps_x; otherwise m = 1 and both derivatives vanish
  double value, first, second;
};

MollifierPoint mollifier_of(const Vector3d& p0, const Vector3d& p1, const Vector3d& q0,
                            const Vector3d& q1, double eps_x, const char* function) {
  require_valid_edges(p0, p1, q0, q1, function);
  if (!(eps_x > 0.0) || !std::isfinite(eps_x)) {
    std::ostringstream s;
    s << function << ": mollifier threshold eps_x = " << eps_x << " must be finite and > 0";
    throw std::invalid_argument(s.str());
  }
  const double c = (p1 - p0).cross(q1 - q0).squaredNorm();
  if (c >= eps_x) return {false, 1.0, 0.0, 0.0};
  const double x = c / eps_x;
  return {true, (2.0 - x) * x, 2.0 * (1.0 - x) / eps_x, -2.0 / (eps_x * eps_x)};
}

ValueGradientHessian<12> cross_norm_in_edge_dofs(const Vector3d& p0, const Vector3d& p1,
                                                 const Vector3d& q0, const Vector3d& q1) {
  Eigen::Matrix<double, 2, 4> map;  // (u, v) = (p1 - p0, q1 - q0) from (p0, p1, q0, q1)
  map << -1, 1, 0, 0,               //
      0, 0, -1, 1;
  return pull_back_blockwise<2, 4>(cross_norm_squared_derivatives(p1 - p0, q1 - q0), map);
}

}  // namespace

const char* to_string(EdgeEdgeRegion region) {
  switch (region) {
    case EdgeEdgeRegion::EdgeEdge:
      return "EdgeEdge";
    case EdgeEdgeRegion::P0EdgeQ:
      return "P0EdgeQ";
    case EdgeEdgeRegion::P1EdgeQ:
      return "P1EdgeQ";
    case EdgeEdgeRegion::Q0EdgeP:
      return "Q0EdgeP";
    case EdgeEdgeRegion::Q1EdgeP:
      return "Q1EdgeP";
    case EdgeEdgeRegion::P0Q0:
      return "P0Q0";
    case EdgeEdgeRegion::P0Q1:
      return "P0Q1";
    case EdgeEdgeRegion::P1Q0:
      return "P1Q0";
    case EdgeEdgeRegion::P1Q1:
      return "P1Q1";
  }
  return "invalid EdgeEdgeRegion";
}

EdgeEdgeResult edge_edge_closest(const Eigen::Ref<const Vector3d>& p0_in,
                                 const Eigen::Ref<const Vector3d>& p1_in,
                                 const Eigen::Ref<const Vector3d>& q0_in,
                                 const Eigen::Ref<const Vector3d>& q1_in) {
  const Vector3d p0 = p0_in, p1 = p1_in, q0 = q0_in, q1 = q1_in;
  require_valid_edges(p0, p1, q0, q1, "edge_edge_closest");
  const Vector3d e0 = p1 - p0;
  const Vector3d e1 = q1 - q0;
  const Vector3d n = e0.cross(e1);
  const double cross_squared = n.squaredNorm();
  EdgeEdgeResult result;

  if (cross_squared >= kParallelEdgeTolerance * e0.squaredNorm() * e1.squaredNorm()) {
    // Stationary point of |p0 + s e0 - q0 - t e1|^2: the difference is a multiple of n, and
    // crossing that condition with e1 (resp. e0) and dotting with n isolates s (resp. t). The
    // cross-product form avoids the cancellation in |e0|^2 |e1|^2 - (e0.e1)^2.
    const Vector3d w = q0 - p0;
    const double s = w.cross(e1).dot(n) / cross_squared;
    const double t = w.cross(e0).dot(n) / cross_squared;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
      // The squared distance is strictly convex in (s, t) here, so this is the minimum.
      const double h = n.dot(w);
      result.region = EdgeEdgeRegion::EdgeEdge;
      result.distance_squared = h * h / cross_squared;
      result.s = s;
      result.t = t;
      result.closest_point_p = p0 + s * e0;
      result.closest_point_q = q0 + t * e1;
      return result;
    }
  }

  // Otherwise the minimum over the parameter square lies on its boundary (for parallel edges
  // too: the function is then constant along a direction that reaches the boundary), i.e. at
  // an endpoint of one edge against the other segment.
  using R = EdgeEdgeRegion;
  struct Candidate {
    const Vector3d* point;
    const Vector3d* x0;
    const Vector3d* x1;
    bool point_on_p;  // the endpoint belongs to P (it is then the segment Q that is clamped)
    double endpoint;  // parameter of the endpoint on its own edge
    R interior, start, end;
  };
  const Candidate candidates[4] = {{&p0, &q0, &q1, true, 0.0, R::P0EdgeQ, R::P0Q0, R::P0Q1},
                                   {&p1, &q0, &q1, true, 1.0, R::P1EdgeQ, R::P1Q0, R::P1Q1},
                                   {&q0, &p0, &p1, false, 0.0, R::Q0EdgeP, R::P0Q0, R::P1Q0},
                                   {&q1, &p0, &p1, false, 1.0, R::Q1EdgeP, R::P0Q1, R::P1Q1}};
  result.distance_squared = std::numeric_limits<double>::infinity();
  for (const Candidate& candidate : candidates) {
    const SegmentClosestPoint hit = closest_point_on_segment(*candidate.point, *candidate.x0, *candidate.x1);
    if (!(hit.distance_squared < result.distance_squared)) continue;
    result.distance_squared = hit.distance_squared;
    result.region =
        hit.t == 0.0 ? candidate.start : (hit.t == 1.0 ? candidate.end : candidate.interior);
    result.s = candidate.point_on_p ? candidate.endpoint : hit.t;
    result.t = candidate.point_on_p ? hit.t : candidate.endpoint;
  }
  result.closest_point_p = p0 + result.s * e0;
  result.closest_point_q = q0 + result.t * e1;
  return result;
}

EdgeEdgeRegion classify_edge_edge(const Eigen::Ref<const Vector3d>& p0,
                                  const Eigen::Ref<const Vector3d>& p1,
                                  const Eigen::Ref<const Vector3d>& q0,
                                  const Eigen::Ref<const Vector3d>& q1) {
  return edge_edge_closest(p0, p1, q0, q1).region;
}

double edge_edge_distance_squared(const Eigen::Ref<const Vector3d>& p0,
                                  const Eigen::Ref<const Vector3d>& p1,
                                  const Eigen::Ref<const Vector3d>& q0,
                                  const Eigen::Ref<const Vector3d>& q1) {
  return edge_edge_closest(p0, p1, q0, q1).distance_squared;
}

double edge_edge_distance_squared(const Eigen::Ref<const Vector3d>& p0,
                                  const Eigen::Ref<const Vector3d>& p1,
                                  const Eigen::Ref<const Vector3d>& q0,
                                  const Eigen::Ref<const Vector3d>& q1, EdgeEdgeRegion region) {
  const char* function = "edge_edge_distance_squared";
  require_valid_edges(p0, p1, q0, q1, function);
  return region_derivatives(p0, p1, q0, q1, region, function).value;
}

Vector12d edge_edge_distance_squared_gradient(const Eigen::Ref<const Vector3d>& p0,
                                              const Eigen::Ref<const Vector3d>& p1,
                                              const Eigen::Ref<const Vector3d>& q0,
                                              const Eigen::Ref<const Vector3d>& q1,
                                              EdgeEdgeRegion region) {
  const char* function = "edge_edge_distance_squared_gradient";
  require_valid_edges(p0, p1, q0, q1, function);
  return region_derivatives(p0, p1, q0, q1, region, function).gradient;
}

Matrix12d edge_edge_distance_squared_hessian(const Eigen::Ref<const Vector3d>& p0,
                                             const Eigen::Ref<const Vector3d>& p1,
                                             const Eigen::Ref<const Vector3d>& q0,
                                             const Eigen::Ref<const Vector3d>& q1,
                                             EdgeEdgeRegion region) {
  const char* function = "edge_edge_distance_squared_hessian";
  require_valid_edges(p0, p1, q0, q1, function);
  return region_derivatives(p0, p1, q0, q1, region, function).hessian;
}

ValueGradientHessian<12> edge_edge_distance_squared_derivatives(
    const Eigen::Ref<const Vector3d>& p0, const Eigen::Ref<const Vector3d>& p1,
    const Eigen::Ref<const Vector3d>& q0, const Eigen::Ref<const Vector3d>& q1,
    EdgeEdgeRegion region) {
  const char* function = "edge_edge_distance_squared_derivatives";
  require_valid_edges(p0, p1, q0, q1, function);
  return region_derivatives(p0, p1, q0, q1, region, function);
}

double edge_edge_mollifier_threshold(const Eigen::Ref<const Vector3d>& p0_rest,
                                     const Eigen::Ref<const Vector3d>& p1_rest,
                                     const Eigen::Ref<const Vector3d>& q0_rest,
                                     const Eigen::Ref<const Vector3d>& q1_rest) {
  require_valid_edges(p0_rest, p1_rest, q0_rest, q1_rest, "edge_edge_mollifier_threshold");
  return kEdgeEdgeMollifierScale * (p1_rest - p0_rest).squaredNorm() *
         (q1_rest - q0_rest).squaredNorm();
}

double edge_edge_mollifier(const Eigen::Ref<const Vector3d>& p0,
                           const Eigen::Ref<const Vector3d>& p1,
                           const Eigen::Ref<const Vector3d>& q0,
                           const Eigen::Ref<const Vector3d>& q1, double eps_x) {
  return mollifier_of(p0, p1, q0, q1, eps_x, "edge_edge_mollifier").value;
}

Vector12d edge_edge_mollifier_gradient(const Eigen::Ref<const Vector3d>& p0,
                                       const Eigen::Ref<const Vector3d>& p1,
                                       const Eigen::Ref<const Vector3d>& q0,
                                       const Eigen::Ref<const Vector3d>& q1, double eps_x) {
  const MollifierPoint m = mollifier_of(p0, p1, q0, q1, eps_x, "edge_edge_mollifier_gradient");
  if (!m.active) return Vector12d::Zero();
  return m.first * cross_norm_in_edge_dofs(p0, p1, q0, q1).gradient;
}

Matrix12d edge_edge_mollifier_hessian(const Eigen::Ref<const Vector3d>& p0,
                                      const Eigen::Ref<const Vector3d>& p1,
                                      const Eigen::Ref<const Vector3d>& q0,
                                      const Eigen::Ref<const Vector3d>& q1, double eps_x) {
  const MollifierPoint m = mollifier_of(p0, p1, q0, q1, eps_x, "edge_edge_mollifier_hessian");
  if (!m.active) return Matrix12d::Zero();
  const ValueGradientHessian<12> c = cross_norm_in_edge_dofs(p0, p1, q0, q1);
  return m.second * c.gradient * c.gradient.transpose() + m.first * c.hessian;
}

}  // namespace growshell
