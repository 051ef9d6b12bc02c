#include "libshell/analysis/rim_folds.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace growshell {
namespace {

/// Below this rms elevation of the rim directions above their best plane the rim is flat.
constexpr double kFlatAmplitude = 1e-8;

}  // namespace

RimFoldAnalysis analyze_rim_folds(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                  int max_mode) {
  if (max_mode < 2) throw std::invalid_argument("rim fold analysis needs max_mode >= 2");
  const auto& sheet = model.sheet_vertices();
  std::vector<char> in_sheet(model.topology().num_vertices(), 0);
  for (int v : sheet) in_sheet[v] = 1;
  const Eigen::MatrixX3d limit = model.limit_positions(x);
  const Eigen::Vector3d centre = model.settings().growth.center;
  const Eigen::VectorXd& X0 = model.reference_positions();
  struct RimVertex {
    Eigen::Vector3d position;
    double angle, distance;
  };
  std::vector<RimVertex> rim;
  for (std::size_t k = 0; k < sheet.size(); ++k) {
    const int v = sheet[k];
    bool on_rim = false;
    for (int u : model.topology().one_ring(v)) on_rim = on_rim || !in_sheet[u];
    if (!on_rim) continue;
    const Eigen::Vector3d d = X0.segment<3>(3 * v) - centre;
    rim.push_back({limit.row(static_cast<Eigen::Index>(k)).transpose(), std::atan2(d.y(), d.x()),
                   d.norm()});
  }
  // Keep the outer rim only (a ring also has an inner one): reference distance at least
  // halfway between the smallest and the largest rim distance.
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0.0;
  for (const auto& p : rim) {
    r_min = std::min(r_min, p.distance);
    r_max = std::max(r_max, p.distance);
  }
  // The apex: the sheet vertex at the growth centre, or (a ring) the inner rim's centroid.
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();
  {
    Eigen::Index nearest = 0;
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < sheet.size(); ++k) {
      const double d = (X0.segment<3>(3 * sheet[k]) - centre).norm();
      if (d < nearest_distance) {
        nearest_distance = d;
        nearest = static_cast<Eigen::Index>(k);
      }
    }
    if (nearest_distance <= 1e-9 * r_max) {
      apex = limit.row(nearest).transpose();
    } else {
      int count = 0;
      for (const auto& p : rim)
        if (p.distance < 0.5 * (r_min + r_max)) {
          apex += p.position;
          ++count;
        }
      apex /= count;
    }
  }
  std::vector<Eigen::Vector3d> points;
  std::vector<double> angles;
  for (const auto& p : rim) {
    if (p.distance < 0.5 * (r_min + r_max) - 1e-12 * r_max) continue;
    points.push_back(p.position);
    angles.push_back(p.angle);
  }
  const Eigen::Index n = static_cast<Eigen::Index>(points.size());
  if (n < 2 * max_mode + 2)
    throw std::invalid_argument("rim has " + std::to_string(n) + " vertices, too few for " +
                                std::to_string(max_mode) + " modes");
  // Fourier series of the closed curve of unit directions apex -> rim point, as a function
  // of the reference angle. Its power per mode, summed over the three components, does not
  // depend on the orientation of the cone. A cone with n folds has directions
  // (cos t cos b, sin t cos b, sin b) with b ~ a cos(n t): the in-plane part has modes 1 and
  // 2kn +- 1, the elevation the odd multiples of n, led by n itself.
  Eigen::MatrixXd A(n, 2 * max_mode + 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    A(i, 0) = 1.0;
    for (int m = 1; m <= max_mode; ++m) {
      A(i, 2 * m - 1) = std::cos(m * angles[i]);
      A(i, 2 * m) = std::sin(m * angles[i]);
    }
  }
  Eigen::MatrixX3d D(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) D.row(i) = (points[i] - apex).normalized().transpose();
  const Eigen::MatrixXd c = A.colPivHouseholderQr().solve(D);  // (2 max_mode + 1) x 3
  RimFoldAnalysis out;
  out.mode_amplitudes.resize(max_mode + 1);
  out.mode_amplitudes(0) = c.row(0).norm();
  for (int m = 1; m <= max_mode; ++m)
    out.mode_amplitudes(m) = std::sqrt(c.row(2 * m - 1).squaredNorm() + c.row(2 * m).squaredNorm());
  Eigen::Index best = 0;
  out.mode_amplitudes.tail(max_mode - 1).maxCoeff(&best);
  // A planar rim (rms distance of the directions from their best plane through the apex
  // below kFlatAmplitude) has no folds; its m >= 2 content is only the uneven spacing of the
  // rim vertices in angle.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(D);
  const double rms_elevation = svd.singularValues()(2) / std::sqrt(static_cast<double>(n));
  out.folds = rms_elevation > kFlatAmplitude ? static_cast<int>(best) + 2 : 0;
  return out;
}

}  // namespace growshell
