#include "studies/turn_free_stability_index.hpp"

#include <stdexcept>
#include <utility>

#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/pattern_rotation.hpp"

namespace growshell {

namespace {

Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>> as_rows(
    const Eigen::Ref<const Eigen::VectorXd>& x) {
  return {x.data(), x.size() / 3, 3};
}

}  // namespace

TurnFreeStabilityIndex::TurnFreeStabilityIndex(const ParametrizedObjective& family,
                                               const ShellModel& model,
                                               std::vector<Eigen::Index> pins,
                                               double max_pin_condition)
    : family_(family), model_(model), pins_(std::move(pins)), max_pin_condition_(max_pin_condition) {
  if (pins_.size() != 6)
    throw std::invalid_argument("TurnFreeStabilityIndex: needs six rigid-motion pins, got " +
                                std::to_string(pins_.size()));
  if (!(max_pin_condition_ >= 1.0))
    throw std::invalid_argument("TurnFreeStabilityIndex: max_pin_condition must be >= 1");
  size_ = model_.reference_positions().lpNorm<Eigen::Infinity>();
  count_pins_ = pins_;
}

std::vector<Eigen::Index> analysis_pins(const ShellModel& model,
                                        const Eigen::Ref<const Eigen::VectorXd>& x,
                                        const std::vector<Eigen::Index>& pins,
                                        double max_pin_condition) {
  return well_conditioned_pins(as_rows(x), pins, model.sheet_vertices(), max_pin_condition);
}

int TurnFreeStabilityIndex::at(const Eigen::Ref<const Eigen::VectorXd>& x, double phi_e) {
  const std::vector<Eigen::Index> pins = analysis_pins(model_, x, pins_, max_pin_condition_);
  if (!count_ || pins != count_pins_) {
    count_ = std::make_unique<HessianNegativeCount>(family_, pins);
    count_pins_ = pins;
  }
  const int full = count_->at(x, phi_e);
  const Eigen::VectorXd turn = pattern_rotation(model_, x, count_pins_);
  if (turn.lpNorm<Eigen::Infinity>() <= 1e-9 * size_) return full;
  return count_->negative_orthogonal_to(turn);
}

int turn_free_index_by_class(SymmetryClassStabilityIndex& index, const ShellModel& model,
                             const Eigen::Ref<const Eigen::VectorXd>& x, double phi_e) {
  const int full = index.at(x, phi_e);
  const Eigen::VectorXd turn = pattern_rotation(model, x, {});
  const double size = model.reference_positions().lpNorm<Eigen::Infinity>();
  if (turn.lpNorm<Eigen::Infinity>() <= 1e-9 * size) return full;
  return index.negative_orthogonal_to(turn);
}

}  // namespace growshell
