#include "solvers/continuation/growth_path.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/objective_at_parameter.hpp"
#include "solvers/newton/cholmod_factorization.hpp"
#include "solvers/newton/fixed_dof_elimination.hpp"
#include "solvers/stability/positive_definiteness.hpp"

namespace growshell {

Eigen::VectorXd equilibrium_tangent(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                    double excess_angle, const std::vector<Eigen::Index>& fixed_dofs) {
  Eigen::SparseMatrix<double> hessian = model.hessian_pattern();
  const FixedDofElimination fixed(hessian, fixed_dofs);
  model.evaluate(x, excess_angle, nullptr, &hessian);
  fixed.apply(hessian);
  CholmodFactorization cholesky;
  cholesky.analyze(hessian);
  if (!cholesky.factorize(hessian, 0.0).positive_definite) return {};
  Eigen::VectorXd rhs = -model.gradient_parameter_derivative(x, excess_angle);
  fixed.zero_fixed(rhs);
  Eigen::VectorXd tangent = cholesky.solve(rhs);
  fixed.zero_fixed(tangent);
  return tangent;
}

GrowthPathResult grow_along_path(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                                 double phi_start, double phi_target,
                                 const std::vector<Eigen::Index>& fixed_dofs,
                                 const NewtonSolver& newton,
                                 const std::function<Eigen::VectorXd(int attempt)>& perturb,
                                 const GrowthPathOptions& options,
                                 const std::function<void(const GrowthPathPoint&)>& on_point,
                                 const std::function<void(const NewtonIterate&)>& on_iterate,
                                 const std::function<void(const GrowthPathFailedStep&)>&
                                     on_failed_step) {
  if (!(options.max_step > 0.0) || !(options.min_step > 0.0) || options.min_step > options.max_step)
    throw std::invalid_argument("GrowthPathOptions: need 0 < min_step <= max_step");
  if (!(options.step_growth >= 1.0))
    throw std::invalid_argument("GrowthPathOptions: step_growth must be >= 1");
  if (x_start.size() != model.dimension())
    throw std::invalid_argument("grow_along_path: x_start has the wrong size");
  NewtonSolver solver = newton;
  GrowthPathResult out;
  out.last.excess_angle = phi_start;
  out.last.x = x_start;
  const double direction = phi_target >= phi_start ? 1.0 : -1.0;
  double step = std::min(options.max_step, std::abs(phi_target - phi_start));
  Eigen::VectorXd tangent;  // dx/dphi at out.last, when known
  while (direction * (phi_target - out.last.excess_angle) > 0.0) {
    const double phi = std::abs(phi_target - out.last.excess_angle) <= step
                           ? phi_target
                           : out.last.excess_angle + direction * step;
    ObjectiveAtParameter energy(model, phi);
    Eigen::VectorXd guess = out.last.x;
    if (options.tangent_predictor && tangent.size() == guess.size())
      guess += (phi - out.last.excess_angle) * tangent;
    NewtonResult result = solver.minimize(energy, guess, fixed_dofs, on_iterate);
    if (!result.converged() && tangent.size() == guess.size()) {
      // The predictor can overshoot near a fold or a bifurcation: retry from the last point.
      result = solver.minimize(energy, out.last.x, fixed_dofs, on_iterate);
    }
    GrowthPathPoint point;
    point.excess_angle = phi;
    point.newton_iterations = result.iterations;
    bool stable = result.converged() && hessian_is_positive_definite(energy, result.x, fixed_dofs);
    while (result.converged() && !stable && point.saddle_escapes < options.max_saddle_escapes) {
      ++point.saddle_escapes;
      result = solver.minimize(energy, result.x + perturb(point.saddle_escapes), fixed_dofs,
                               on_iterate);
      point.newton_iterations += result.iterations;
      stable = result.converged() && hessian_is_positive_definite(energy, result.x, fixed_dofs);
    }
    if (!stable) {
      ++out.failed_steps;
      out.message = result.converged() ? "no stable equilibrium found after " +
                                             std::to_string(point.saddle_escapes) +
                                             " perturbations of a saddle"
                                       : result.message;
      const bool give_up = step / 2 < options.min_step;
      if (on_failed_step)
        on_failed_step({out.last.excess_angle, phi, out.message, give_up ? 0.0 : step / 2});
      if (give_up) {
        out.message = "path ended at phi_e = " + std::to_string(out.last.excess_angle) +
                      ": step to " + std::to_string(phi) + " failed (" + out.message + ")";
        return out;
      }
      step /= 2;
      continue;
    }
    point.x = std::move(result.x);
    out.last = std::move(point);
    ++out.steps;
    if (on_point) on_point(out.last);
    if (options.tangent_predictor) tangent = equilibrium_tangent(model, out.last.x, out.last.excess_angle, fixed_dofs);
    step = std::min(options.max_step, options.step_growth * step);
  }
  out.reached_target = true;
  out.message.clear();
  return out;
}

}  // namespace growshell
