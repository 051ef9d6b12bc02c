#include "libshell/analysis/state_evaluator.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

namespace growshell {
namespace {

/// The reference triangulation with a uniform grid of buckets for point location.
struct Interpolant {
  Eigen::MatrixX2d reference;  // reference limit positions (x, y) of the sheet vertices
  Eigen::MatrixX3d current;    // their current limit positions
  std::vector<std::array<int, 3>> triangles;  // sheet indices
  Eigen::Vector2d origin;
  double cell = 1.0;
  int nx = 1, ny = 1;
  std::vector<std::vector<int>> buckets;  // triangles overlapping each cell

  /// Barycentric coordinates of p in triangle t (unclamped).
  Eigen::Vector3d barycentric(int t, const Eigen::Vector2d& p) const {
    const auto& tri = triangles[static_cast<std::size_t>(t)];
    const Eigen::Vector2d a = reference.row(tri[0]), b = reference.row(tri[1]),
                          c = reference.row(tri[2]);
    Eigen::Matrix2d M;
    M.col(0) = b - a;
    M.col(1) = c - a;
    const Eigen::Vector2d l = M.inverse() * (p - a);
    return {1.0 - l(0) - l(1), l(0), l(1)};
  }
  double distance(int t, const Eigen::Vector2d& p) const {
    const Eigen::Vector3d l = barycentric(t, p);
    if (l.minCoeff() >= 0.0) return 0.0;
    const auto& tri = triangles[static_cast<std::size_t>(t)];
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = reference.row(tri[static_cast<std::size_t>(k)]);
      const Eigen::Vector2d b = reference.row(tri[static_cast<std::size_t>((k + 1) % 3)]);
      const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      best = std::min(best, (p - a - s * (b - a)).norm());
    }
    return best;
  }
  Eigen::Vector3d interpolate(int t, const Eigen::Vector3d& l) const {
    const auto& tri = triangles[static_cast<std::size_t>(t)];
    return (l(0) * current.row(tri[0]) + l(1) * current.row(tri[1]) + l(2) * current.row(tri[2]))
        .transpose();
  }
  Eigen::Vector3d operator()(const Eigen::Vector3d& X) const {
    const Eigen::Vector2d p = X.head<2>();
    const int i = static_cast<int>(std::floor((p.x() - origin.x()) / cell));
    const int j = static_cast<int>(std::floor((p.y() - origin.y()) / cell));
    // Inside: the first triangle of the point's cell that contains it (ties on shared edges
    // give the same value up to rounding).
    const double slack = -1e-12;
    if (i >= 0 && i < nx && j >= 0 && j < ny)
      for (int t : buckets[static_cast<std::size_t>(j * nx + i)]) {
        const Eigen::Vector3d l = barycentric(t, p);
        if (l.minCoeff() >= slack) return interpolate(t, l);
      }
    // Outside: linear extrapolation from the nearest triangle (lowest index among ties).
    int best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
      const double d = distance(t, p);
      if (d < best_distance) {
        best_distance = d;
        best = t;
      }
    }
    return interpolate(best, barycentric(best, p));
  }
};

}  // namespace

StateEvaluator sheet_state_evaluator(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != model.dimension())
    throw std::invalid_argument("sheet_state_evaluator: the state has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(model.dimension()));
  if (!x.allFinite())
    throw std::invalid_argument("sheet_state_evaluator: the state holds a non-finite value");
  auto in = std::make_shared<Interpolant>();
  in->reference = model.limit_positions(model.reference_positions()).leftCols<2>();
  in->current = model.limit_positions(x);
  const auto& sheet = model.sheet_vertices();
  std::vector<int> sheet_index(static_cast<std::size_t>(model.topology().num_vertices()), -1);
  for (std::size_t k = 0; k < sheet.size(); ++k) sheet_index[static_cast<std::size_t>(sheet[k])] = static_cast<int>(k);
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const std::array<int, 3>& f = model.topology().face(model.patches().face[static_cast<std::size_t>(e)]);
    in->triangles.push_back({sheet_index[static_cast<std::size_t>(f[0])],
                             sheet_index[static_cast<std::size_t>(f[1])],
                             sheet_index[static_cast<std::size_t>(f[2])]});
  }
  if (in->triangles.empty()) throw std::invalid_argument("sheet_state_evaluator: the model has no elements");
  // Buckets of about one element each.
  const Eigen::Vector2d lo = in->reference.colwise().minCoeff().transpose();
  const Eigen::Vector2d hi = in->reference.colwise().maxCoeff().transpose();
  const double extent = std::max((hi - lo).maxCoeff(), std::numeric_limits<double>::min());
  const int per_side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(in->triangles.size()))));
  in->cell = extent / per_side * (1.0 + 1e-9);
  in->origin = lo;
  in->nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / in->cell)));
  in->ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / in->cell)));
  in->buckets.assign(static_cast<std::size_t>(in->nx * in->ny), {});
  for (int t = 0; t < static_cast<int>(in->triangles.size()); ++t) {
    Eigen::Vector2d a = in->reference.row(in->triangles[static_cast<std::size_t>(t)][0]), b = a;
    for (int k = 1; k < 3; ++k) {
      const Eigen::Vector2d p = in->reference.row(in->triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)]);
      a = a.cwiseMin(p);
      b = b.cwiseMax(p);
    }
    const auto clampi = [](int v, int n) { return std::clamp(v, 0, n - 1); };
    const int i0 = clampi(static_cast<int>(std::floor((a.x() - lo.x()) / in->cell)), in->nx);
    const int i1 = clampi(static_cast<int>(std::floor((b.x() - lo.x()) / in->cell)), in->nx);
    const int j0 = clampi(static_cast<int>(std::floor((a.y() - lo.y()) / in->cell)), in->ny);
    const int j1 = clampi(static_cast<int>(std::floor((b.y() - lo.y()) / in->cell)), in->ny);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) in->buckets[static_cast<std::size_t>(j * in->nx + i)].push_back(t);
  }
  return [in](const Eigen::Vector3d& X) { return (*in)(X); };
}

}  // namespace growshell
