#include "python/sheet_thickness_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell {
namespace {

/// The sheet's triangles in a uniform grid of cells, for locating points.
struct SheetLocator {
  Eigen::MatrixX2d points;
  Eigen::MatrixX3i faces;
  Eigen::VectorXd values;
  bool per_face = false;
  Eigen::Vector2d lower, cell;
  int columns = 1, rows = 1;
  std::vector<std::vector<int>> cells;

  /// The grid column (axis 0) or row (axis 1) of a coordinate, clamped into the grid.
  int cell_of(double v, int axis) const {
    const int n = axis == 0 ? columns : rows;
    return std::clamp(static_cast<int>(std::floor((v - lower(axis)) / cell(axis))), 0, n - 1);
  }

  Eigen::Vector3d barycentric(int f, const Eigen::Vector2d& p) const {
    const Eigen::Vector2d a = points.row(faces(f, 0)), b = points.row(faces(f, 1)),
                          c = points.row(faces(f, 2));
    const double det = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    const double u = ((b - p).x() * (c - p).y() - (b - p).y() * (c - p).x()) / det;
    const double v = ((c - p).x() * (a - p).y() - (c - p).y() * (a - p).x()) / det;
    return {u, v, 1.0 - u - v};
  }

  double value(int f, Eigen::Vector3d w) const {
    if (per_face) return values(f);
    w = w.cwiseMax(0.0);
    w /= w.sum();
    return w(0) * values(faces(f, 0)) + w(1) * values(faces(f, 1)) + w(2) * values(faces(f, 2));
  }

  double operator()(const Eigen::Vector3d& x) const {
    const Eigen::Vector2d p(x.x(), x.y());
    const int i = cell_of(p.x(), 0), j = cell_of(p.y(), 1);
    int best = -1;
    double best_outside = std::numeric_limits<double>::infinity();
    Eigen::Vector3d best_w;
    const auto consider = [&](int f) {
      const Eigen::Vector3d w = barycentric(f, p);
      const double outside = -std::min(0.0, w.minCoeff());
      if (outside < best_outside) {
        best_outside = outside;
        best = f;
        best_w = w;
      }
    };
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int ci = i + di, cj = j + dj;
        if (ci < 0 || cj < 0 || ci >= columns || cj >= rows) continue;
        for (const int f : cells[static_cast<std::size_t>(cj * columns + ci)]) consider(f);
      }
    if (best < 0 || best_outside > 1e-9)
      for (int f = 0; f < faces.rows() && best_outside > 1e-9; ++f) consider(f);
    return value(best, best_w);
  }
};

}  // namespace

ThicknessField sheet_thickness_field(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                     const Eigen::VectorXd& values, bool per_face) {
  const Eigen::Index expected = per_face ? faces.rows() : vertices.rows();
  if (values.size() != expected)
    throw std::invalid_argument("thickness has " + std::to_string(values.size()) +
                                " values; per " + (per_face ? "face" : "vertex") + " it needs " +
                                std::to_string(expected));
  for (Eigen::Index k = 0; k < values.size(); ++k)
    if (!(std::isfinite(values(k)) && values(k) > 0.0))
      throw std::invalid_argument("thickness[" + std::to_string(k) + "] = " +
                                  std::to_string(values(k)) + " must be finite and > 0");
  if (faces.rows() == 0) throw std::invalid_argument("the sheet has no faces");
  auto s = std::make_shared<SheetLocator>();
  s->points = vertices.leftCols<2>();
  s->faces = faces;
  s->values = values;
  s->per_face = per_face;
  s->lower = s->points.colwise().minCoeff().transpose();
  const Eigen::Vector2d extent =
      (s->points.colwise().maxCoeff().transpose() - s->lower).cwiseMax(1e-12);
  const int n = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(faces.rows()) / 2.0)));
  s->columns = s->rows = n;
  s->cell = extent / n;
  s->cells.assign(static_cast<std::size_t>(n * n), {});
  for (int f = 0; f < faces.rows(); ++f) {
    Eigen::Vector2d lo = s->points.row(faces(f, 0)), hi = lo;
    for (int c = 1; c < 3; ++c) {
      lo = lo.cwiseMin(s->points.row(faces(f, c)).transpose());
      hi = hi.cwiseMax(s->points.row(faces(f, c)).transpose());
    }
    for (int j = s->cell_of(lo.y(), 1); j <= s->cell_of(hi.y(), 1); ++j)
      for (int i = s->cell_of(lo.x(), 0); i <= s->cell_of(hi.x(), 0); ++i)
        s->cells[static_cast<std::size_t>(j * n + i)].push_back(f);
  }
  return [s](const Eigen::Vector3d& x) { return (*s)(x); };
}

}  // namespace growshell
