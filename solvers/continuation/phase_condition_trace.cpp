#include "solvers/continuation/phase_condition_trace.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "solvers/continuation/phase_conditioned_family.hpp"
#include "solvers/stability/hessian_negative_count.hpp"

namespace growshell {

BranchTrace trace_branch_with_phase_condition(
    const ParametrizedObjective& family, const Eigen::Ref<const Eigen::VectorXd>& functional,
    const Eigen::Ref<const Eigen::VectorXd>& x0, double lambda0,
    const Eigen::Ref<const Eigen::VectorXd>& direction_state, double direction_parameter,
    const std::vector<Eigen::Index>& fixed_dofs, const ArclengthOptions& options,
    const std::function<void(const BranchSample&)>& on_sample,
    const std::function<void(const SpecialPoint&)>& on_special,
    const std::vector<BranchEvent>& events,
    const std::function<void(const LocatedEvent&)>& on_event) {
  const Eigen::Index n = family.dimension();
  if (functional.size() != n || x0.size() != n || direction_state.size() != n)
    throw std::invalid_argument("trace_branch_with_phase_condition: the functional, x0 and "
                                "direction_state need " + std::to_string(n) + " entries");
  const double norm = functional.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    throw std::invalid_argument(
        "trace_branch_with_phase_condition: the functional must be finite and not vanish");
  const Eigen::VectorXd unit = functional / norm;
  PhaseConditionedFamily conditioned(family, unit, unit.dot(x0));

  const auto strip = [n](BranchSample s) {
    if (s.x.size() == n + 1) s.x.conservativeResize(n);
    if (s.tangent_state.size() == n + 1) s.tangent_state.conservativeResize(n);
    return s;
  };
  const auto state = [n](const Eigen::VectorXd& z) -> Eigen::VectorXd {
    return z.size() == n + 1 ? Eigen::VectorXd(z.head(n)) : z;
  };

  // The start's multiplier: the gradient's share along c, so that the start is as close to a
  // stationary point of the Lagrangian as x0 is to an equilibrium.
  Eigen::VectorXd g;
  family.evaluate(x0, lambda0, &g, nullptr);
  Eigen::VectorXd z0(n + 1);
  z0.head(n) = x0;
  z0(n) = phase_multiplier(g, unit, fixed_dofs);
  Eigen::VectorXd direction = Eigen::VectorXd::Zero(n + 1);
  direction.head(n) = direction_state;

  ArclengthOptions o = options;
  // Without the caller's index: the bordered Hessian's count less the one negative eigenvalue
  // that the border adds (In([[H, c], [c^T, 0]]) = In(H on c-perp) + (1, 1)), which stays
  // defined where H itself is singular along the orbit of an exact symmetry.
  HessianNegativeCount bordered_count(conditioned, fixed_dofs);
  o.stability_index = [&](const BranchSample& s) {
    if (options.stability_index) return options.stability_index(strip(s));
    return bordered_count.at(s.x, s.parameter) - 1;
  };
  if (options.accept_step)
    o.accept_step = [&](const BranchSample& from, const BranchSample& to) {
      return options.accept_step(strip(from), strip(to));
    };
  std::vector<BranchEvent> state_events = events;
  for (BranchEvent& e : state_events)
    e.value = [&, value = e.value](const BranchSample& s) { return value(strip(s)); };

  BranchTrace trace = trace_branch_along(
      conditioned, z0, lambda0, direction, direction_parameter, fixed_dofs, o,
      [&](const BranchSample& s) {
        if (on_sample) on_sample(strip(s));
      },
      [&](SpecialPoint sp) {
        sp.x = state(sp.x);
        if (on_special) on_special(sp);
      },
      state_events,
      [&](LocatedEvent e) {
        e.x = state(e.x);
        if (on_event) on_event(e);
      });
  trace.last = strip(std::move(trace.last));
  for (SpecialPoint& sp : trace.special_points) sp.x = state(sp.x);
  for (LocatedEvent& e : trace.events) e.x = state(e.x);
  return trace;
}

}  // namespace growshell
