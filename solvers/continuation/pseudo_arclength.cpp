#include "solvers/continuation/pseudo_arclength.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "solvers/newton/fixed_dof_elimination.hpp"
#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {
namespace {

/// Adds the wall time of its scope to a counter.
class ScopedSeconds {
 public:
  explicit ScopedSeconds(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ScopedSeconds() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedSeconds(const ScopedSeconds&) = delete;
  ScopedSeconds& operator=(const ScopedSeconds&) = delete;

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

/// Newton on the bordered system and the tangent/inertia at converged points. Owns the
/// Hessian buffer and the factorisation (analysed once).
class BranchSolver {
 public:
  BranchSolver(const ParametrizedObjective& family, const std::vector<Eigen::Index>& fixed_dofs,
               const ArclengthOptions& options)
      : family_(family),
        hessian_(family.hessian_pattern()),
        fixed_(hessian_, fixed_dofs),
        options_(options),
        weight_(options.state_weight / static_cast<double>(std::max<Eigen::Index>(1, fixed_.free_count()))) {
    factorization_.analyze(hessian_);
  }

  double weight() const { return weight_; }

  /// Weighted inner product of two tangents.
  double dot(const Eigen::VectorXd& ax, double al, const Eigen::VectorXd& bx, double bl) const {
    return weight_ * ax.dot(bx) + al * bl;
  }

  /// Linearises at (x, lambda): gradient (fixed entries zeroed), factorised Hessian and
  /// d(gradient)/d(lambda). False if anything is not finite or the factorisation failed.
  bool linearize(const Eigen::VectorXd& x, double lambda) {
    if (!std::isfinite(lambda) || !x.allFinite()) return false;
    // A diverging corrector may leave the family's domain.
    if (!family_.accepts_parameter(lambda)) return false;
    ++cost_.linearizations;
    double e = 0.0;
    {
      ScopedSeconds timer(cost_.assembly_seconds);
      e = family_.evaluate(x, lambda, &gradient_, &hessian_);
    }
    if (!std::isfinite(e) || !gradient_.allFinite()) return false;
    fixed_.zero_fixed(gradient_);
    fixed_.apply(hessian_);
    const Eigen::Map<const Eigen::VectorXd> values(hessian_.valuePtr(), hessian_.nonZeros());
    if (!values.allFinite()) return false;
    factorized_ = false;
    try {
      ++cost_.factorizations;
      ScopedSeconds timer(cost_.factorization_seconds);
      factorization_.factorize(hessian_);
    } catch (const std::runtime_error&) {
      return false;
    }
    if (factorization_.zero_pivots() > 0) return false;
    {
      ScopedSeconds timer(cost_.assembly_seconds);
      parameter_derivative_ = family_.gradient_parameter_derivative(x, lambda);
    }
    fixed_.zero_fixed(parameter_derivative_);
    factorized_ = parameter_derivative_.allFinite();
    return factorized_;
  }

  /// Unit tangent at the last linearisation, oriented along (rx, rl).
  void tangent(const Eigen::VectorXd& rx, double rl, Eigen::VectorXd& tx, double& tl) {
    Eigen::VectorXd b = timed_solve(parameter_derivative_);
    fixed_.zero_fixed(b);
    const double s = 1.0 / std::sqrt(weight_ * b.squaredNorm() + 1.0);
    tx = -s * b;
    tl = s;
    if (dot(tx, tl, rx, rl) < 0.0) {
      tx = -tx;
      tl = -tl;
    }
  }

  int negative_eigenvalues() const { return factorization_.negative_eigenvalues(); }

  /// H^-1 v at the last linearisation (fixed entries zero).
  Eigen::VectorXd solve_hessian(Eigen::VectorXd v) {
    fixed_.zero_fixed(v);
    Eigen::VectorXd y = timed_solve(v);
    fixed_.zero_fixed(y);
    return y;
  }

  /// Corrects the predictor (xp, lp) on the hyperplane through it orthogonal to (tx, tl).
  /// On success fills `sample` (state, inertia, tangent oriented along (tx, tl)) and sets
  /// step_factor(). With the chord corrector the iterations start from the last
  /// factorisation, if there is one, and Newton takes over where the chord stops contracting.
  /// With `analyse` false only the state and parameter are wanted (an event's bisection): the
  /// tangent and the stability index are left out, and so is a chord's final factorisation.
  /// `max_iterations` > 0 replaces options.max_corrector_iterations (a trace's start).
  bool correct(const Eigen::VectorXd& xp, double lp, const Eigen::VectorXd& tx, double tl,
               BranchSample& sample, bool analyse = true, int max_iterations = 0) {
    const int max_newton = max_iterations > 0 ? max_iterations : options_.max_corrector_iterations;
    Eigen::VectorXd x = xp;
    double lambda = lp;
    const bool use_chord = options_.corrector == ArclengthOptions::Corrector::Chord && factorized_;
    int chord_iterations = 0;
    bool chord_converged = false;
    if (use_chord) {
      chord_converged = chord(xp, lp, tx, tl, x, lambda, chord_iterations);
      if (chord_converged && !analyse) {
        sample.x = x;
        sample.parameter = lambda;
        sample.corrector_iterations = chord_iterations;
        return true;
      }
      if (!chord_converged) ++cost_.chord_fallbacks;
    }
    // Newton from the predictor or from the chord's best iterate; a converged chord's point
    // converges at once, and is factorised here for its tangent and stability index.
    double first_residual = 0.0;
    for (int it = 0; it <= max_newton; ++it) {
      if (!linearize(x, lambda)) return false;
      const double residual = fixed_.free_inf_norm(gradient_);
      if (it == 0) first_residual = residual;
      if (residual <= options_.gradient_tolerance) {
        // After a chord that stopped contracting, its iterations count as one of Newton's.
        step_factor_ = chord_converged ? factor(options_.target_chord_iterations, chord_iterations)
                                       : factor(options_.target_iterations, use_chord ? it + 1 : it);
        return converged(x, lambda, chord_iterations + it, tx, tl, sample, analyse);
      }
      if (it == max_newton) return false;
      if (it > 0 && it == options_.stall_iterations &&
          residual > options_.stall_reduction * first_residual) {
        ++cost_.stalled_correctors;
        return false;
      }
      Eigen::VectorXd a = timed_solve(gradient_);
      Eigen::VectorXd b = timed_solve(parameter_derivative_);
      fixed_.zero_fixed(a);
      fixed_.zero_fixed(b);
      const double c = weight_ * tx.dot(x - xp) + tl * (lambda - lp);
      const double denominator = tl - weight_ * tx.dot(b);
      if (!(std::abs(denominator) > 0.0)) return false;
      const double dl = (weight_ * tx.dot(a) - c) / denominator;
      const Eigen::VectorXd dx = a + dl * b;
      const double t = update_fraction(x, lambda, dx, dl);
      x -= t * dx;
      lambda += t * dl;
      if (!x.allFinite() || !std::isfinite(lambda)) return false;
    }
    return false;
  }

  /// Makes (x, lambda) of `sample` the point the next chord starts from: after a bisection
  /// the last factorisation is of some point inside the bracket, and a trace must not depend
  /// on that (a trace resumed from a sample then takes the same steps as one that went on).
  void anchor_chord_at(const BranchSample& sample) {
    if (options_.corrector == ArclengthOptions::Corrector::Chord)
      linearize(sample.x, sample.parameter);
  }

  /// The factor by which the step control changes the step after the last successful
  /// correct(): target / iterations, in [1/2, 2].
  double step_factor() const { return step_factor_; }

  TraceCost& cost() { return cost_; }

 private:
  static double factor(int target, int iterations) {
    return std::clamp(static_cast<double>(target) / std::max(1, iterations), 0.5, 2.0);
  }

  /// Fills `sample` with the converged point (x, lambda) of the last linearisation: its
  /// inertia (or, if `analyse`, the caller's stability index) and, if `analyse`, its tangent.
  bool converged(const Eigen::VectorXd& x, double lambda, int iterations,
                 const Eigen::VectorXd& tx, double tl, BranchSample& sample, bool analyse) {
    sample.x = x;
    sample.parameter = lambda;
    sample.corrector_iterations = iterations;
    sample.negative_eigenvalues = negative_eigenvalues();
    if (!analyse) return true;
    tangent(tx, tl, sample.tangent_state, sample.tangent_parameter);
    if (options_.stability_index) {
      ++cost_.stability_evaluations;
      ScopedSeconds timer(cost_.stability_seconds);
      try {
        sample.negative_eigenvalues = options_.stability_index(sample);
      } catch (const std::runtime_error&) {
        return false;
      }
    }
    return true;
  }

  /// The free gradient's inf-norm at (x, lambda) from a gradient-only assembly (into
  /// gradient_); NaN where the family cannot be evaluated.
  double residual_at(const Eigen::VectorXd& x, double lambda) {
    if (!std::isfinite(lambda) || !x.allFinite() || !family_.accepts_parameter(lambda))
      return std::numeric_limits<double>::quiet_NaN();
    ++cost_.gradient_evaluations;
    double e = 0.0;
    {
      ScopedSeconds timer(cost_.assembly_seconds);
      e = family_.evaluate(x, lambda, &gradient_, nullptr);
    }
    if (!std::isfinite(e) || !gradient_.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    fixed_.zero_fixed(gradient_);
    return fixed_.free_inf_norm(gradient_);
  }

  /// The fraction t of the Newton update (x, lambda) -> (x - t dx, lambda + t dl) to take:
  /// 1, or with max_residual_backtracks > 0 the first of 1, 1/2, 1/4, ... at which the free
  /// gradient's 2-norm is below residual_growth_limit times its value at (x, lambda) (2^-max
  /// if none is). Uses gradient_ of the linearisation at (x, lambda) and overwrites it.
  double update_fraction(const Eigen::VectorXd& x, double lambda, const Eigen::VectorXd& dx,
                         double dl) {
    if (options_.max_residual_backtracks <= 0) return 1.0;
    const double bound = options_.residual_growth_limit * gradient_.norm();
    double t = 1.0;
    for (int k = 0; k < options_.max_residual_backtracks; ++k) {
      if (residual_at(x - t * dx, lambda + t * dl) >= 0.0 && gradient_.norm() <= bound) break;
      t *= 0.5;
      ++cost_.residual_backtracks;
    }
    return t;
  }

  /// Chord iterations on the bordered system with the last factorisation (and its
  /// d(gradient)/d(lambda)), from (x, lambda) = (xp, lp). True if the residual fell to the
  /// tolerance, with (x, lambda) the converged point; false where it stopped contracting, ran
  /// out of iterations or left the domain, with (x, lambda) its lowest-residual iterate.
  /// `iterations` counts the updates made.
  bool chord(const Eigen::VectorXd& xp, double lp, const Eigen::VectorXd& tx, double tl,
             Eigen::VectorXd& x, double& lambda, int& iterations) {
    Eigen::VectorXd b = timed_solve(parameter_derivative_);
    fixed_.zero_fixed(b);
    const double denominator = tl - weight_ * tx.dot(b);
    iterations = 0;
    if (!(std::abs(denominator) > 0.0)) return false;
    Eigen::VectorXd best_x = x;
    double best_lambda = lambda;
    double best = std::numeric_limits<double>::infinity();
    double previous = best;
    for (;; ++iterations) {
      const double residual = residual_at(x, lambda);
      if (!std::isfinite(residual)) break;
      if (residual < best) {
        best = residual;
        best_x = x;
        best_lambda = lambda;
      }
      if (residual <= options_.gradient_tolerance) return true;
      if (iterations >= options_.max_chord_iterations ||
          residual > options_.chord_contraction * previous)
        break;
      previous = residual;
      Eigen::VectorXd a = timed_solve(gradient_);
      fixed_.zero_fixed(a);
      const double c = weight_ * tx.dot(x - xp) + tl * (lambda - lp);
      const double dl = (weight_ * tx.dot(a) - c) / denominator;
      x -= a + dl * b;
      lambda += dl;
    }
    x = best_x;
    lambda = best_lambda;
    return false;
  }

  Eigen::VectorXd timed_solve(const Eigen::VectorXd& rhs) {
    ++cost_.solves;
    ScopedSeconds timer(cost_.solve_seconds);
    return factorization_.solve(rhs);
  }

  const ParametrizedObjective& family_;
  Eigen::SparseMatrix<double> hessian_;
  FixedDofElimination fixed_;
  ArclengthOptions options_;
  double weight_;
  SymmetricIndefiniteFactorization factorization_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd parameter_derivative_;
  /// The factorisation and parameter_derivative_ are those of one point (the last
  /// successful linearisation), which the chord corrector may start from.
  bool factorized_ = false;
  double step_factor_ = 1.0;
  TraceCost cost_;
};

}  // namespace

const char* to_string(SpecialPoint::Kind kind) {
  return kind == SpecialPoint::Kind::Fold ? "fold" : "branch_point";
}

BranchTrace trace_branch(const ParametrizedObjective& family, const Eigen::Ref<const Eigen::VectorXd>& x0,
                         double lambda0, int direction, const std::vector<Eigen::Index>& fixed_dofs,
                         const ArclengthOptions& options,
                         const std::function<void(const BranchSample&)>& on_sample,
                         const std::function<void(const SpecialPoint&)>& on_special) {
  return trace_branch_along(family, x0, lambda0, Eigen::VectorXd::Zero(x0.size()),
                            direction >= 0 ? 1.0 : -1.0, fixed_dofs, options, on_sample,
                            on_special);
}

Eigen::VectorXd critical_mode(const ParametrizedObjective& family, const Eigen::Ref<const Eigen::VectorXd>& x,
                              double lambda, const Eigen::Ref<const Eigen::VectorXd>& hint,
                              const std::vector<Eigen::Index>& fixed_dofs,
                              const ArclengthOptions& options, int iterations) {
  BranchSolver solver(family, fixed_dofs, options);
  if (!solver.linearize(x, lambda))
    throw std::runtime_error("critical_mode: the Hessian cannot be factorised at lambda = " +
                             std::to_string(lambda));
  Eigen::VectorXd y = hint;
  for (int k = 0; k < iterations; ++k) {
    y = solver.solve_hessian(y);
    const double norm = std::sqrt(solver.weight() * y.squaredNorm());
    if (!(norm > 0.0) || !std::isfinite(norm))
      throw std::runtime_error("critical_mode: inverse iteration broke down at lambda = " +
                               std::to_string(lambda) + " (hint orthogonal to the range?)");
    y /= norm;
  }
  return y;
}

namespace {

/// The step after a sample reached by a step of `step`: `factor` times longer (the solver's
/// step_factor(): longer when its corrector took fewer iterations than the target, shorter
/// when more), at most max_step.
double next_step_after(double step, double factor, const ArclengthOptions& options) {
  return std::min(options.max_step, step * factor);
}

/// The fold ahead of `last`, extrapolated from dlambda/ds at it and at the sample before it
/// (at arclength `previous_arclength`, with dlambda/ds `previous_slope`): where dlambda/ds,
/// taken linear in s, vanishes. None unless |dlambda/ds| falls between the two with its sign
/// kept (a fold approached, not passed).
std::optional<double> extrapolated_fold(double previous_arclength, double previous_slope,
                                        const BranchSample& last) {
  const double slope = last.tangent_parameter;
  const double ds = last.arclength - previous_arclength;
  if (!(ds > 0.0) || !(slope * previous_slope > 0.0) ||
      !(std::abs(slope) < std::abs(previous_slope)))
    return std::nullopt;
  const double curvature = (slope - previous_slope) / ds;  // d2lambda/ds2, opposite to slope
  return last.parameter - slope * slope / (2.0 * curvature);
}

/// The trace proper; trace_branch_along wraps it to collect the solver's cost.
BranchTrace trace_with_solver(BranchSolver& solver, const Eigen::Ref<const Eigen::VectorXd>& x0,
                               double lambda0,
                               const Eigen::Ref<const Eigen::VectorXd>& direction_state,
                               double direction_parameter,
                               const ArclengthOptions& options,
                               const std::function<void(const BranchSample&)>& on_sample,
                               const std::function<void(const SpecialPoint&)>& on_special,
                               const std::vector<BranchEvent>& events,
                               const std::function<void(const LocatedEvent&)>& on_event) {
  if (!(options.min_step > 0.0 && options.min_step <= options.initial_step &&
        options.initial_step <= options.max_step))
    throw std::invalid_argument("ArclengthOptions: need 0 < min_step <= initial_step <= max_step");
  if (!(options.gradient_tolerance > 0.0))
    throw std::invalid_argument("ArclengthOptions: gradient_tolerance must be > 0");
  if (options.max_residual_backtracks < 0)
    throw std::invalid_argument("ArclengthOptions: max_residual_backtracks must be >= 0");
  if (!(options.residual_growth_limit >= 1.0))
    throw std::invalid_argument("ArclengthOptions: residual_growth_limit must be >= 1");
  if (options.max_corrector_iterations < 1 || options.start_corrector_iterations < 0)
    throw std::invalid_argument(
        "ArclengthOptions: max_corrector_iterations must be >= 1 and start_corrector_iterations "
        ">= 0");
  if (!(options.fold_approach_tolerance >= 0.0))
    throw std::invalid_argument("ArclengthOptions: fold_approach_tolerance must be >= 0");
  if (options.stall_iterations < 0)
    throw std::invalid_argument("ArclengthOptions: stall_iterations must be >= 0");
  if (!(options.stall_reduction > 0.0 && options.stall_reduction <= 1.0))
    throw std::invalid_argument("ArclengthOptions: stall_reduction must be in (0, 1]");
  if (options.growth_pause_after_failure < 0 || options.initial_growth_pause < 0)
    throw std::invalid_argument(
        "ArclengthOptions: growth_pause_after_failure and initial_growth_pause must be >= 0");
  BranchTrace out;
  // The caller's callbacks and the event test functions, timed.
  const auto sample_done = [&](const BranchSample& s) {
    ScopedSeconds timer(solver.cost().callback_seconds);
    if (on_sample) on_sample(s);
  };
  const auto step_accepted = [&](const BranchSample& from, const BranchSample& to) {
    if (!options.accept_step) return true;
    ScopedSeconds timer(solver.cost().event_seconds);
    try {
      if (options.accept_step(from, to)) return true;
    } catch (const std::runtime_error&) {
    }
    ++solver.cost().rejected_steps;
    return false;
  };
  const auto event_value = [&](const BranchEvent& e, const BranchSample& s) {
    ScopedSeconds timer(solver.cost().event_seconds);
    return e.value(s);
  };

  // The start: correct (x0, lambda0) on the hyperplane orthogonal to the given direction and
  // orient its tangent along that direction.
  {
    const Eigen::VectorXd dx = direction_state;
    const double norm = std::sqrt(solver.dot(dx, direction_parameter, dx, direction_parameter));
    if (!(norm > 0.0)) throw std::invalid_argument("trace_branch_along: zero direction");
    BranchSample start;
    if (!solver.correct(x0, lambda0, dx / norm, direction_parameter / norm, start, true,
                        options.start_corrector_iterations)) {
      out.last.x = x0;
      out.last.parameter = lambda0;
      out.message = "the start is not an equilibrium the corrector can converge to";
      return out;
    }
    out.last = std::move(start);
    out.start_converged = true;
    out.last.next_step = options.initial_step;
    sample_done(out.last);
  }
  std::vector<double> event_values;
  for (const BranchEvent& e : events) event_values.push_back(event_value(e, out.last));

  double step = options.initial_step;
  const double cos_max = std::cos(options.max_tangent_angle);
  // The step control's factor of an accepted step, at most 1 during a growth pause (which
  // the step uses up).
  out.growth_pause_left = options.initial_growth_pause;
  const auto paused = [&out](double factor) {
    if (out.growth_pause_left <= 0) return factor;
    --out.growth_pause_left;
    return std::min(factor, 1.0);
  };
  // The sample before out.last (its arclength and dlambda/ds), for the fold's extrapolation.
  double previous_arclength = 0.0, previous_tangent_parameter = 0.0;
  bool have_previous = false;
  while (out.steps < options.max_steps) {
    const BranchSample& p = out.last;
    if (p.parameter < options.parameter_min || p.parameter > options.parameter_max) {
      out.reached_bound = true;
      out.message = "reached the parameter bound";
      return out;
    }
    BranchSample next;
    const Eigen::VectorXd xp = p.x + step * p.tangent_state;
    const double lp = p.parameter + step * p.tangent_parameter;
    const bool converged = solver.correct(xp, lp, p.tangent_state, p.tangent_parameter, next);
    const bool kept_direction =
        converged && (step <= options.angle_test_max_step ||
                      solver.dot(next.tangent_state, next.tangent_parameter, p.tangent_state,
                                 p.tangent_parameter) >= cos_max);
    if (converged && !kept_direction) ++solver.cost().tangent_angle_rejections;
    const bool ok = kept_direction && step_accepted(p, next);
    // The step control's factor of this step (bisections below correct other points).
    double step_factor = solver.step_factor();
    if (!ok) {
      ++out.failed_steps;
      out.growth_pause_left = options.growth_pause_after_failure;
      if (options.fold_approach_tolerance > 0.0 && have_previous) {
        const std::optional<double> fold =
            extrapolated_fold(previous_arclength, previous_tangent_parameter, p);
        if (fold && std::abs(*fold - p.parameter) <= options.fold_approach_tolerance) {
          out.approached_fold = true;
          out.fold_parameter = *fold;
          out.reached_bound = true;
          std::ostringstream m;
          m << std::setprecision(8) << "approached a fold at parameter " << *fold
            << " (extrapolated; the last sample lies " << std::setprecision(2)
            << std::abs(*fold - p.parameter) << " before it)";
          out.message = m.str();
          return out;
        }
      }
      step /= 2;
      if (step < options.min_step) {
        out.message = "step below min_step at parameter " + std::to_string(p.parameter);
        return out;
      }
      continue;
    }
    next.arclength = p.arclength + step;

    bool bisected = false;  // the solver's last factorisation is not next's
    if (next.negative_eigenvalues != p.negative_eigenvalues) {
      bisected = true;
      // Bisect the step in arclength, keeping the count change inside [s_lo, s_hi], until
      // lambda differs by less than the tolerance across the bracket.
      double s_lo = 0.0, s_hi = step, lambda_lo = p.parameter, slope_lo = p.tangent_parameter;
      BranchSample hi = next;
      // Located when lambda varies by less than the tolerance over the bracket: its ends
      // differ by less, and (at a fold, where both ends may lie at the same lambda below the
      // turning point) the larger slope dlambda/ds at an end times the bracket's arclength,
      // which bounds how far lambda rises inside, is less too.
      const auto located = [&] {
        const double slope = std::max(std::abs(slope_lo), std::abs(hi.tangent_parameter));
        return std::abs(hi.parameter - lambda_lo) <= options.special_point_tolerance &&
               slope * (s_hi - s_lo) <= options.special_point_tolerance;
      };
      for (int k = 0; k < 60 && !located(); ++k) {
        // The midpoint may sit exactly on the singular point (zero pivot), or so close to it
        // that the corrector does not converge: then another point inside the bracket serves
        // as well (a bracket only has to shrink). Ends the bisection only if all fail.
        BranchSample mid;
        const auto corrected_at = [&](double s) {
          return solver.correct(p.x + s * p.tangent_state, p.parameter + s * p.tangent_parameter,
                                p.tangent_state, p.tangent_parameter, mid);
        };
        double s_mid = 0.0;
        bool corrected = false;
        for (const double fraction : {0.5, 0.51, 0.25, 0.75, 0.1, 0.9}) {
          s_mid = s_lo + fraction * (s_hi - s_lo);
          if ((corrected = corrected_at(s_mid))) break;
        }
        if (!corrected) break;
        if (mid.negative_eigenvalues == p.negative_eigenvalues) {
          s_lo = s_mid;
          lambda_lo = mid.parameter;
          slope_lo = mid.tangent_parameter;
        } else {
          s_hi = s_mid;
          hi = std::move(mid);
        }
      }
      // At a branch point the augmented system is singular, and next to it the tangent is
      // ill-determined: a sample that landed closer past the point than the previous one lay
      // before it can swing onto the other branch or back, and even look like a fold (on a
      // penalised contact branch this ran as a dozen spurious folds within 3e-4 of the
      // stability loss). Step over instead: from p to as far past the point as p lies before
      // it, and at least half the largest step past it, accepted if the count is the
      // same and the tangent still agrees with p's.
      const double s_over = s_hi + std::max(s_hi, 0.5 * options.max_step);
      if (step - s_hi < std::max(s_hi, 0.25 * options.max_step) && s_over <= options.max_step) {
        BranchSample over;
        if (solver.correct(p.x + s_over * p.tangent_state,
                           p.parameter + s_over * p.tangent_parameter, p.tangent_state,
                           p.tangent_parameter, over) &&
            over.negative_eigenvalues == next.negative_eigenvalues &&
            solver.dot(over.tangent_state, over.tangent_parameter, p.tangent_state,
                       p.tangent_parameter) >= cos_max &&
            step_accepted(p, over)) {
          over.arclength = p.arclength + s_over;
          step_factor = solver.step_factor();
          next = std::move(over);
          step = s_over;
          ++out.branch_point_steps_over;
        }
      }
      SpecialPoint sp;
      // A fold turns the branch back in lambda; a branch point does not.
      sp.kind = (p.tangent_parameter * next.tangent_parameter < 0.0) ? SpecialPoint::Kind::Fold
                                                                     : SpecialPoint::Kind::BranchPoint;
      sp.parameter = 0.5 * (hi.parameter + lambda_lo);
      sp.x = hi.x;
      sp.negative_before = p.negative_eigenvalues;
      sp.negative_after = next.negative_eigenvalues;
      sp.multiplicity = std::abs(next.negative_eigenvalues - p.negative_eigenvalues);
      sp.bracket_width = std::abs(hi.parameter - lambda_lo);
      out.special_points.push_back(sp);
      if (on_special) {
        ScopedSeconds timer(solver.cost().callback_seconds);
        on_special(sp);
      }
      if (options.max_special_points > 0 &&
          static_cast<int>(out.special_points.size()) >= options.max_special_points) {
        out.last = std::move(next);
        ++out.steps;
        out.last.next_step = next_step_after(step, paused(step_factor), options);
        sample_done(out.last);
        out.reached_bound = true;
        out.message = "found max_special_points special points";
        return out;
      }
    }

    // Events: sign changes of the test functions, located like special points.
    bool stop = false;
    std::vector<double> next_values;
    for (const BranchEvent& e : events) next_values.push_back(event_value(e, next));
    for (std::size_t k = 0; k < events.size(); ++k) {
      if (!(event_values[k] * next_values[k] < 0.0)) continue;
      bisected = true;
      double s_lo = 0.0, s_hi = step, lambda_lo = p.parameter;
      BranchSample hi = next;
      // Unless the test function needs it, the bisection's points have no tangent or index.
      bool hi_analysed = true;
      for (int it = 0; it < 60 && std::abs(hi.parameter - lambda_lo) > options.special_point_tolerance;
           ++it) {
        const double s_mid = 0.5 * (s_lo + s_hi);
        BranchSample mid;
        if (!solver.correct(p.x + s_mid * p.tangent_state, p.parameter + s_mid * p.tangent_parameter,
                            p.tangent_state, p.tangent_parameter, mid, events[k].needs_tangent))
          break;
        if (event_value(events[k], mid) * event_values[k] > 0.0) {
          s_lo = s_mid;
          lambda_lo = mid.parameter;
        } else {
          s_hi = s_mid;
          hi = std::move(mid);
          hi_analysed = events[k].needs_tangent;
        }
      }
      LocatedEvent located{events[k].kind, 0.5 * (hi.parameter + lambda_lo), hi.x,
                           std::abs(hi.parameter - lambda_lo)};
      out.events.push_back(located);
      if (on_event) {
        ScopedSeconds timer(solver.cost().callback_seconds);
        on_event(located);
      }
      if (events[k].stop) {
        // The trace ends at the event's far end: a sample like any other (else at `next`).
        BranchSample end;
        if (hi_analysed || solver.correct(p.x + s_hi * p.tangent_state,
                                          p.parameter + s_hi * p.tangent_parameter,
                                          p.tangent_state, p.tangent_parameter, end)) {
          if (!hi_analysed) hi = std::move(end);
          hi.arclength = p.arclength + s_hi;
          next = std::move(hi);
        }
        stop = true;
        break;
      }
    }
    event_values = next_values;
    if (bisected) solver.anchor_chord_at(next);

    previous_arclength = out.last.arclength;
    previous_tangent_parameter = out.last.tangent_parameter;
    have_previous = true;
    out.last = std::move(next);
    ++out.steps;
    step = next_step_after(step, paused(step_factor), options);
    out.last.next_step = step;
    sample_done(out.last);
    if (stop) {
      out.reached_bound = true;
      out.message = "stopped at event '" + out.events.back().kind + "'";
      return out;
    }
  }
  out.reached_bound = true;
  out.message = "reached max_steps";
  return out;
}

}  // namespace

BranchTrace trace_branch_along(const ParametrizedObjective& family,
                               const Eigen::Ref<const Eigen::VectorXd>& x0, double lambda0,
                               const Eigen::Ref<const Eigen::VectorXd>& direction_state,
                               double direction_parameter,
                               const std::vector<Eigen::Index>& fixed_dofs,
                               const ArclengthOptions& options,
                               const std::function<void(const BranchSample&)>& on_sample,
                               const std::function<void(const SpecialPoint&)>& on_special,
                               const std::vector<BranchEvent>& events,
                               const std::function<void(const LocatedEvent&)>& on_event) {
  if (x0.size() != family.dimension())
    throw std::invalid_argument("trace_branch: x0 has the wrong size");
  const auto start = std::chrono::steady_clock::now();
  BranchSolver solver(family, fixed_dofs, options);
  BranchTrace out = trace_with_solver(solver, x0, lambda0, direction_state,
                                      direction_parameter, options, on_sample,
                                      on_special, events, on_event);
  out.cost = solver.cost();
  out.cost.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace growshell
