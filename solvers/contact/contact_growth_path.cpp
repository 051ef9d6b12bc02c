#include "solvers/contact/contact_growth_path.hpp"

#include "core/objective_at_parameter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/contact/straight_path_crossing.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"
#include "solvers/stability/positive_definiteness.hpp"

namespace growshell {

ContactCandidates near_penalty_pairs(const ContactProxy& proxy,
                                     const Eigen::Ref<const Eigen::VectorXd>& y,
                                     const ContactBranchOptions& options) {
  return near_contact_pairs(proxy, y, options.contact_distance + options.candidate_margin,
                            options.exclusion_radius, options.selection);
}

ContactRelaxation relax_with_contact(const ShellModel& model, double excess_angle,
                                     const ContactProxy& proxy, Eigen::VectorXd& y,
                                     const std::vector<Eigen::Index>& fixed_dofs,
                                     const ContactBranchOptions& options,
                                     const NewtonOptions& newton, int max_rounds) {
  ContactRelaxation out;
  ContactCandidates pairs = near_penalty_pairs(proxy, y, options);
  // With a bound b on the motion of a dof per Newton step, one solve stops once a dof has
  // moved candidate_margin / 4 (b capped at that too), and the pairs are searched again at the
  // new state: two primitives then approach each other by less than candidate_margin between
  // searches, so no pair outside the set can come closer than the contact distance unseen (a
  // vertex pushed through a layer whose triangles were not penalised would end on the wrong
  // side, where the penalty drives it further in). The bounded solves share one budget of
  // newton.max_iterations steps; without a bound every round has its own, as before.
  const bool motion_bounded = std::isfinite(newton.max_step_inf_norm);
  NewtonOptions chunk = newton;
  if (motion_bounded) {
    chunk.max_travel = 0.25 * options.candidate_margin;
    chunk.max_step_inf_norm = std::min(newton.max_step_inf_norm, chunk.max_travel);
  }
  int iterations_left = newton.max_iterations;
  for (int round = 0; round < max_rounds;) {
    PenalizedShell total(model, proxy, pairs, options);
    if (motion_bounded) chunk.max_iterations = std::max(1, iterations_left);
    ObjectiveAtParameter total_at(total.energy, excess_angle);
    const NewtonResult r = NewtonSolver(chunk).minimize(total_at, y, fixed_dofs);
    y = r.x;
    ++out.solves;
    out.newton_iterations += r.iterations;
    out.factorizations += r.factorizations;
    iterations_left -= std::max(1, r.iterations);
    if (r.status == NewtonStatus::TravelLimit) {
      if (iterations_left <= 0) {
        out.message =
            "relaxation failed: newton.max_iterations = " + std::to_string(newton.max_iterations) +
            " used up while moving";
        return out;
      }
      // Moved as far as the pair set is trusted: go on with the pairs near the new state (a
      // union over a long way would only carry pairs left far behind).
      pairs = near_penalty_pairs(proxy, y, options);
      continue;
    }
    if (!r.converged()) {
      out.message = "relaxation failed: " + r.message;
      return out;
    }
    ++round;
    // Settled if y is also an equilibrium (to the Newton force tolerance) of the penalty on the
    // pairs near y itself, the energy a trace from y continues with.
    PenalizedShell own(model, proxy, near_penalty_pairs(proxy, y, options), options);
    Eigen::VectorXd g;
    const double e = own.energy.evaluate(y, excess_angle, &g, nullptr);
    for (const Eigen::Index i : fixed_dofs) g[i] = 0.0;  // reactions of the held dofs
    if (g.lpNorm<Eigen::Infinity>() <= newton.gradient_tolerance) {
      out.relaxed = true;
      out.energy = e;
      return out;
    }
    // Otherwise: if the set y was minimised with covers every pair near y (a vertex near two
    // triangles, e.g. between two layers, keeps both), y is an equilibrium of a penalty that
    // misses no contact, and is accepted; else minimise again with the union of both sets,
    // which only grows, so the rounds end.
    const ContactCandidates merged = merge_contact_pairs(pairs, own.pairs);
    if (merged.size() == pairs.size()) {
      out.relaxed = true;
      out.energy = r.energy;
      return out;
    }
    pairs = merged;
  }
  out.message =
      "the pair set did not settle in " + std::to_string(max_rounds) + " relaxation rounds";
  return out;
}

namespace {

/// Whether y is a strict minimum of shell + penalty (pairs near y) at phi_e, the pins held: an
/// unshifted Cholesky factorisation of its Hessian succeeds. If not, `mode` is its lowest
/// eigenvector (the way off the saddle). Counts the test (and the eigensolve) in `work`.
bool strict_minimum(const ShellModel& model, const ContactProxy& proxy, double phi_e,
                    const Eigen::VectorXd& y, const std::vector<Eigen::Index>& pins,
                    const ContactBranchOptions& o, Eigen::VectorXd* mode,
                    ContactStepWork& work) {
  PenalizedShell total(model, proxy, near_penalty_pairs(proxy, y, o), o);
  ObjectiveAtParameter total_at(total.energy, phi_e);
  ++work.stability_tests;
  ++work.factorizations;
  if (hessian_is_positive_definite(total_at, y, pins, 0.0)) return true;
  ++work.eigen_solves;
  EigenpairOptions eig;
  eig.count = 1;
  const Eigenpairs lowest = lowest_eigenpairs(total_at, y, pins, eig);
  // Positive (to the eigensolver's tolerance) where the factorisation failed on rounding.
  if (lowest.values[0] > 0.0) return true;
  *mode = lowest.vectors.col(0);
  return false;
}

/// Whether relax_with_contact relaxed y, its cost added to `work`; `why` gets its message on
/// failure.
bool relax_counted(const ShellModel& model, double phi_e, const ContactProxy& proxy,
                   Eigen::VectorXd& y, const std::vector<Eigen::Index>& pins,
                   const ContactBranchOptions& o, const NewtonOptions& newton, std::string* why,
                   ContactStepWork& work) {
  const ContactRelaxation r = relax_with_contact(model, phi_e, proxy, y, pins, o, newton);
  ++work.tries;
  work.solves += r.solves;
  work.newton_iterations += r.newton_iterations;
  work.factorizations += r.factorizations;
  if (!r.relaxed) *why = r.message;
  return r.relaxed;
}

}  // namespace

ContactGrowthResult grow_with_contact(
    const ShellModel& model, const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    double phi0, double phi_target, const std::vector<Eigen::Index>& fixed_dofs,
    const ContactGrowthOptions& options,
    const std::function<void(const ContactGrowthPoint&)>& on_point,
    const BranchSample* previous) {
  if (!(options.max_step > 0.0 && options.min_step > 0.0 && options.min_step <= options.max_step))
    throw std::invalid_argument("ContactGrowthOptions: need 0 < min_step <= max_step");
  if (!(options.initial_step >= 0.0 && options.initial_step <= options.max_step))
    throw std::invalid_argument("ContactGrowthOptions: need 0 <= initial_step <= max_step");
  if (options.max_saddle_escapes < 0)
    throw std::invalid_argument("ContactGrowthOptions::max_saddle_escapes must be >= 0");
  if (previous && previous->x.size() != 0 && previous->x.size() != x0.size())
    throw std::invalid_argument("grow_with_contact: the previous state has " +
                                std::to_string(previous->x.size()) + " entries, x0 " +
                                std::to_string(x0.size()));
  const ContactBranchOptions& o = options.contact;
  const double direction = phi_target >= phi0 ? 1.0 : -1.0;
  ContactGrowthResult out;
  Eigen::VectorXd x = x0;
  double phi = phi0;
  double step = options.initial_step > 0.0 ? options.initial_step : options.max_step;
  out.last.sample.sample.x = x0;
  out.last.sample.sample.parameter = phi0;
  if (previous) {
    out.before_last.x = previous->x;
    out.before_last.parameter = previous->parameter;
  }
  std::vector<Eigen::Index> pins = fixed_dofs;
  ContactStepWork work;  // of the point being sought, over all its tries
  while (direction * (phi_target - phi) > 1e-12) {
    // Pins whose lever arm the deformation has taken away leave a nearly free spin, whose
    // eigenvalue near zero would also blur the strict-minimum test below.
    pins = rigid_pins_for_state(model, x, pins, o);
    const double next =
        direction > 0 ? std::min(phi + step, phi_target) : std::max(phi - step, phi_target);
    Eigen::VectorXd y;
    std::string why;
    bool accepted = false;
    bool from_prediction = false;
    int escapes = 0;
    Eigen::VectorXd mode;
    const BranchSample& before = out.before_last;
    Eigen::VectorXd shift;
    if (options.secant_predictor && before.x.size() == x.size() && before.parameter != phi) {
      shift = (x - before.x) * ((next - phi) / (phi - before.parameter));
      for (const Eigen::Index i : pins) shift[i] = 0.0;
      // After a slide (a dof moved farther than the pair search's margin in one step) the
      // extrapolation is no part of a smooth path and may fall into another basin: not tried.
      if (!(shift.lpNorm<Eigen::Infinity>() <= o.candidate_margin)) shift.resize(0);
    }
    if (shift.size() > 0) {
      const Eigen::VectorXd predicted = x + shift;
      y = predicted;
      accepted = !first_vertex_triangle_crossing(proxy, x, predicted, o.exclusion_radius) &&
                 relax_counted(model, next, proxy, y, pins, o, options.newton, &why, work) &&
                 (y - predicted).lpNorm<Eigen::Infinity>() <=
                     shift.lpNorm<Eigen::Infinity>() &&
                 strict_minimum(model, proxy, next, y, pins, o, &mode, work);
      ++(accepted ? out.predicted_steps : out.discarded_predictions);
      work.prediction_discarded = work.prediction_discarded || !accepted;
      from_prediction = accepted;
    }
    if (!accepted) {
      y = x;
      for (; escapes <= options.max_saddle_escapes; ++escapes) {
        if (!relax_counted(model, next, proxy, y, pins, o, options.newton, &why, work))
          break;
        if (strict_minimum(model, proxy, next, y, pins, o, &mode, work)) {
          accepted = true;
          break;
        }
        // A saddle: push along the negative mode and minimise again.
        const double sign = escapes % 2 == 0 ? 1.0 : -1.0;
        y += sign * (0.5 * o.contact_distance / mode.cwiseAbs().maxCoeff()) * mode;
        why = "a saddle after " + std::to_string(escapes + 1) + " pushes";
      }
    }
    if (!accepted) {
      ++out.failed_steps;
      ++work.halvings;
      step /= 2;
      if (step < options.min_step) {
        out.message = "step below min_step at phi_e = " + std::to_string(phi) + ": " + why;
        return out;
      }
      continue;
    }
    ++out.steps;
    out.before_last.x = x;
    out.before_last.parameter = phi;
    phi = next;
    x = y;
    BranchSample s;
    s.parameter = phi;
    s.x = x;
    s.tangent_state = Eigen::VectorXd::Zero(x.size());
    s.tangent_parameter = direction;
    step = std::min(options.max_step, 1.5 * step);
    s.next_step = step;
    ContactGrowthPoint point;
    point.sample = describe_contact_sample(model, proxy, s, near_penalty_pairs(proxy, x, o), o);
    point.pins = pins;
    point.saddle_escapes = escapes;
    point.jumped = escapes > 0;
    point.from_prediction = from_prediction;
    point.work = work;
    work = ContactStepWork{};
    out.last = point;
    if (on_point) on_point(point);
  }
  out.reached_target = true;
  return out;
}

}  // namespace growshell
