// bench_damped_vs_implicit: the paper's method (explicit damped dynamics after every growth
// step) against growshell's (Newton with sparse Cholesky), on the same model, from the same
// state, through the same growth steps, to the same force tolerance.
//
// A disc of the default scene (R = 1, Y = 1e4 Pa, nu = 0.3) on the rings mesh, grown from a
// small two-fold perturbation onto the cone at --phi-start by Newton's method (untimed), then
// by both methods in --steps equal steps to --phi-end, each step starting from the method's own
// previous equilibrium. Prints per step the wall time of each, their
// energies and the largest difference of their states, and ends with the line
//   damped/implicit wall-time ratio: R
// Exits 1 if the two methods' equilibria differ (energy by more than 1e-6 of it, or a state by
// more than 1e-3 h). With --max-seconds T, a damped relaxation still short of the tolerance after
// T seconds ends the run: the last line then reads "damped/implicit wall-time ratio: > R" (a
// lower bound) and the exit status is 4. A program, not a test: timings do not belong in the
// test suite.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "examples/support/command_line.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "solvers/dynamics/damped_dynamics.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace {

using namespace growshell;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

int run(int argc, char** argv) {
  examples::CommandLine cl(argc, argv);
  if (cl.help()) {
    std::puts(
        "usage: bench_damped_vs_implicit [--h 0.04] [--size-slope 0.3] [--phi-start 0.5]\n"
        "                                [--phi-end 1.0]\n"
        "                                [--steps 4] [--integrator fire|verlet] [--tolerance "
        "1e-6]\n"
        "                                [--max-seconds T]\n"
        "  --tolerance: force tolerance of both methods relative to Y h^3 / R\n"
        "  --max-seconds: wall-time cap of each damped relaxation (default: none)");
    return 0;
  }
  const double h = cl.number("--h", 0.04);
  const double slope = cl.number("--size-slope", 0.3);
  const double phi_start = cl.number("--phi-start", 0.5);
  const double phi_end = cl.number("--phi-end", 1.0);
  const int steps = cl.integer("--steps", 4);
  const std::string integrator = cl.text("--integrator", "fire");
  const double tolerance = cl.number("--tolerance", 1e-6);
  const double max_seconds = cl.number("--max-seconds", std::numeric_limits<double>::infinity());
  cl.reject_unknown();
  if (!(max_seconds > 0.0)) throw std::invalid_argument("--max-seconds must be > 0");
  if (!(h > 0.0 && h < 0.25)) throw std::invalid_argument("--h must be in (0, 0.25)");
  if (!(slope > 0.0)) throw std::invalid_argument("--size-slope must be > 0");
  if (!(phi_start > 0.0 && phi_end > phi_start) || steps < 1)
    throw std::invalid_argument("need 0 < --phi-start < --phi-end and --steps >= 1");
  if (integrator != "fire" && integrator != "verlet")
    throw std::invalid_argument("--integrator must be fire or verlet");
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance must be > 0");

  RingDiscMeshOptions mesh;
  mesh.size_slope = slope;
  mesh.size_floor = h / 4;
  ShellModelSettings settings;
  settings.thickness = constant_thickness(h);
  const ShellModel model(make_ring_disc_mesh(mesh), settings);
  const Eigen::VectorXd& X = model.reference_positions();
  const std::vector<Eigen::Index> pins = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);
  // The two-fold perturbation z = 1e-3 r^2 cos 2 theta (mirror-symmetric, so neither method is
  // pushed along the pattern's nearly free turn).
  Eigen::VectorXd start = X;
  for (Eigen::Index v = 0; v < X.size() / 3; ++v)
    start(3 * v + 2) = 1e-3 * (X(3 * v) * X(3 * v) - X(3 * v + 1) * X(3 * v + 1));
  const Eigen::VectorXd mass = (model.reference().vertex_areas().array() * h + 1e-12)
                                   .matrix()
                                   .replicate(1, 3)
                                   .transpose()
                                   .reshaped();
  const double force_tolerance = tolerance * model.natural_force_scale();
  NewtonOptions newton;
  newton.gradient_tolerance = force_tolerance;
  DampedDynamicsOptions damped;
  damped.integrator =
      integrator == "fire" ? DampedIntegrator::Fire : DampedIntegrator::ViscousVerlet;
  damped.gradient_tolerance = force_tolerance;
  damped.max_steps = 50000000;
  damped.max_seconds = max_seconds;

  std::printf(
      "# rings disc, h = %g, size_slope %g: %lld unknowns; %s against Newton, force "
      "tolerance %.3g N\n",
      h, slope, static_cast<long long>(model.dimension()), integrator.c_str(), force_tolerance);
  std::printf("# %7s %11s %9s %11s %9s %10s %12s %12s\n", "phi_e", "newton_s", "newton_it",
              "damped_s", "damped_n", "dt", "dE/E", "max|dx|/h");
  // Onto the cone at phi_start: Newton with the decrement test, in steps of at most 0.1 (the
  // path from flat crosses the branch point, where the gradient alone converges slowly).
  {
    NewtonOptions warm = newton;
    warm.decrement_tolerance = 1e-9 * settings.material.youngs_modulus * h * h * h;
    warm.max_iterations = 1000;
    const int warm_steps = static_cast<int>(std::ceil(phi_start / 0.1));
    for (int k = 1; k <= warm_steps; ++k) {
      ObjectiveAtParameter energy(model, phi_start * k / warm_steps);
      NewtonResult r = NewtonSolver(warm).minimize(energy, start, pins);
      if (!r.converged()) throw std::runtime_error("warm-up to phi_start failed: " + r.message);
      start = r.x;
    }
    ObjectiveAtParameter energy(model, phi_start);
    NewtonResult r = NewtonSolver(newton).minimize(energy, start, pins);  // to the tolerance
    if (!r.converged()) throw std::runtime_error("warm-up to phi_start failed: " + r.message);
    start = r.x;
  }
  Eigen::VectorXd x_newton = start, x_damped = start;
  double newton_seconds = 0.0, damped_seconds = 0.0;
  bool same = true;
  for (int k = 1; k <= steps; ++k) {
    const double phi = phi_start + (phi_end - phi_start) * k / steps;
    ObjectiveAtParameter energy(model, phi);
    auto t0 = Clock::now();
    const NewtonResult nr = NewtonSolver(newton).minimize(energy, x_newton, pins);
    const double tn = seconds_since(t0);
    if (!nr.converged())
      throw std::runtime_error("Newton failed at phi_e = " + std::to_string(phi) + ": " +
                               nr.message);
    const DampedDynamicsResult dr = relax_by_damped_dynamics(energy, x_damped, mass, pins, damped);
    if (!dr.converged) {
      newton_seconds += tn;
      damped_seconds += dr.seconds;
      std::printf(
          "  %7.4f %11.3f %9d %11.3f %9d %10.3g   damped not converged: %s (force %.3g N)\n", phi,
          tn, nr.iterations, dr.seconds, dr.steps, dr.time_step, dr.message.c_str(),
          dr.gradient_inf_norm);
      std::printf("damped/implicit wall-time ratio: > %.1f\n", damped_seconds / newton_seconds);
      return 4;
    }
    x_newton = nr.x;
    x_damped = dr.x;
    newton_seconds += tn;
    damped_seconds += dr.seconds;
    const double de = (dr.energy - nr.energy) / std::abs(nr.energy);
    const double dx = (dr.x - nr.x).lpNorm<Eigen::Infinity>() / h;
    same = same && std::abs(de) <= 1e-6 && dx <= 1e-3;
    std::printf("  %7.4f %11.3f %9d %11.3f %9d %10.3g %+12.3e %12.3e\n", phi, tn, nr.iterations,
                dr.seconds, dr.steps, dr.time_step, de, dx);
    std::fflush(stdout);
  }
  std::printf("# total: Newton %.3f s, damped %.3f s; equilibria %s\n", newton_seconds,
              damped_seconds, same ? "the same" : "DIFFER");
  std::printf("damped/implicit wall-time ratio: %.1f\n", damped_seconds / newton_seconds);
  return same ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "bench_damped_vs_implicit: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_damped_vs_implicit: %s\n", e.what());
    return 3;
  }
}
