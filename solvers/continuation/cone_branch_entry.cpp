#include "solvers/continuation/cone_branch_entry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace growshell {

Eigen::VectorXd fold_mode_hint(const ShellModel& model, int folds) {
  const Eigen::VectorXd& X = model.reference_positions();
  Eigen::VectorXd hint = Eigen::VectorXd::Zero(X.size());
  for (Eigen::Index v = 0; v < X.size() / 3; ++v) {
    const double r = std::hypot(X(3 * v), X(3 * v + 1));
    const double t = std::atan2(X(3 * v + 1), X(3 * v));
    hint(3 * v + 2) = std::pow(r, folds) * std::cos(folds * t);
  }
  return hint;
}

int rim_angular_wavenumber(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& mode) {
  const Eigen::VectorXd& X = model.reference_positions();
  double r_max = 0.0;
  for (const int v : model.sheet_vertices()) r_max = std::max(r_max, X.segment<2>(3 * v).norm());
  double best = -1.0;
  int best_k = 0;
  for (int k = 2; k <= 8; ++k) {
    double c = 0.0, s = 0.0, count = 0.0;
    for (const int v : model.sheet_vertices()) {
      if (X.segment<2>(3 * v).norm() < 0.999 * r_max) continue;
      const double t = std::atan2(X(3 * v + 1), X(3 * v));
      c += mode(3 * v + 2) * std::cos(k * t);
      s += mode(3 * v + 2) * std::sin(k * t);
      count += 1.0;
    }
    const double power = (c * c + s * s) / (count * count);
    if (power > best) {
      best = power;
      best_k = k;
    }
  }
  return best_k;
}

ConeBranchEntry enter_cone_branch(const ParametrizedObjective& family, const ShellModel& model,
                                  const ConeEntryOptions& entry,
                                  const std::vector<Eigen::Index>& fixed_dofs,
                                  const ArclengthOptions& cone_options,
                                  const std::function<void(const SpecialPoint&)>& on_special) {
  if (entry.folds < 2)
    throw std::invalid_argument("enter_cone_branch: folds must be >= 2, not " +
                                std::to_string(entry.folds));
  if (!(entry.thickness > 0.0 && entry.radius > 0.0))
    throw std::invalid_argument("enter_cone_branch: thickness and radius must be > 0");
  const double h_over_r2 = (entry.thickness / entry.radius) * (entry.thickness / entry.radius);
  ArclengthOptions flat_options = cone_options;
  flat_options.initial_step = std::min(1e-3, 0.25 * h_over_r2);
  flat_options.max_step = std::min(0.01, 2.5 * h_over_r2);
  flat_options.min_step = std::min(flat_options.min_step, 1e-3 * flat_options.initial_step);
  flat_options.special_point_tolerance =
      std::min(cone_options.special_point_tolerance, 1e-3 * h_over_r2);
  flat_options.max_special_points = entry.folds - 1;

  ConeBranchEntry out;
  std::vector<SpecialPoint> flat_points;
  out.flat = trace_branch(family, model.reference_positions(), entry.phi_start, +1, fixed_dofs,
                          flat_options, {}, [&](const SpecialPoint& sp) {
                            flat_points.push_back(sp);
                            if (on_special) on_special(sp);
                          });
  const Eigen::VectorXd hint = fold_mode_hint(model, entry.folds);
  for (const SpecialPoint& sp : flat_points) {
    Eigen::VectorXd mode =
        critical_mode(family, sp.x, sp.parameter, hint, fixed_dofs, cone_options);
    if (rim_angular_wavenumber(model, mode) != entry.folds) continue;
    out.found = true;
    out.branch_point = sp;
    out.mode = std::move(mode);
  }
  if (!out.found) {
    out.message =
        "no branch point with a " + std::to_string(entry.folds) +
        "-fold mode on the flat branch up to phi_e = " + std::to_string(out.flat.last.parameter) +
        " (" + out.flat.message + ")";
    return out;
  }
  out.switch_step = 0.005 * std::min(1.0, entry.thickness / (0.005 * entry.radius));
  out.start = out.branch_point.x + out.switch_step * out.mode;
  return out;
}

BranchPointDeparture leave_branch_point(
    const ConeBranchEntry& entry,
    const std::function<BranchTrace(const Eigen::VectorXd& start, const Eigen::VectorXd& mode)>&
        trace,
    int max_attempts) {
  if (!entry.found)
    throw std::invalid_argument("leave_branch_point: the entry has no branch point (" +
                                entry.message + ")");
  if (max_attempts < 1)
    throw std::invalid_argument("leave_branch_point: max_attempts must be >= 1, not " +
                                std::to_string(max_attempts));
  BranchPointDeparture out;
  TraceCost failed;
  double step = entry.switch_step;
  for (out.attempts = 1;; ++out.attempts, step *= 0.5) {
    const Eigen::VectorXd start =
        out.attempts == 1 ? entry.start : Eigen::VectorXd(entry.branch_point.x + step * entry.mode);
    out.trace = trace(start, entry.mode);
    out.switch_step = step;
    if (out.trace.start_converged || out.attempts == max_attempts) break;
    failed += out.trace.cost;
  }
  out.trace.cost += failed;
  return out;
}

}  // namespace growshell
