#include "solvers/contact/lowest_skewed_state.hpp"

#include <cmath>
#include <stdexcept>

namespace growshell {

LowestSkewedState::LowestSkewedState(double symmetric_energy, double relative_margin)
    : threshold_(symmetric_energy - relative_margin * std::abs(symmetric_energy)),
      energy_(symmetric_energy) {
  if (!std::isfinite(symmetric_energy))
    throw std::invalid_argument("LowestSkewedState: the symmetric energy must be finite");
  if (!(relative_margin >= 0.0 && std::isfinite(relative_margin)))
    throw std::invalid_argument("LowestSkewedState: the relative margin must be finite and >= 0");
}

bool LowestSkewedState::offer(double energy, const Eigen::Ref<const Eigen::VectorXd>& x) {
  // energy_ starts at the symmetric energy, at or above the threshold; NaN fails both.
  if (!(energy < threshold_ && energy < energy_)) return false;
  energy_ = energy;
  state_ = x;
  return true;
}

}  // namespace growshell
