// The library from C++: a disc of thickness h = 0.04 grown to phi_e = 1 in steps, each
// equilibrium found by Newton's method from the last. README.md shows this file in full.
#include <cstdio>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

int main() {
  using namespace growshell;
  const double h = 0.04;
  RingDiscMeshOptions mesh;  // R = 1; element size clamp(0.1 r, h/4, inf): the default mesh
  mesh.size_slope = 0.1;
  mesh.size_floor = h / 4;
  ShellModelSettings settings;  // Y = 1e4 Pa, nu = 0.3
  settings.thickness = constant_thickness(h);
  ShellModel model(make_ring_disc_mesh(mesh), settings);

  // Unknowns: every control point, vertex-major (x0, y0, z0, x1, ...). A small saddle
  // z = 1e-3 (x^2 - y^2) starts the two-fold mode.
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    x(3 * v + 2) = 1e-3 * (x(3 * v) * x(3 * v) - x(3 * v + 1) * x(3 * v + 1));
  // Six pinned dofs (on the mesh's mirror axes) remove the rigid motions without biasing the
  // equilibrium.
  const Eigen::MatrixX3d points =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
  const std::vector<Eigen::Index> pins =
      mirror_axis_pinned_dofs(points, model.sheet_vertices(), Eigen::Vector3d::Zero());

  NewtonOptions options;
  options.gradient_tolerance = 1e-7 * model.natural_force_scale();  // Y h^3 / R, N
  // The pattern's turn about the axis is nearly free on a mesh, which can hold the gradient
  // at its rounding floor: also accept a Newton decrement below 1e-6 Y h^3 R^2 (J).
  options.decrement_tolerance = 1e-6 * settings.material.youngs_modulus * h * h * h;
  NewtonSolver newton(options);
  for (int step = 1; step <= 10; ++step) {
    const double phi_e = 0.1 * step;  // excess angle (rad)
    ObjectiveAtParameter energy(model, phi_e);  // the sheet's energy at this phi_e
    const NewtonResult r = newton.minimize(energy, x, pins);
    if (!r.converged()) {
      std::printf("Newton failed at phi_e = %.1f: %s\n", phi_e, r.message.c_str());
      return 1;
    }
    x = r.x;
    const ShellEnergyBreakdown e = model.energy_breakdown(x, phi_e);
    std::printf("phi_e = %.1f  E_s = %.6e J  E_b = %.6e J  Eb_hat = %.6f 1/m^2  (%d iterations)\n",
                phi_e, e.stretching, e.bending, e.normalized_bending(), r.iterations);
  }
  return 0;
}
