#include "libshell/contact/straight_path_crossing.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libshell/contact/near_contact_pairs.hpp"

namespace growshell {
namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

/// Rows p, a, b, c at time tau.
Corners corners_at(const Corners& start, const Corners& end, double tau) {
  return start + tau * (end - start);
}

/// (p - a) . ((b - a) x (c - a)) at time tau.
double signed_volume(const Corners& start, const Corners& end, double tau) {
  const Corners q = corners_at(start, end, tau);
  const Eigen::Vector3d p = q.row(0), a = q.row(1), b = q.row(2), c = q.row(3);
  return (p - a).dot((b - a).cross(c - a));
}

/// Whether p lies in the triangle (a, b, c) it is coplanar with: its barycentric coordinates,
/// from the projection onto the triangle's plane, are all >= -tolerance. A triangle without
/// area holds nothing.
bool inside_triangle(const Corners& q) {
  const Eigen::Vector3d p = q.row(0), a = q.row(1), b = q.row(2), c = q.row(3);
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  if (!(area2 > 0.0)) return false;
  // Twice the signed areas of the sub-triangles opposite each corner, against the normal.
  const double wa = (b - p).cross(c - p).dot(n) / area2;
  const double wb = (c - p).cross(a - p).dot(n) / area2;
  const double wc = (a - p).cross(b - p).dot(n) / area2;
  // A vertex passing through the shared edge of two triangles must be caught by one of them
  // whatever the rounding of the root.
  constexpr double kTolerance = 1e-9;
  return wa >= -kTolerance && wb >= -kTolerance && wc >= -kTolerance;
}

}  // namespace

std::optional<double> vertex_triangle_crossing_time(const Corners& start, const Corners& end) {
  // The cubic f(tau) from its values at 0, 1/3, 2/3, 1 (divided differences on equal
  // spacing), for its critical points only; the roots are bisected on f itself.
  const std::array<double, 4> f = {signed_volume(start, end, 0.0),
                                   signed_volume(start, end, 1.0 / 3.0),
                                   signed_volume(start, end, 2.0 / 3.0),
                                   signed_volume(start, end, 1.0)};
  // f(tau) = c0 + c1 tau + c2 tau^2 + c3 tau^3 through the four samples (s = 3 tau).
  const double d1 = f[1] - f[0], d2 = f[2] - 2 * f[1] + f[0], d3 = f[3] - 3 * f[2] + 3 * f[1] - f[0];
  // Newton form in s: f = f0 + d1 s + d2 s (s - 1) / 2 + d3 s (s - 1)(s - 2) / 6.
  const double c3 = d3 / 6.0 * 27.0;
  const double c2 = (d2 / 2.0 - d3 / 2.0) * 9.0;
  const double c1 = (d1 - d2 / 2.0 + d3 / 3.0) * 3.0;
  // Break points: 0, the critical points in (0, 1), 1.
  std::vector<double> breaks = {0.0, 1.0};
  const double qa = 3 * c3, qb = 2 * c2, qc = c1;
  const double scale = std::max({std::abs(qa), std::abs(qb), std::abs(qc)});
  if (scale > 0.0) {
    if (std::abs(qa) > 1e-14 * scale) {
      const double disc = qb * qb - 4 * qa * qc;
      if (disc >= 0.0) {
        const double r = std::sqrt(disc);
        // The numerically stable pair of roots.
        const double q = -0.5 * (qb + (qb >= 0 ? r : -r));
        if (q != 0.0) {
          breaks.push_back(q / qa);
          breaks.push_back(qc / q);
        } else {
          breaks.push_back(0.0);
        }
      }
    } else if (std::abs(qb) > 0.0) {
      breaks.push_back(-qc / qb);
    }
  }
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> pieces;
  for (const double t : breaks)
    if (t >= 0.0 && t <= 1.0 && (pieces.empty() || t > pieces.back())) pieces.push_back(t);
  for (size_t k = 0; k + 1 < pieces.size(); ++k) {
    double lo = pieces[k], hi = pieces[k + 1];
    double f_lo = signed_volume(start, end, lo);
    const double f_hi = signed_volume(start, end, hi);
    if (!(f_lo * f_hi < 0.0)) continue;  // no strict change of side on this piece
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      const double f_mid = signed_volume(start, end, mid);
      if (f_mid == 0.0) {
        lo = hi = mid;
        break;
      }
      if ((f_mid < 0.0) == (f_lo < 0.0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    const double root = 0.5 * (lo + hi);
    if (inside_triangle(corners_at(start, end, root))) return root;
  }
  return std::nullopt;
}

std::optional<PathCrossing> first_vertex_triangle_crossing(
    const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    const Eigen::Ref<const Eigen::VectorXd>& x1, double exclusion_radius) {
  if (x0.size() != proxy.map.cols() || x1.size() != proxy.map.cols())
    throw std::invalid_argument("first_vertex_triangle_crossing: the states have " +
                                std::to_string(x0.size()) + " and " + std::to_string(x1.size()) +
                                " entries, the proxy's map " + std::to_string(proxy.map.cols()));
  if (!(exclusion_radius >= 0.0) || !std::isfinite(exclusion_radius))
    throw std::invalid_argument("first_vertex_triangle_crossing: exclusion_radius = " +
                                std::to_string(exclusion_radius) + " must be finite and >= 0");
  const Eigen::MatrixX3d start = proxy_positions(proxy, x0), end = proxy_positions(proxy, x1);
  const double largest_motion = (end - start).rowwise().norm().maxCoeff();
  if (!(largest_motion > 0.0)) return std::nullopt;
  // Pairs farther apart than twice the largest motion at x0 cannot meet on the path.
  NearPairSelection vertex_triangle;
  vertex_triangle.edge_edge_pairs = false;
  const ContactCandidates pairs = near_contact_pairs(
      proxy, x0, 2.0 * largest_motion * (1.0 + 1e-9), exclusion_radius, vertex_triangle);
  std::optional<PathCrossing> first;
  for (Eigen::Index k = 0; k < pairs.vertex_triangle.rows(); ++k) {
    const int p = pairs.vertex_triangle(k, 0), t = pairs.vertex_triangle(k, 1);
    Corners s, e;
    s.row(0) = start.row(p);
    e.row(0) = end.row(p);
    for (int c = 0; c < 3; ++c) {
      s.row(1 + c) = start.row(proxy.triangles(t, c));
      e.row(1 + c) = end.row(proxy.triangles(t, c));
    }
    const std::optional<double> time = vertex_triangle_crossing_time(s, e);
    if (time && (!first || *time < first->time)) first = PathCrossing{p, t, *time};
  }
  return first;
}

}  // namespace growshell
