#include "libshell/analysis/state_evaluator.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "libshell/subdivision/limit_surface.hpp"

namespace growshell {
namespace {

/// The reference triangulation with a uniform grid of buckets for point location, and the
/// elements' patches for the exact limit surface.
struct Interpolant {
  Eigen::MatrixX2d reference;  // reference limit positions (x, y) of the sheet vertices
  std::vector<std::array<int, 3>> triangles;  // sheet indices, one per element
  Eigen::MatrixX3d reference_control;  // control points, one row per vertex
  Eigen::MatrixX3d current_control;
  std::vector<LoopPatch> patches;  // per element (= per triangle)
  double tolerance = 0.0;  // of the parameter search, in reference length
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
  /// The parameter (v, w) of element t, in its triangle, whose reference limit point is
  /// nearest p, by Newton's method on the planar map (v, w) -> X(v, w) projected onto the
  /// triangle, from the barycentric guess l; `residual` gets |p - X(v, w)|.
  Eigen::Vector2d parameter(int t, const Eigen::Vector2d& p, const Eigen::Vector3d& l,
                            double* residual) const {
    const LoopPatch& patch = patches[static_cast<std::size_t>(t)];
    const auto project = [](Eigen::Vector2d q) {
      q = q.cwiseMax(0.0);
      const double sum = q.sum();
      return sum > 1.0 ? Eigen::Vector2d(q / sum) : q;
    };
    Eigen::Vector2d q = project(Eigen::Vector2d(l(1), l(2)));
    double r = std::numeric_limits<double>::infinity();
    for (int iteration = 0; iteration < 30; ++iteration) {
      const LimitSurfacePoint S = evaluate_limit_surface(reference_control, patch, q(0), q(1));
      const Eigen::Vector2d d = p - S.position.head<2>();
      r = d.norm();
      if (r <= tolerance) break;
      const Eigen::Matrix2d J = S.tangents.topRows<2>();
      const Eigen::Vector2d next = project(q + J.partialPivLu().solve(d));
      if ((next - q).norm() < 1e-15) break;  // pinned at the triangle's edge: p lies beyond it
      q = next;
    }
    *residual = r;
    return q;
  }
  /// Where material point p lies: element t, parameter q, and the first-order step s in
  /// (v, w) from q to p where p lies beyond the element (zero where it is on it).
  struct Location {
    int t = 0;
    Eigen::Vector2d q = Eigen::Vector2d::Zero();
    Eigen::Vector2d s = Eigen::Vector2d::Zero();
    PatchBasis basis;  // of element t at q
  };
  /// The location of p at parameter q of element t: the step s is the first-order one from the
  /// reference limit point there to p, where p lies beyond the element (residual above the
  /// tolerance).
  Location located(int t, const Eigen::Vector2d& q, const Eigen::Vector2d& p) const {
    const LoopPatch& patch = patches[static_cast<std::size_t>(t)];
    Location at{t, q, Eigen::Vector2d::Zero(), evaluate_patch_basis(patch, q(0), q(1))};
    const LimitSurfacePoint R = evaluate_limit_surface(reference_control, patch, at.basis);
    const Eigen::Vector2d d = p - R.position.head<2>();
    if (d.norm() > tolerance) at.s = R.tangents.topRows<2>().partialPivLu().solve(d);
    return at;
  }
  Location locate(const Eigen::Vector3d& X) const {
    const Eigen::Vector2d p = X.head<2>();
    const int i = static_cast<int>(std::floor((p.x() - origin.x()) / cell));
    const int j = static_cast<int>(std::floor((p.y() - origin.y()) / cell));
    // The element of the point's cell whose reference limit surface covers it: first those
    // whose limit-vertex triangle contains it, then the others of the cell (the limit image of
    // an element bulges past its vertices' triangle by O(spacing^2)); ties on shared edges
    // give the same value up to rounding.
    const double slack = -1e-12;
    if (i >= 0 && i < nx && j >= 0 && j < ny) {
      const std::vector<int>& cell_triangles = buckets[static_cast<std::size_t>(j * nx + i)];
      int best = -1;
      double best_residual = std::numeric_limits<double>::infinity();
      Eigen::Vector2d best_q = Eigen::Vector2d::Zero();
      for (const bool containing : {true, false})
        for (int t : cell_triangles) {
          const Eigen::Vector3d l = barycentric(t, p);
          if ((l.minCoeff() >= slack) != containing) continue;
          double residual = 0.0;
          const Eigen::Vector2d q = parameter(t, p, l, &residual);
          if (residual <= tolerance) return located(t, q, p);
          if (residual < best_residual) {
            best_residual = residual;
            best = t;
            best_q = q;
          }
        }
      if (best >= 0) return located(best, best_q, p);
    }
    // Outside: first-order continuation from the nearest triangle (lowest index among ties).
    int best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
      const double d = distance(t, p);
      if (d < best_distance) {
        best_distance = d;
        best = t;
      }
    }
    const Eigen::Vector3d l = barycentric(best, p);
    double residual = 0.0;
    return located(best, parameter(best, p, l, &residual), p);
  }
  /// y at a location: the current limit surface there, continued to first order by its step.
  Eigen::Vector3d operator()(const Eigen::Vector3d& X) const {
    const Location at = locate(X);
    const LimitSurfacePoint S =
        evaluate_limit_surface(current_control, patches[static_cast<std::size_t>(at.t)], at.basis);
    return S.position + S.tangents * at.s;
  }
};

/// The interpolant of `model`'s reference (its current control points empty).
std::shared_ptr<Interpolant> reference_interpolant(const ShellModel& model, const char* caller) {
  auto in = std::make_shared<Interpolant>();
  in->reference = model.limit_positions(model.reference_positions()).leftCols<2>();
  in->reference_control = Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(
      model.reference_positions().data(), model.dimension() / 3, 3);
  in->patches = model.patches().patch;
  const auto& sheet = model.sheet_vertices();
  std::vector<int> sheet_index(static_cast<std::size_t>(model.topology().num_vertices()), -1);
  for (std::size_t k = 0; k < sheet.size(); ++k) sheet_index[static_cast<std::size_t>(sheet[k])] = static_cast<int>(k);
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const std::array<int, 3>& f = model.topology().face(model.patches().face[static_cast<std::size_t>(e)]);
    in->triangles.push_back({sheet_index[static_cast<std::size_t>(f[0])],
                             sheet_index[static_cast<std::size_t>(f[1])],
                             sheet_index[static_cast<std::size_t>(f[2])]});
  }
  if (in->triangles.empty())
    throw std::invalid_argument(std::string(caller) + ": the model has no elements");
  // Buckets of about one element each.
  const Eigen::Vector2d lo = in->reference.colwise().minCoeff().transpose();
  const Eigen::Vector2d hi = in->reference.colwise().maxCoeff().transpose();
  const double extent = std::max((hi - lo).maxCoeff(), std::numeric_limits<double>::min());
  const int per_side = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(in->triangles.size()))));
  in->cell = extent / per_side * (1.0 + 1e-9);
  in->tolerance = 1e-13 * extent;
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
  return in;
}

}  // namespace

StateEvaluator sheet_state_evaluator(const ShellModel& model,
                                     const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != model.dimension())
    throw std::invalid_argument("sheet_state_evaluator: the state has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(model.dimension()));
  if (!x.allFinite())
    throw std::invalid_argument("sheet_state_evaluator: the state holds a non-finite value");
  std::shared_ptr<Interpolant> in = reference_interpolant(model, "sheet_state_evaluator");
  in->current_control =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
  return [in](const Eigen::Vector3d& X) { return (*in)(X); };
}

MaterialPointSampling::MaterialPointSampling(const ShellModel& model,
                                             const Eigen::Ref<const Eigen::MatrixX3d>& points)
    : dimension_(model.dimension()) {
  if (!points.allFinite())
    throw std::invalid_argument("MaterialPointSampling: a material point is not finite");
  const std::shared_ptr<const Interpolant> in =
      reference_interpolant(model, "MaterialPointSampling");
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Interpolant::Location at = in->locate(points.row(k).transpose());
    const std::vector<int>& control = in->patches[static_cast<std::size_t>(at.t)].control;
    // y = sum_j (value_j + first_j . s) x_j: the limit position, continued to first order.
    const Eigen::VectorXd weights = at.basis.value + at.basis.first * at.s;
    for (std::size_t j = 0; j < control.size(); ++j)
      entries.emplace_back(k, control[j], weights(static_cast<Eigen::Index>(j)));
  }
  basis_.resize(points.rows(), dimension_ / 3);
  basis_.setFromTriplets(entries.begin(), entries.end());
}

Eigen::MatrixX3d MaterialPointSampling::positions(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != dimension_)
    throw std::invalid_argument("MaterialPointSampling::positions: the state has " +
                                std::to_string(x.size()) + " entries, the model " +
                                std::to_string(dimension_));
  const Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>> control(x.data(),
                                                                                x.size() / 3, 3);
  return basis_ * control;
}

}  // namespace growshell
