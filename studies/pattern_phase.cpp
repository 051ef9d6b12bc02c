#include "studies/pattern_phase.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace growshell {

namespace {

/// sum A_i w_i e^{-i n theta_i} of the out-of-plane components of y.
std::complex<double> fourier_component(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& y,
                                       int folds) {
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::VectorXd& area = model.reference().vertex_areas();
  const Eigen::Vector3d& c = model.settings().growth.center;
  std::complex<double> sum = 0.0;
  for (const int v : model.sheet_vertices()) {
    const double theta = std::atan2(X(3 * v + 1) - c.y(), X(3 * v) - c.x());
    sum += area(v) * y(3 * v + 2) * std::polar(1.0, -folds * theta);
  }
  return sum;
}

}  // namespace

double pattern_orientation(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                           const Eigen::Ref<const Eigen::VectorXd>& direction, int folds) {
  if (x.size() != model.dimension() || direction.size() != model.dimension())
    throw std::invalid_argument("pattern_orientation: the state and the direction need " +
                                std::to_string(model.dimension()) + " entries");
  if (folds < 1) throw std::invalid_argument("pattern_orientation: needs n >= 1 folds");
  const Eigen::VectorXd& X = model.reference_positions();
  double area = 0.0;
  for (const int v : model.sheet_vertices()) area += model.reference().vertex_areas()(v);
  const double scale = 1e-12 * area * X.lpNorm<Eigen::Infinity>();
  std::complex<double> component = fourier_component(model, x, folds);
  if (!(std::abs(component) > scale)) {
    component = fourier_component(model, direction, folds);
    if (!(std::abs(component) > 1e-12 * area * direction.lpNorm<Eigen::Infinity>()))
      throw std::invalid_argument("pattern_orientation: neither the state nor the direction has an " +
                                  std::to_string(folds) + "-fold out-of-plane pattern");
  }
  return -std::arg(component) / folds;
}

Eigen::VectorXd pattern_phase_functional(const ShellModel& model,
                                         const Eigen::Ref<const Eigen::VectorXd>& x,
                                         const Eigen::Ref<const Eigen::VectorXd>& direction,
                                         int folds) {
  const double theta0 = pattern_orientation(model, x, direction, folds);
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::VectorXd& area = model.reference().vertex_areas();
  const Eigen::Vector3d& c = model.settings().growth.center;
  Eigen::VectorXd functional = Eigen::VectorXd::Zero(model.dimension());
  for (const int v : model.sheet_vertices()) {
    const double theta = std::atan2(X(3 * v + 1) - c.y(), X(3 * v) - c.x());
    functional(3 * v + 2) = area(v) * std::sin(folds * (theta - theta0));
  }
  return functional;
}

}  // namespace growshell
