#pragma once
/// \file
/// Following stable equilibria of a growing shell in natural-parameter steps of the excess
/// angle phi_e: tangent predictor, Newton corrector, step control, and escape from saddles.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// Step control of grow_along_path. Angles in radians.
struct GrowthPathOptions {
  double max_step = 0.1;     ///< largest step in phi_e
  double min_step = 1e-4;    ///< a step that fails below this ends the path
  double step_growth = 1.5;  ///< step factor after a success (a failure halves it)
  /// Use the first-order predictor x + dphi dx/dphi, dx/dphi = -H^-1 d(gradient)/d(phi_e).
  bool tangent_predictor = true;
  /// How often a converged saddle (Hessian not positive definite) is perturbed and
  /// re-minimised before the step counts as failed.
  int max_saddle_escapes = 5;
};

/// One converged, stable point of the path.
struct GrowthPathPoint {
  double excess_angle = 0.0;
  Eigen::VectorXd x;
  int newton_iterations = 0;  ///< summed over re-minimisations
  int saddle_escapes = 0;     ///< perturbations needed to leave a saddle
};

/// A step of grow_along_path that found no stable equilibrium, as it is given up: from the last
/// point's excess angle to `to`, why, and the step tried next (0 if none: the path ends).
struct GrowthPathFailedStep {
  double from = 0.0, to = 0.0;
  std::string why;
  double next_step = 0.0;
};

/// Outcome of grow_along_path. `last` always holds the last converged point (the start if no
/// step converged), so no computed result is lost when the path ends early.
struct GrowthPathResult {
  bool reached_target = false;
  std::string message;  ///< why the path ended early (empty when it reached the target)
  GrowthPathPoint last;
  int steps = 0;
  int failed_steps = 0;
};

/// Grows from the equilibrium (or any state) `x_start` at `phi_start` to `phi_target`
/// (either direction). At every step's excess angle a predictor is corrected by `newton`
/// (minimising the model at that angle) with `fixed_dofs` held, and a converged state that is not a strict
/// minimum (see hessian_is_positive_definite) is displaced by `perturb(attempt)` (a vector of
/// the model's dimension) and re-minimised. Every accepted point is passed to `on_point`, every
/// failed step to `on_failed_step` (so that a caller can report a path that is struggling
/// rather than fall silent). A failing step is halved; the path ends, keeping its last point,
/// below options.min_step.
GrowthPathResult grow_along_path(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x_start,
                                 double phi_start, double phi_target,
                                 const std::vector<Eigen::Index>& fixed_dofs,
                                 const NewtonSolver& newton,
                                 const std::function<Eigen::VectorXd(int attempt)>& perturb,
                                 const GrowthPathOptions& options = {},
                                 const std::function<void(const GrowthPathPoint&)>& on_point = {},
                                 const std::function<void(const NewtonIterate&)>& on_iterate = {},
                                 const std::function<void(const GrowthPathFailedStep&)>&
                                     on_failed_step = {});

/// Equilibrium tangent dx/d(phi_e) = -H^-1 d(gradient)/d(phi_e) at (x, phi_e) with `fixed_dofs`
/// held (metres per radian). Returns an empty vector where H is not positive definite.
Eigen::VectorXd equilibrium_tangent(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                    double excess_angle, const std::vector<Eigen::Index>& fixed_dofs);

}  // namespace growshell
