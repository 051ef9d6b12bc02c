#include "libshell/contact/limit_surface_distance.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "libshell/subdivision/closest_limit_point.hpp"
#include "libshell/subdivision/limit_surface.hpp"

namespace growshell {
namespace {

constexpr double kOnSurfaceTolerance = 1e-12;
constexpr double kTieTolerance = 1e-12;

void check_vertex(int vertex, Eigen::Index rows, const char* what) {
  if (vertex < 0 || vertex >= rows)
    throw std::invalid_argument(std::string("limit_surface_distance: ") + what + " vertex " +
                                std::to_string(vertex) + " is outside the " +
                                std::to_string(rows) + " control points");
}

/// The directions along which the minimiser may move: the parameter plane, one side of the
/// triangle, or none.
Eigen::MatrixXd free_directions(int active) {
  const int count = (active & 1) + ((active >> 1) & 1) + ((active >> 2) & 1);
  if (count == 0) return Eigen::Matrix2d::Identity();
  if (count >= 2) return Eigen::MatrixXd(2, 0);
  Eigen::MatrixXd z(2, 1);
  if (active & kSideV0) z.col(0) = Eigen::Vector2d(0.0, 1.0);
  if (active & kSideW0) z.col(0) = Eigen::Vector2d(1.0, 0.0);
  if (active & kSideU0) z.col(0) = Eigen::Vector2d(1.0, -1.0) / std::sqrt(2.0);
  return z;
}

/// The closest point of the candidates' surface to p, and its element (-1 if no search
/// converged).
struct CandidateFoot {
  ClosestLimitPoint point;
  int element = -1;
};

CandidateFoot closest_on_candidates(const ControlPointRows& positions,
                                    const ElementPatches& patches, const Eigen::Vector3d& p,
                                    const std::vector<int>& candidates) {
  const Eigen::Index rows = positions.rows();
  CandidateFoot found;
  found.point.half_squared_distance = std::numeric_limits<double>::infinity();
  // Every candidate element, each searched from its centroid; the lowest distance wins. An
  // element's surface lies in the convex hull of its control points (the Loop weights and
  // subdivision masks are positive and sum to one), so the distance from the point to their
  // bounding box bounds its distance from below: elements are searched in the order of that
  // bound, and those whose bound exceeds the best distance found are left out (the answer is
  // the same; the searches, on irregular elements a subdivision per evaluation, are not).
  std::vector<std::pair<double, int>> order;
  order.reserve(candidates.size());
  for (int e : candidates) {
    const LoopPatch& patch = patches.patch[static_cast<std::size_t>(e)];
    Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d high = -low;
    for (int v : patch.control) {
      check_vertex(v, rows, "element");
      if (!positions.row(v).allFinite())
        throw std::invalid_argument("limit_surface_distance: control point " + std::to_string(v) +
                                    " of element " + std::to_string(e) + " is not finite");
      low = low.cwiseMin(positions.row(v).transpose());
      high = high.cwiseMax(positions.row(v).transpose());
    }
    const Eigen::Vector3d outside = (low - p).cwiseMax(p - high).cwiseMax(0.0);
    order.emplace_back(outside.norm(), e);
  }
  std::sort(order.begin(), order.end());
  for (const auto& [bound, e] : order) {
    // Strictly farther than the best, beyond what a tie (below) could still reach.
    if (found.element >= 0 &&
        bound * bound > 2.0 * found.point.half_squared_distance * (1.0 + 4.0 * kTieTolerance))
      break;
    const LoopPatch& patch = patches.patch[static_cast<std::size_t>(e)];
    const ClosestLimitPoint c =
        closest_limit_point(positions, patch, p, Eigen::Vector2d(1.0 / 3.0, 1.0 / 3.0));
    if (!c.converged) continue;
    bool better = found.element < 0;
    if (!better) {
      // Equal distances to rounding: a minimiser free inside its element before one held on
      // a side (the foot just across that side is the free one's, and the held point differs
      // from it to first order, though its distance only to second), then the lower element.
      const double tie =
          kTieTolerance * std::max(c.half_squared_distance, found.point.half_squared_distance);
      if (c.half_squared_distance < found.point.half_squared_distance - tie)
        better = true;
      else if (c.half_squared_distance <= found.point.half_squared_distance + tie)
        better = (c.active == 0) != (found.point.active == 0) ? c.active == 0 : e < found.element;
    }
    if (better) {
      found.point = c;
      found.element = e;
    }
  }
  return found;
}

}  // namespace

LimitSurfaceDistance limit_surface_distance(const ControlPointRows& positions,
                                            const ElementPatches& patches,
                                            const ControlPointCombination& point,
                                            const std::vector<int>& candidates, bool with_hessian) {
  if (candidates.empty())
    throw std::invalid_argument("limit_surface_distance: no candidate elements");
  if (point.vertex.empty() || point.vertex.size() != point.weight.size())
    throw std::invalid_argument("limit_surface_distance: the point has " +
                                std::to_string(point.vertex.size()) + " vertices and " +
                                std::to_string(point.weight.size()) +
                                " weights (it needs as many of each, at least one)");
  const Eigen::Index rows = positions.rows();
  const auto elements = static_cast<int>(patches.patch.size());
  for (int e : candidates)
    if (e < 0 || e >= elements)
      throw std::invalid_argument("limit_surface_distance: candidate element " +
                                  std::to_string(e) + " is outside the " +
                                  std::to_string(elements) + " elements");
  // The point's vertices first (repeated vertices merged), then the elements'.
  LimitSurfaceDistance result;
  std::vector<double> weight_in_r;
  const auto local_index = [&](int vertex) {
    for (std::size_t k = 0; k < result.vertices.size(); ++k)
      if (result.vertices[k] == vertex) return static_cast<int>(k);
    result.vertices.push_back(vertex);
    weight_in_r.push_back(0.0);
    return static_cast<int>(result.vertices.size() - 1);
  };
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < point.vertex.size(); ++k) {
    check_vertex(point.vertex[k], rows, "point");
    if (!positions.row(point.vertex[k]).allFinite() || !std::isfinite(point.weight[k]))
      throw std::invalid_argument("limit_surface_distance: the point's vertex " +
                                  std::to_string(point.vertex[k]) +
                                  " or its weight is not finite");
    p += point.weight[k] * positions.row(point.vertex[k]).transpose();
    weight_in_r[static_cast<std::size_t>(local_index(point.vertex[k]))] += point.weight[k];
  }

  const CandidateFoot found = closest_on_candidates(positions, patches, p, candidates);
  const ClosestLimitPoint& best = found.point;
  result.element = found.element;
  if (result.element < 0)
    throw std::domain_error("limit_surface_distance: the closest-point search converged on none "
                            "of the " + std::to_string(candidates.size()) + " candidate elements");
  result.point = p;
  result.closest = best.position;
  result.parameter = best.parameter;
  result.active = best.active;
  const Eigen::Vector3d r = p - best.position;
  result.distance = r.norm();
  // On the surface to within the rounding of the positions: no direction to differentiate.
  if (!(result.distance > kOnSurfaceTolerance * std::max(p.cwiseAbs().maxCoeff(),
                                                          best.position.cwiseAbs().maxCoeff())))
    throw std::domain_error("limit_surface_distance: the point lies on the surface (element " +
                            std::to_string(result.element) +
                            "), where the distance is not differentiable");

  const LoopPatch& patch = patches.patch[static_cast<std::size_t>(result.element)];
  const PatchBasis basis = evaluate_patch_basis(patch, best.parameter.x(), best.parameter.y());
  std::vector<int> patch_local(patch.control.size());
  for (std::size_t a = 0; a < patch.control.size(); ++a) {
    patch_local[a] = local_index(patch.control[a]);
    weight_in_r[static_cast<std::size_t>(patch_local[a])] -= basis.value(static_cast<Eigen::Index>(a));
  }
  const auto m = static_cast<Eigen::Index>(result.vertices.size());
  result.gradient.resize(3 * m);
  for (Eigen::Index j = 0; j < m; ++j)
    result.gradient.segment<3>(3 * j) = weight_in_r[static_cast<std::size_t>(j)] * r / result.distance;
  if (!with_hessian) return result;

  const LimitSurfacePoint s = evaluate_limit_surface(positions, patch, basis);
  Eigen::Matrix2d a = s.metric;
  a(0, 0) -= r.dot(s.second.col(0));
  a(1, 1) -= r.dot(s.second.col(1));
  a(0, 1) -= r.dot(s.second.col(2));
  a(1, 0) = a(0, 1);
  // B = d2D / dxi dX (2 x 3m): -(c_j x_a + N_j,a r) for each control point j.
  Eigen::MatrixXd b(2, 3 * m);
  for (Eigen::Index j = 0; j < m; ++j)
    for (int alpha = 0; alpha < 2; ++alpha)
      b.block<1, 3>(alpha, 3 * j) =
          -weight_in_r[static_cast<std::size_t>(j)] * s.tangents.col(alpha).transpose();
  for (std::size_t k = 0; k < patch.control.size(); ++k)
    for (int alpha = 0; alpha < 2; ++alpha)
      b.block<1, 3>(alpha, 3 * patch_local[k]) -=
          basis.first(static_cast<Eigen::Index>(k), alpha) * r.transpose();
  Eigen::MatrixXd hessian_d(3 * m, 3 * m);
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::Index k = 0; k < m; ++k)
      hessian_d.block<3, 3>(3 * j, 3 * k) = weight_in_r[static_cast<std::size_t>(j)] *
                                            weight_in_r[static_cast<std::size_t>(k)] *
                                            Eigen::Matrix3d::Identity();
  const Eigen::MatrixXd z = free_directions(result.active);
  if (z.cols() > 0) {
    const Eigen::MatrixXd az = z.transpose() * a * z;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(az, Eigen::EigenvaluesOnly);
    if (!(eig.eigenvalues().minCoeff() > 1e-12 * s.metric.norm()))
      throw std::domain_error(
          "limit_surface_distance: the closest point on element " +
          std::to_string(result.element) +
          " is degenerate (the point lies at or beyond a focal point of the surface)");
    const Eigen::MatrixXd bz = z.transpose() * b;
    hessian_d -= bz.transpose() * az.ldlt().solve(bz);
  }
  result.hessian =
      (hessian_d - result.gradient * result.gradient.transpose()) / result.distance;
  return result;
}

}  // namespace growshell
