// econe_at: grow a flat disc to a given excess angle and write the e-cone found there.
//
// A flat disc with a small, seeded, smooth out-of-plane perturbation is grown in small
// steps of the excess angle phi_e; at each step Newton's method (sparse Cholesky, line
// search) finds the equilibrium from a tangent predictor (grow_along_path). A converged state
// whose Hessian is not positive definite is a saddle (the flat disc past its buckling
// threshold): it is perturbed again and re-minimised, so each reported state is stable.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "examples/support/command_line.hpp"
#include "examples/support/scene_command_line.hpp"
#include "examples/support/disc_perturbation.hpp"
#include "examples/support/guarded_main.hpp"
#include "libshell/analysis/rim_folds.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "libshell/io/vtk_writer.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/continuation/growth_path.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: econe_at [SCENE.json] [options]
  SCENE.json         scene (default: the paper's disc, R = 1, h = 0.02, Y = 1e4, nu = 0.3,
                     the rings mesh with size_slope 0.1); a disc
  --h H              thickness (default 0.02, units of R)
  --phi PHI          target excess angle phi_e in radians (default: continuation.phi_max, 3.73)
  --step DPHI        largest step in phi_e (default 0.1)
  --mesh FAMILY      mesh family: rings (default), gmsh or lattice (mesh.family)
  --size-slope C     element size per distance from the centre, rings and gmsh families
                     (mesh.size_slope, default 0.1)
  --rings N          rings of the lattice family (mesh.rings, default 24)
  --grading P        radial grading exponent of the lattice family, 1 = uniform (default 3)
  --min-spacing S    smallest spacing, at the centre (mesh.min_spacing, default h/2)
  --quadrature D     quadrature degree 1..6 (default 2)
  --nu NU            Poisson ratio (default 0.3)
  --youngs Y         Young's modulus in Pa (default 1e4)
  --seed S           seed of the initial perturbation (default 1)
  --amplitude A      perturbation amplitude in units of R (default 1e-3)
  --tolerance T      force tolerance relative to Y h^3 / R (default 1e-7)
  --energy-tolerance E  Newton-decrement tolerance relative to Y h^3 R^2 (default 1e-6)
  --out DIR          output directory (default out/econe)
  --verbose 1        print every Newton iteration
)";

using examples::disc_perturbation;

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress lines appear as they are made
  auto [scene, cl] = examples::read_scene_command_line(argc, argv);
  if (cl.help()) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const auto set = [&](const char* option, const char* key) {
    examples::apply_option(scene, cl, option, key);
  };
  set("--h", "thickness");
  examples::apply_mesh_options(scene, cl);
  const std::string grading = cl.text("--grading", "");
  if (!grading.empty()) {
    examples::require_family_reads(scene, "--grading", grading);
    apply_override(scene, "mesh.grading_exponent", grading);
  }
  set("--min-spacing", "mesh.min_spacing");
  set("--quadrature", "mesh.quadrature_degree");
  set("--nu", "material.poisson_ratio");
  set("--youngs", "material.youngs_modulus");
  const double phi_target = cl.number("--phi", scene.continuation.phi_max);
  const double max_step = cl.number("--step", 0.1);
  const int seed = cl.integer("--seed", 1);
  const double amplitude = cl.number("--amplitude", 1e-3);
  const double rtol = cl.number("--tolerance", 1e-7);
  const double etol = cl.number("--energy-tolerance", 1e-6);
  const std::string out_dir = cl.text("--out", "out/econe");
  const bool verbose = cl.integer("--verbose", 0) != 0;
  cl.reject_unknown();
  validate_scene(scene);
  if (scene.geometry.shape != SceneShape::Disc)
    throw std::invalid_argument("econe_at grows discs (geometry.shape = disc)");
  if (!(std::isfinite(phi_target) && phi_target >= 0.0))
    throw std::invalid_argument("--phi must be finite and >= 0");
  if (!(max_step > 0.0)) throw std::invalid_argument("--step must be > 0");

  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  const ShellModelSettings settings = scene_model_settings(scene);
  ShellModel model(scene_mesh(scene), settings);
  std::filesystem::create_directories(out_dir);
  std::printf("# disc R = 1, h = %g, %s mesh, %lld elements, %lld unknowns, Y = %g, nu = %g\n", h,
              mesh_family_name(scene.mesh.family).c_str(),
              static_cast<long long>(model.num_elements()),
              static_cast<long long>(model.dimension()), settings.material.youngs_modulus,
              settings.material.poisson_ratio);

  const Eigen::MatrixX3d positions = Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(
      model.reference_positions().data(), model.dimension() / 3, 3);
  // Rigid motions: pins on the mesh's mirror axes, so that symmetric states stay symmetric.
  const std::vector<Eigen::Index> pinned = mirror_axis_pinned_dofs(
      positions, model.sheet_vertices(), model.settings().growth.center);
  NewtonOptions newton_options;
  newton_options.gradient_tolerance = rtol * model.natural_force_scale();
  newton_options.decrement_tolerance = etol * settings.material.youngs_modulus * h * h * h;
  NewtonSolver newton(newton_options);

  std::mt19937 rng(static_cast<std::uint32_t>(seed));
  const Eigen::VectorXd x_start =
      model.reference_positions() + disc_perturbation(model, amplitude, rng, 1.0);
  std::ofstream steps(out_dir + "/steps.csv");
  if (!steps) throw std::runtime_error("cannot write " + out_dir + "/steps.csv");
  steps << "phi_e,E_stretch,E_bend,Eb_hat,area,newton_iterations,folds,perturbations\n";
  steps.precision(12);
  std::printf("%8s %13s %13s %11s %6s %5s\n", "phi_e", "E_stretch", "E_bend", "Eb_hat", "iters",
              "folds");
  auto last_line = std::chrono::steady_clock::now();  // of the last line printed
  const auto on_point = [&](const GrowthPathPoint& p) {
    last_line = std::chrono::steady_clock::now();
    const ShellEnergyBreakdown parts = model.energy_breakdown(p.x, p.excess_angle);
    const int folds = analyze_rim_folds(model, p.x).folds;
    std::printf("%8.4f %13.6e %13.6e %11.6f %6d %5d%s\n", p.excess_angle, parts.stretching,
                parts.bending, parts.normalized_bending(), p.newton_iterations, folds,
                p.saddle_escapes ? "  (left a saddle by perturbation)" : "");
    steps << p.excess_angle << ',' << parts.stretching << ',' << parts.bending << ','
          << parts.normalized_bending() << ',' << parts.current_area << ','
          << p.newton_iterations << ',' << folds << ',' << p.saddle_escapes << '\n';
    steps.flush();
  };
  // Every Newton iterate with --verbose; without it, one at least every 10 s while a step is
  // busy, so that the program is never silent for longer.
  const auto log_iteration = [verbose, &last_line](const NewtonIterate& it) {
    const auto now = std::chrono::steady_clock::now();
    if (!verbose && now - last_line < std::chrono::seconds(10)) return;
    last_line = now;
    std::printf("    newton %3d  E %.12e  |g| %.3e  alpha %.3g  |dx| %.3e  shift %.3e\n",
                it.iteration, it.energy, it.gradient_inf_norm, it.step_length, it.step_inf_norm,
                it.shift);
  };
  GrowthPathOptions path_options;
  path_options.max_step = max_step;
  // A step that finds no stable state is said at once, so that a struggling path never falls
  // silent while its steps shrink.
  const auto on_failed_step = [](const GrowthPathFailedStep& f) {
    std::printf("# step %.6f -> %.6f failed: %s; %s\n", f.from, f.to, f.why.c_str(),
                f.next_step > 0.0 ? ("trying a step of " + std::to_string(f.next_step)).c_str()
                                  : "giving up (step below its minimum)");
    std::fflush(stdout);
  };
  const GrowthPathResult path = grow_along_path(
      model, x_start, 0.0, phi_target, pinned, newton,
      [&](int) { return disc_perturbation(model, amplitude, rng, 1.0); }, path_options, on_point,
      log_iteration, on_failed_step);
  const Eigen::VectorXd& x = path.last.x;
  if (!path.reached_target) {
    write_vtu(out_dir + "/last_converged.vtu", shell_snapshot(model, x, path.last.excess_angle, 2));
    std::fprintf(stderr, "econe_at: error: %s; the last converged state (phi_e = %.6g) is in %s\n",
                 path.message.c_str(), path.last.excess_angle,
                 (out_dir + "/last_converged.vtu").c_str());
    return 3;
  }
  const double phi = path.last.excess_angle;

  const ShellEnergyBreakdown parts = model.energy_breakdown(x, phi);
  const RimFoldAnalysis rim = analyze_rim_folds(model, x);
  write_vtu(out_dir + "/econe.vtu", shell_snapshot(model, x, phi, 2));
  std::printf("\nphi_e            %.6f\n", phi);
  std::printf("E_stretch        %.9e J\n", parts.stretching);
  std::printf("E_bend           %.9e J\n", parts.bending);
  std::printf("Eb_hat           %.9f (integral of U_b / area, 1/R^2)\n", parts.normalized_bending());
  std::printf("folds            %d (rim mode amplitudes m=2: %.4g, m=3: %.4g)\n", rim.folds,
              rim.mode_amplitudes(2), rim.mode_amplitudes(3));
  std::printf("wrote            %s/econe.vtu, %s/steps.csv\n", out_dir.c_str(), out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("econe_at", run, argc, argv);
}
