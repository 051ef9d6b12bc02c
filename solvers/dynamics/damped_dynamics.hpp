#pragma once
/// \file
/// Equilibria by explicit damped dynamics, the way the paper found them: the unknowns move as
/// lumped masses under the forces -dE/dx until those forces fall below the same tolerance as
/// Newton's method. Two integrators: FIRE (Bitzek et al., Phys. Rev. Lett. 97, 170201 (2006):
/// semi-implicit Euler steps with velocities mixed towards the force and reset whenever they
/// run against it, and an adaptive time step) and velocity Verlet with viscous damping below
/// critical for the softest mode. A baseline to measure the implicit path against
/// (docs/performance.md, "Damped dynamics against Newton"), not a solver for production runs.

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "core/sparse_objective.hpp"

namespace growshell {

/// The integrator of relax_by_damped_dynamics.
enum class DampedIntegrator {
  Fire,           ///< FIRE: velocity mixing, resets, adaptive step
  ViscousVerlet,  ///< velocity Verlet with the force -c M v, c = 2 damping_ratio omega_min
};

/// Settings of relax_by_damped_dynamics. Times are in the units that the masses and the
/// energy give (with masses in kg and energies in J, seconds).
struct DampedDynamicsOptions {
  DampedIntegrator integrator = DampedIntegrator::Fire;
  /// Converged when the infinity norm of the free gradient is at most this (> 0), as
  /// NewtonOptions::gradient_tolerance.
  double gradient_tolerance = 1e-8;
  int max_steps = 10000000;  ///< >= 1
  /// Stop, not converged, after this much wall time (s, > 0).
  double max_seconds = std::numeric_limits<double>::infinity();
  /// The stable step is 2 / omega_max, omega_max^2 the largest eigenvalue of M^-1 H at x0
  /// (from power iteration); the step taken is this fraction of it, in (0, 1). FIRE raises
  /// its step up to fire_max_step_factor times that.
  double step_fraction = 0.5;
  int power_iterations = 60;  ///< for omega_max, >= 1
  /// ViscousVerlet: the damping as a fraction of critical for the softest mode, in (0, 1];
  /// omega_min^2 is the lowest eigenvalue of M^-1 H at x0 (mass-normalised, fixed dofs held).
  double damping_ratio = 0.9;
  /// FIRE's constants (the paper's values).
  double fire_alpha_start = 0.1;
  double fire_alpha_decay = 0.99;
  double fire_step_increase = 1.1;
  double fire_step_decrease = 0.5;
  int fire_delay_steps = 5;
  double fire_max_step_factor = 10.0;
};

/// Result of relax_by_damped_dynamics.
struct DampedDynamicsResult {
  bool converged = false;
  std::string message;
  Eigen::VectorXd x;  ///< the last state
  double energy = 0.0;
  double gradient_inf_norm = 0.0;  ///< free dofs, at x
  int steps = 0;                   ///< time steps taken
  int gradient_evaluations = 0;
  double time_step = 0.0;  ///< the stable step's estimate used (before FIRE's adaptation)
  double seconds = 0.0;    ///< wall time
};

/// Moves x0 (the dofs in `fixed_dofs` held) under the forces -grad E of `objective` with the
/// per-dof masses `mass` (> 0 each, e.g. lumped reference areas times h), from rest, until the
/// free gradient's infinity norm is at most options.gradient_tolerance, max_steps are taken,
/// or max_seconds pass. Non-finite energies or forces end the run (not converged). Throws
/// std::invalid_argument for sizes that do not match, a non-positive mass, a fixed dof out of
/// range, or options out of range (naming the field).
DampedDynamicsResult relax_by_damped_dynamics(SparseObjective& objective,
                                              const Eigen::Ref<const Eigen::VectorXd>& x0,
                                              const Eigen::VectorXd& mass,
                                              const std::vector<Eigen::Index>& fixed_dofs,
                                              const DampedDynamicsOptions& options = {});

}  // namespace growshell
