#include "studies/power_law_fit.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace growshell {

std::optional<PowerLawFit> fit_power_law(const std::vector<double>& x, const std::vector<double>& y,
                                         double limit) {
  if (x.size() != y.size())
    throw std::invalid_argument("fit_power_law: " + std::to_string(x.size()) + " abscissae but " +
                                std::to_string(y.size()) + " values");
  if (!std::isfinite(limit)) throw std::invalid_argument("fit_power_law: the limit must be finite");
  std::vector<double> u, v;  // log x, log(y - limit)
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !(x[i] > 0.0) || !(y[i] > limit)) continue;
    u.push_back(std::log(x[i]));
    v.push_back(std::log(y[i] - limit));
  }
  const auto n = static_cast<double>(u.size());
  if (u.size() < 2) return std::nullopt;
  double mu = 0.0, mv = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    mu += u[i] / n;
    mv += v[i] / n;
  }
  double suu = 0.0, suv = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    suu += (u[i] - mu) * (u[i] - mu);
    suv += (u[i] - mu) * (v[i] - mv);
  }
  if (!(suu > 0.0)) return std::nullopt;
  PowerLawFit fit;
  fit.limit = limit;
  fit.exponent = suv / suu;
  const double log_amplitude = mv - fit.exponent * mu;
  fit.amplitude = std::exp(log_amplitude);
  fit.points = static_cast<int>(u.size());
  for (std::size_t i = 0; i < u.size(); ++i)
    fit.max_relative_misfit = std::max(
        fit.max_relative_misfit, std::abs(std::exp(log_amplitude + fit.exponent * u[i] - v[i]) - 1.0));
  return fit;
}

}  // namespace growshell
