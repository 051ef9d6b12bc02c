#include "solvers/dynamics/damped_dynamics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "solvers/stability/mass_normalized_eigenpairs.hpp"

namespace growshell {

namespace {

using Clock = std::chrono::steady_clock;

void validate(const DampedDynamicsOptions& o) {
  const auto fail = [](const char* field, const char* range) {
    throw std::invalid_argument(std::string("DampedDynamicsOptions::") + field + " must be " +
                                range);
  };
  if (!(o.gradient_tolerance > 0.0)) fail("gradient_tolerance", "> 0");
  if (o.max_steps < 1) fail("max_steps", ">= 1");
  if (!(o.max_seconds > 0.0)) fail("max_seconds", "> 0");
  if (!(o.step_fraction > 0.0 && o.step_fraction < 1.0)) fail("step_fraction", "in (0, 1)");
  if (o.power_iterations < 1) fail("power_iterations", ">= 1");
  if (!(o.damping_ratio > 0.0 && o.damping_ratio <= 1.0)) fail("damping_ratio", "in (0, 1]");
  if (!(o.fire_alpha_start > 0.0 && o.fire_alpha_start < 1.0))
    fail("fire_alpha_start", "in (0, 1)");
  if (!(o.fire_alpha_decay > 0.0 && o.fire_alpha_decay <= 1.0))
    fail("fire_alpha_decay", "in (0, 1]");
  if (!(o.fire_step_increase >= 1.0)) fail("fire_step_increase", ">= 1");
  if (!(o.fire_step_decrease > 0.0 && o.fire_step_decrease < 1.0))
    fail("fire_step_decrease", "in (0, 1)");
  if (o.fire_delay_steps < 0) fail("fire_delay_steps", ">= 0");
  if (!(o.fire_max_step_factor >= 1.0)) fail("fire_max_step_factor", ">= 1");
}

/// y = H v for the symmetric H given by its upper triangle.
Eigen::VectorXd symmetric_product(const Eigen::SparseMatrix<double>& upper,
                                  const Eigen::VectorXd& v) {
  Eigen::VectorXd y = upper * v + upper.transpose() * v;
  y -= upper.diagonal().cwiseProduct(v);
  return y;
}

/// The largest eigenvalue of M^-1 H on the free dofs (H at x0), by power iteration on
/// M^-1/2 H M^-1/2 from a fixed start, raised by 5 % against its underestimate.
double largest_frequency_squared(const Eigen::SparseMatrix<double>& upper,
                                 const Eigen::VectorXd& mass, const Eigen::VectorXd& free,
                                 int iterations) {
  const Eigen::VectorXd scale = mass.cwiseSqrt().cwiseInverse().cwiseProduct(free);
  Eigen::VectorXd v(mass.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) v(i) = free(i) * (1.0 + 0.5 * std::sin(1.7 * i));
  v.normalize();
  double lambda = 0.0;
  for (int k = 0; k < iterations; ++k) {
    Eigen::VectorXd w = scale.cwiseProduct(symmetric_product(upper, scale.cwiseProduct(v)));
    lambda = v.dot(w);
    const double norm = w.norm();
    if (!(norm > 0.0)) break;
    v = w / norm;
  }
  return 1.05 * std::abs(lambda);
}

}  // namespace

DampedDynamicsResult relax_by_damped_dynamics(SparseObjective& objective,
                                              const Eigen::Ref<const Eigen::VectorXd>& x0,
                                              const Eigen::VectorXd& mass,
                                              const std::vector<Eigen::Index>& fixed_dofs,
                                              const DampedDynamicsOptions& options) {
  validate(options);
  const Eigen::Index n = objective.dimension();
  if (x0.size() != n || mass.size() != n)
    throw std::invalid_argument("relax_by_damped_dynamics: x0 and mass need " + std::to_string(n) +
                                " entries");
  if (!(mass.minCoeff() > 0.0))
    throw std::invalid_argument("relax_by_damped_dynamics: every mass must be > 0");
  Eigen::VectorXd free = Eigen::VectorXd::Ones(n);
  for (const Eigen::Index d : fixed_dofs) {
    if (d < 0 || d >= n)
      throw std::invalid_argument("relax_by_damped_dynamics: fixed dof " + std::to_string(d) +
                                  " out of range");
    free(d) = 0.0;
  }
  const auto t0 = Clock::now();
  DampedDynamicsResult out;
  out.x = x0;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = objective.hessian_pattern();
  out.energy = objective.evaluate(out.x, &g, &H);
  ++out.gradient_evaluations;
  const double omega_max =
      std::sqrt(largest_frequency_squared(H, mass, free, options.power_iterations));
  if (!(omega_max > 0.0) || !std::isfinite(omega_max)) {
    out.message = "no stiffness at the start (largest frequency " + std::to_string(omega_max) + ")";
    return out;
  }
  double dt = options.step_fraction * 2.0 / omega_max;
  out.time_step = dt;
  double damping = 0.0;  // c of the viscous force -c M v
  if (options.integrator == DampedIntegrator::ViscousVerlet) {
    EigenpairOptions eig;
    eig.count = 1;
    const Eigenpairs lowest =
        lowest_mass_normalized_eigenpairs(objective, out.x, mass, fixed_dofs, eig);
    // A negative lowest eigenvalue (a saddle at the start) gives no softest frequency; its
    // magnitude sets the damping then.
    damping = 2.0 * options.damping_ratio * std::sqrt(std::abs(lowest.values[0]));
  }
  const Eigen::VectorXd inverse_mass = mass.cwiseInverse().cwiseProduct(free);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd a = -g.cwiseProduct(inverse_mass);
  const double dt_max = options.fire_max_step_factor * dt;
  double alpha = options.fire_alpha_start;
  int positive_steps = 0;
  const auto free_gradient_norm = [&free](const Eigen::VectorXd& grad) {
    return grad.cwiseProduct(free).lpNorm<Eigen::Infinity>();
  };
  out.gradient_inf_norm = free_gradient_norm(g);
  while (true) {
    if (!std::isfinite(out.energy) || !std::isfinite(out.gradient_inf_norm)) {
      out.message = "non-finite energy or force after " + std::to_string(out.steps) + " steps";
      break;
    }
    if (out.gradient_inf_norm <= options.gradient_tolerance) {
      out.converged = true;
      std::ostringstream m;
      m << "converged in " << out.steps << " steps (force " << out.gradient_inf_norm << ")";
      out.message = m.str();
      break;
    }
    if (out.steps >= options.max_steps) {
      out.message = "max_steps = " + std::to_string(options.max_steps) + " reached";
      break;
    }
    if (out.steps % 64 == 0 &&
        std::chrono::duration<double>(Clock::now() - t0).count() > options.max_seconds) {
      out.message = "max_seconds reached after " + std::to_string(out.steps) + " steps";
      break;
    }
    if (options.integrator == DampedIntegrator::Fire) {
      // Power of the forces: downhill keeps going (faster), uphill stops the sheet.
      const double power = a.cwiseProduct(mass).dot(v);
      if (power > 0.0) {
        if (++positive_steps > options.fire_delay_steps) {
          dt = std::min(dt * options.fire_step_increase, dt_max);
          alpha *= options.fire_alpha_decay;
        }
      } else {
        positive_steps = 0;
        dt *= options.fire_step_decrease;
        alpha = options.fire_alpha_start;
        out.x -= 0.5 * dt * v;  // back half a step along the overshoot
        v.setZero();
      }
      v += dt * a;
      const double v_norm = v.norm(), a_norm = a.norm();
      if (a_norm > 0.0) v = (1.0 - alpha) * v + alpha * (v_norm / a_norm) * a;
      out.x += dt * v;
      out.energy = objective.evaluate(out.x, &g, nullptr);
      a = -g.cwiseProduct(inverse_mass);
    } else {
      // Velocity Verlet with the viscous force taken half explicitly, half implicitly.
      const Eigen::VectorXd v_half = v + 0.5 * dt * (a - damping * v);
      out.x += dt * v_half.cwiseProduct(free);
      out.energy = objective.evaluate(out.x, &g, nullptr);
      a = -g.cwiseProduct(inverse_mass);
      v = (v_half + 0.5 * dt * a) / (1.0 + 0.5 * dt * damping);
    }
    ++out.gradient_evaluations;
    ++out.steps;
    out.gradient_inf_norm = free_gradient_norm(g);
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

}  // namespace growshell
