#include "solvers/newton/newton_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "solvers/newton/cholmod_factorization.hpp"
#include "solvers/newton/fixed_dof_elimination.hpp"

namespace growshell {
namespace {

// Energies that agree to this relative precision are treated as equal in the line search:
// near a minimum the Newton decrease falls below the rounding noise of a sum of many element
// energies, and the gradient (not the energy) then decides whether a step made progress.
constexpr double kEnergyNoise = 128.0 * std::numeric_limits<double>::epsilon();

// Beyond this multiple of the Gershgorin bound on |eigenvalues| a shift must have made the
// matrix positive definite; failing there means the factorisation itself is broken.
constexpr double kShiftCapOverGershgorin = 1e3;

// NewtonOptions::adaptive_shift: the first shift tried after the unshifted Hessian failed and no
// earlier shift is known, relative to the mean |diagonal|.
constexpr double kAdaptiveFirstShift = 1e-4;

bool all_finite(const Eigen::VectorXd& v) { return v.allFinite(); }

std::string sci(double v) {
  std::ostringstream s;
  s.precision(3);
  s << std::scientific << v;
  return s.str();
}

}  // namespace

NewtonSolver::NewtonSolver(NewtonOptions options) : options_(options) {
  const NewtonOptions& o = options_;
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("NewtonOptions: " + what);
  };
  if (o.max_iterations < 0)
    fail("max_iterations = " + std::to_string(o.max_iterations) + " must be >= 0");
  if (!(o.gradient_tolerance > 0.0) || !std::isfinite(o.gradient_tolerance)) {
    fail("gradient_tolerance = " + sci(o.gradient_tolerance) + " must be finite and > 0");
  }
  if (!(o.decrement_tolerance >= 0.0) || !std::isfinite(o.decrement_tolerance)) {
    fail("decrement_tolerance = " + sci(o.decrement_tolerance) + " must be finite and >= 0");
  }
  if (!(o.armijo_c1 > 0.0 && o.armijo_c1 < 1.0)) {
    fail("armijo_c1 = " + sci(o.armijo_c1) + " must lie in (0, 1)");
  }
  if (o.max_line_search_steps < 1) {
    fail("max_line_search_steps = " + std::to_string(o.max_line_search_steps) + " must be >= 1");
  }
  if (!(o.max_step_inf_norm > 0.0)) {
    fail("max_step_inf_norm = " + sci(o.max_step_inf_norm) + " must be > 0");
  }
  if (!(o.max_travel > 0.0)) {
    fail("max_travel = " + sci(o.max_travel) + " must be > 0");
  }
  if (!(o.shift_initial_factor > 0.0) || !std::isfinite(o.shift_initial_factor)) {
    fail("shift_initial_factor = " + sci(o.shift_initial_factor) + " must be finite and > 0");
  }
  if (!(o.shift_growth > 1.0) || !std::isfinite(o.shift_growth)) {
    fail("shift_growth = " + sci(o.shift_growth) + " must be finite and > 1");
  }
}

NewtonResult NewtonSolver::minimize(SparseObjective& objective,
                                    const Eigen::Ref<const Eigen::VectorXd>& x0,
                                    const std::vector<Eigen::Index>& fixed_dofs,
                                    const std::function<void(const NewtonIterate&)>& on_iterate) {
  const NewtonOptions& opt = options_;
  const Eigen::Index n = objective.dimension();
  if (x0.size() != n) {
    throw std::invalid_argument("NewtonSolver::minimize: x0 has size " + std::to_string(x0.size()) +
                                ", objective dimension is " + std::to_string(n));
  }
  Eigen::SparseMatrix<double> hessian = objective.hessian_pattern();
  if (hessian.rows() != n || hessian.cols() != n) {
    throw std::invalid_argument("NewtonSolver::minimize: hessian_pattern() is " +
                                std::to_string(hessian.rows()) + " x " +
                                std::to_string(hessian.cols()) + ", expected " + std::to_string(n) +
                                " x " + std::to_string(n));
  }
  const FixedDofElimination fixed = [&] {
    try {
      return FixedDofElimination(hessian, fixed_dofs);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("NewtonSolver::minimize: ") + e.what());
    }
  }();
  const Eigen::Index n_free = fixed.free_count();

  NewtonResult result;
  Eigen::VectorXd x = x0;
  Eigen::VectorXd gradient(n);
  double energy = objective.evaluate(x, &gradient, nullptr);
  if (gradient.size() != n) {
    throw std::logic_error("NewtonSolver::minimize: objective returned a gradient of size " +
                           std::to_string(gradient.size()) + ", expected " + std::to_string(n));
  }
  auto finish = [&](NewtonStatus status, std::string message, const Eigen::VectorXd& fx, double fe,
                    const Eigen::VectorXd& fg) {
    result.status = status;
    result.message = std::move(message);
    result.x = fx;
    result.energy = fe;
    result.gradient = fg;
    return result;
  };
  if (!std::isfinite(energy) || !all_finite(gradient)) {
    return finish(NewtonStatus::NonFiniteValue,
                  std::string("non-finite ") + (std::isfinite(energy) ? "gradient" : "energy") +
                      " at the initial point x0",
                  x, energy, gradient);
  }
  double gradient_norm = fixed.free_inf_norm(gradient);
  if (gradient_norm <= opt.gradient_tolerance || n_free == 0) {
    return finish(NewtonStatus::Converged,
                  "converged at x0: free gradient inf-norm " + sci(gradient_norm), x, energy,
                  gradient);
  }

  CholmodFactorization cholesky;
  cholesky.analyze(hessian);

  // Buffers reused across iterations.
  Eigen::VectorXd best_x = x;
  double best_energy = energy;
  Eigen::VectorXd best_gradient = gradient;
  Eigen::VectorXd rhs(n);
  Eigen::VectorXd step(n);
  Eigen::VectorXd x_trial(n);
  Eigen::VectorXd gradient_trial(n);
  Eigen::VectorXd row_abs_sum(n);
  double last_shift = 0.0;
  double last_alpha = 1.0;
  result.log.reserve(static_cast<size_t>(std::min(opt.max_iterations, 256)));

  auto fail_at_best = [&](NewtonStatus status, const std::string& message) {
    return finish(status, message, best_x, best_energy, best_gradient);
  };

  for (int iteration = 1; iteration <= opt.max_iterations; ++iteration) {
    // Built only on failure: the iteration itself allocates nothing but the solve's vector.
    auto where = [&] {
      return "iteration " + std::to_string(iteration) + " (free gradient inf-norm " +
             sci(gradient_norm) + ")";
    };
    objective.evaluate(x, nullptr, &hessian);
    double* values = hessian.valuePtr();
    const Eigen::Index nnz = hessian.nonZeros();
    for (Eigen::Index k = 0; k < nnz; ++k) {
      if (!std::isfinite(values[k])) {
        return fail_at_best(NewtonStatus::NonFiniteValue, "non-finite Hessian entry at " + where());
      }
    }
    // Fixed dofs decouple: their step is zero and their pivot has the typical magnitude.
    const double mean_diagonal = fixed.apply(hessian);

    // Gershgorin bound on the spectral radius (upper triangle mirrored).
    row_abs_sum.setZero();
    {
      const int* outer = hessian.outerIndexPtr();
      const int* inner = hessian.innerIndexPtr();
      for (Eigen::Index col = 0; col < n; ++col) {
        for (int k = outer[col]; k < outer[col + 1]; ++k) {
          row_abs_sum[inner[k]] += std::abs(values[k]);
          if (inner[k] != col) row_abs_sum[col] += std::abs(values[k]);
        }
      }
    }
    const double shift_cap =
        kShiftCapOverGershgorin * std::max(row_abs_sum.maxCoeff(), mean_diagonal);

    // Shift sequence: start one growth factor below the last successful shift, trying the
    // unshifted Hessian first once that start falls below the smallest meaningful shift
    // (adaptive_shift: as the last line search says, see NewtonOptions).
    const double shift_floor = opt.shift_initial_factor * mean_diagonal;
    double shift_start = last_shift / opt.shift_growth;
    bool try_unshifted = shift_start < shift_floor;
    if (opt.adaptive_shift) {
      try_unshifted = last_shift <= kAdaptiveFirstShift * mean_diagonal &&
                      (last_alpha == 1.0 || last_shift == 0.0);
      if (last_alpha < 0.25)
        shift_start = std::max(last_shift, shift_floor) * opt.shift_growth;
      else if (last_alpha < 1.0)
        shift_start = last_shift;
      // Without a shift to go by (the last Hessian was positive definite), an indefinite one
      // is shifted from 1e-4 of its mean diagonal up rather than from the numerical zero: a
      // negative curvature that small is a nearly free mode, not worth eight factorisations.
      shift_start = std::max(shift_start, last_shift == 0.0 ? kAdaptiveFirstShift * mean_diagonal
                                                            : shift_floor);
    }
    int attempts = 0;
    bool factorized = false;
    double shift = 0.0;
    if (try_unshifted) {
      ++attempts;
      ++result.factorizations;
      factorized = cholesky.factorize(hessian, 0.0).positive_definite;
      shift = factorized ? 0.0 : std::max(shift_start, shift_floor);
    } else {
      shift = shift_start;
    }
    while (!factorized) {
      if (shift > shift_cap) {
        return fail_at_best(NewtonStatus::FactorizationFailed,
                            "Hessian not positive definite even with shift " + sci(shift) +
                                " after " + std::to_string(attempts) + " attempts at " + where());
      }
      ++attempts;
      ++result.factorizations;
      factorized = cholesky.factorize(hessian, shift).positive_definite;
      if (!factorized) shift *= opt.shift_growth;
    }
    last_shift = shift;

    rhs = -gradient;
    fixed.zero_fixed(rhs);
    step = cholesky.solve(rhs);
    fixed.zero_fixed(step);
    if (!all_finite(step)) {
      return fail_at_best(NewtonStatus::NonFiniteValue,
                          "non-finite Newton step (shift " + sci(shift) + ") at " + where());
    }
    double slope = -rhs.dot(step);
    if (!(slope < 0.0)) {
      // (H + shift I) is positive definite, so only rounding can get here; the scaled
      // steepest-descent direction is a descent direction whatever the Hessian.
      step = rhs / (mean_diagonal + shift);
      slope = -rhs.dot(step);
    }
    if (shift <= shift_floor && -0.5 * slope <= opt.decrement_tolerance) {
      return finish(NewtonStatus::Converged,
                    "converged in " + std::to_string(iteration - 1) +
                        " iterations: Newton decrement " + sci(-0.5 * slope) +
                        " J, free gradient inf-norm " + sci(gradient_norm),
                    x, energy, gradient);
    }
    const double step_norm = step.lpNorm<Eigen::Infinity>();
    if (step_norm > opt.max_step_inf_norm) {
      const double scale = opt.max_step_inf_norm / step_norm;
      step *= scale;
      slope *= scale;
    }

    double alpha = 1.0;
    bool accepted = false;
    double trial_energy = 0.0;
    double trial_gradient_norm = 0.0;
    const double energy_noise = kEnergyNoise * std::abs(energy);
    for (int trial = 0; trial < opt.max_line_search_steps; ++trial) {
      x_trial.noalias() = x + alpha * step;
      trial_energy = objective.evaluate(x_trial, &gradient_trial, nullptr);
      // A non-finite energy or gradient marks x_trial as outside the energy's domain.
      if (std::isfinite(trial_energy) && all_finite(gradient_trial)) {
        trial_gradient_norm = fixed.free_inf_norm(gradient_trial);
        const bool armijo = trial_energy <= energy + opt.armijo_c1 * alpha * slope;
        const bool within_noise =
            trial_energy <= energy + energy_noise && trial_gradient_norm < gradient_norm;
        if (armijo || within_noise) {
          accepted = true;
          break;
        }
      }
      alpha *= 0.5;
    }
    if (!accepted) {
      return fail_at_best(NewtonStatus::LineSearchFailed,
                          "line search found no sufficient decrease in " +
                              std::to_string(opt.max_line_search_steps) +
                              " trials (last step length " + sci(2.0 * alpha) + ", shift " +
                              sci(shift) + ") at " + where());
    }
    last_alpha = alpha;
    x.swap(x_trial);
    gradient.swap(gradient_trial);
    energy = trial_energy;
    gradient_norm = trial_gradient_norm;
    if (energy < best_energy) {
      best_x = x;
      best_energy = energy;
      best_gradient = gradient;
    }

    NewtonIterate record;
    record.iteration = iteration;
    record.energy = energy;
    record.gradient_inf_norm = gradient_norm;
    record.step_length = alpha;
    record.step_inf_norm = alpha * step.lpNorm<Eigen::Infinity>();
    record.shift = shift;
    record.factorization_attempts = attempts;
    result.log.push_back(record);
    result.iterations = iteration;
    if (on_iterate) on_iterate(record);

    if (gradient_norm <= opt.gradient_tolerance) {
      return finish(NewtonStatus::Converged,
                    "converged in " + std::to_string(iteration) +
                        " iterations: free gradient inf-norm " + sci(gradient_norm) +
                        ", last shift " + sci(shift),
                    x, energy, gradient);
    }
    if (std::isfinite(opt.max_travel)) {
      const double travel = (x - x0).lpNorm<Eigen::Infinity>();
      if (travel >= opt.max_travel)
        return finish(NewtonStatus::TravelLimit,
                      "moved " + sci(travel) + " from x0 (max_travel " + sci(opt.max_travel) +
                          ") in " + std::to_string(iteration) +
                          " iterations: free gradient inf-norm " + sci(gradient_norm),
                      x, energy, gradient);
    }
  }
  return fail_at_best(NewtonStatus::MaxIterations,
                      "reached max_iterations = " + std::to_string(opt.max_iterations) +
                          " with free gradient inf-norm " + sci(gradient_norm) + " (tolerance " +
                          sci(opt.gradient_tolerance) + "), last shift " + sci(last_shift));
}

const char* to_string(NewtonStatus status) {
  switch (status) {
    case NewtonStatus::Converged:
      return "Converged";
    case NewtonStatus::MaxIterations:
      return "MaxIterations";
    case NewtonStatus::LineSearchFailed:
      return "LineSearchFailed";
    case NewtonStatus::NonFiniteValue:
      return "NonFiniteValue";
    case NewtonStatus::FactorizationFailed:
      return "FactorizationFailed";
    case NewtonStatus::TravelLimit:
      return "TravelLimit";
  }
  return "unknown";
}

}  // namespace growshell
