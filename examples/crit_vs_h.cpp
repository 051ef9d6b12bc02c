// crit_vs_h: the critical excess angle phi_e^crit for a list of thicknesses. For each h the disc
// is grown from flat without contact to --phi-start, the symmetric branch is followed through
// contact to --phi-top, the state there is pushed along its lowest mode and relaxed onto the
// skewed cone, whose branch is followed down and up to --phi-top, and phi_e^crit is reported
// both ways: where the energies of the two branches cross, and where the symmetric branch
// loses stability (solvers/contact/econe_branches.hpp). One line per thickness on stdout and
// in DIR/crit_vs_h.csv; each thickness's branches and events as trace_contact writes them are
// not kept (run trace_contact --h H for those). With --phi-contact-start the cone is instead
// traced from flat by continuation without contact (solvers/contact/contact_free_cone.hpp),
// which passes the symmetric cone's subcritical branch point, and its samples join the
// symmetric branch for the crossing: with an exclusion radius that leaves the apex core out of
// the contact (--exclusion-factor 8) this gives the proxy-converged phi_e^crit (docs/contact.md,
// "Exclusion radius").
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/contact_free_cone_options.hpp"
#include "examples/support/disc_perturbation.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/mirror_subspace_option.hpp"
#include "examples/support/scene_command_line.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_free_cone.hpp"
#include "solvers/contact/econe_branches.hpp"
#include "solvers/continuation/growth_path.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace {

using namespace growshell;
using Clock = std::chrono::steady_clock;

const char* kUsage = R"(usage: crit_vs_h [SCENE.json] [options]
  SCENE.json          scene (default: the paper's disc); its thickness is replaced by each h
                      (physics.contact_exclusion_radius "auto" follows it as 8 h; a number
                      in the scene is used as it is for every h)
  --h LIST            thicknesses, comma separated (default 0.04,0.03,0.02,0.015)
  --mesh FAMILY       mesh family: rings (default), gmsh or lattice (mesh.family)
  --size-slope C      element size per distance from the centre, rings and gmsh families
                      (mesh.size_slope, default 0.1)
  --rings N           resolution of the lattice family (rings of a disc, radial layers of a ring)
  --phi-start P       contact-free growth from flat up to P (default 5.0)
  --phi-contact-start P  instead: the cone traced from flat by continuation up to P (below
                      first contact; e.g. 6.25 with --exclusion-factor 8), its samples part of
                      the symmetric branch
  --exclusion-factor F  exclusion radius F h for every h (default: the scene's,
                      physics.contact_exclusion_radius; auto = 8 h)
  --phi-top P         the symmetric branch is followed up to P and relaxed there (default 7.0)
  --stiffness-factor F  penalty stiffness k = F Y l^2 / h (default 10)
  --max-step S        largest arclength step (default 0.05)
  --tolerance T       force tolerance relative to Y h^3 / R (default 1e-5)
  --symmetric-subspace 0  trace the symmetric branch in the full space (default 1: among the
                      states with both mirrors x -> -x, y -> -y, as trace_contact)
  --out DIR           output directory (default out/crit_vs_h)
)";

std::string number_or_nan(double v) {
  if (!std::isfinite(v)) return "nan";
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  auto [base, cl] = examples::read_scene_command_line(argc, argv);
  if (cl.help()) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const std::vector<double> thicknesses = cl.number_list("--h", "0.04,0.03,0.02,0.015");
  for (const double h : thicknesses)
    if (!(h > 0.0)) throw std::invalid_argument("--h: a thickness must be > 0");
  examples::apply_mesh_options(base, cl);
  const double phi_start = cl.number("--phi-start", 5.0);
  const double phi_contact_start = cl.number("--phi-contact-start", 0.0);
  const double exclusion_factor = cl.number("--exclusion-factor", 0.0);
  const double phi_top = cl.number("--phi-top", 7.0);
  const double stiffness_factor = cl.number("--stiffness-factor", 10.0);
  const double max_step = cl.number("--max-step", 0.05);
  const double tolerance = cl.number("--tolerance", 1e-5);
  const bool symmetric_subspace = cl.integer("--symmetric-subspace", 1) != 0;
  const std::string out_dir = cl.text("--out", "out/crit_vs_h");
  cl.reject_unknown();
  if (!(phi_start > 0.0 && phi_start < phi_top))
    throw std::invalid_argument("need 0 < --phi-start < --phi-top");
  if (!(phi_contact_start >= 0.0 && phi_contact_start < phi_top))
    throw std::invalid_argument("--phi-contact-start must be in (0, --phi-top)");
  if (!(exclusion_factor == 0.0 || exclusion_factor >= 1.0))
    throw std::invalid_argument("--exclusion-factor must be >= 1 (the contact distance h)");
  if (!(stiffness_factor > 0.0)) throw std::invalid_argument("--stiffness-factor must be > 0");
  if (!(max_step > 0.0)) throw std::invalid_argument("--max-step must be > 0");
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance must be > 0");
  if (base.geometry.shape != SceneShape::Disc)
    throw std::invalid_argument("crit_vs_h traces discs (geometry.shape = disc)");
  validate_scene(base);

  std::filesystem::create_directories(out_dir);
  std::ofstream csv(out_dir + "/crit_vs_h.csv");
  csv << "h,phi_contact,phi_crit_stability,phi_crit_energy,crossing_error_estimate,"
         "crossings,skewed_found,symmetric_steps,skewed_steps,seconds\n";
  csv.flush();
  std::printf("%8s %12s %14s %14s %10s %6s %8s\n", "h", "phi_contact", "crit_stability",
              "crit_energy", "error", "skewed", "seconds");
  for (const double h : thicknesses) {
    const auto t0 = Clock::now();
    Scene scene = base;
    apply_override(scene, "thickness", number_or_nan(h));
    if (exclusion_factor > 0.0)
      apply_override(scene, "physics.contact_exclusion_radius",
                     number_or_nan(exclusion_factor * h));
    validate_scene(scene);
    ShellModel model(scene_mesh(scene), scene_model_settings(scene));
    const double R = scene.geometry.radius;
    const double Y = scene.material.youngs_modulus;
    const ContactProxy proxy = make_contact_proxy(model, 1);
    const Eigen::VectorXd& X = model.reference_positions();
    const auto pinned = mirror_axis_pinned_dofs(
        Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
        model.sheet_vertices(), model.settings().growth.center);
    NewtonOptions newton;
    newton.gradient_tolerance = tolerance * model.natural_force_scale();
    newton.decrement_tolerance =
        1e-9 * Y * h * h * h;  // tight: the traces starting here test the force

    // The start of the traces with contact: natural growth from flat to --phi-start, or the
    // cone by continuation to --phi-contact-start (its samples join the symmetric branch).
    Eigen::VectorXd start;
    double start_phi = 0.0;
    std::vector<BranchSample> cone_samples;
    std::optional<SpecialPoint> cone_stability_loss;
    if (phi_contact_start > 0.0) {
      const ContactFreeConeOptions cone_options =
          examples::contact_free_cone_options(scene, model, tolerance, phi_contact_start);
      ContactFreeCone cone = trace_contact_free_cone(model, proxy, pinned, cone_options);
      if (!cone.found) {
        std::printf("%8.4f  %s\n", h, cone.message.c_str());
        csv << h << ",nan,nan,nan,nan,0,0,0,0,"
            << std::chrono::duration<double>(Clock::now() - t0).count() << '\n';
        csv.flush();
        continue;
      }
      for (const SpecialPoint& p : cone.special_points)
        if (!cone_stability_loss && p.negative_before == 0 && p.negative_after > 0)
          cone_stability_loss = p;
      start = cone.start.x;
      start_phi = cone.start.parameter;
      cone_samples = std::move(cone.samples);
      cone_samples.pop_back();  // the start: the first sample of the trace with contact
    } else {
      std::mt19937 rng(scene.continuation.seed);
      const double amplitude = scene.continuation.perturbation_amplitude;
      GrowthPathOptions path_options;
      path_options.max_step = 0.25;
      const GrowthPathResult path = grow_along_path(
          model, X + examples::disc_perturbation(model, amplitude, rng, R), 0.0, phi_start, pinned,
          NewtonSolver(newton),
          [&](int) { return examples::disc_perturbation(model, amplitude, rng, R); }, path_options);
      if (!path.reached_target) {
        std::printf("%8.4f  growth from flat ended at phi_e = %.4f: %s\n", h,
                    path.last.excess_angle, path.message.c_str());
        csv << h << ",nan,nan,nan,nan,0,0,0,0,"
            << std::chrono::duration<double>(Clock::now() - t0).count() << '\n';
        csv.flush();
        continue;
      }
      start = path.last.x;
      start_phi = path.last.excess_angle;
    }

    EconeBranchOptions options;
    ContactBranchOptions& c = options.contact;
    c.contact_distance = scene.physics.contact_distance.value_or(h);
    c.exclusion_radius = resolved_exclusion_radius(scene);
    c.candidate_margin = h;
    c.stiffness = stiffness_factor * contact_stiffness_scale(Y, h, proxy_mean_edge_length(proxy));
    c.violation_tolerance = 0.25 * h;
    c.repin_above_condition = 20.0;  // as trace_contact: pins chosen again where they degrade
    // The cone grown in natural steps (--phi-start) has its fold pattern turned against the
    // mesh, so it is traced in the full space; the cone entered by continuation
    // (--phi-contact-start) keeps the mirrors.
    c.symmetric_subspace = examples::subspace_for_start(
        examples::mirror_subspace_option(model, scene.geometry.radius, symmetric_subspace), start,
        0.1 * h);
    c.arclength.initial_step = max_step / 4;
    c.arclength.max_step = max_step;
    c.arclength.min_step = 1e-6;
    c.arclength.gradient_tolerance = tolerance * model.natural_force_scale();
    c.arclength.max_tangent_angle = 0.5;
    c.arclength.angle_test_max_step = 0.02 * max_step;
    options.symmetric_end = phi_top;
    options.skewed_end = phi_top;
    options.skewed_start = SkewedStart::Top;
    options.relaxation = newton;
    options.relaxation.max_iterations = 400;
    // As trace_contact: the decrement test stops the relaxation's crawl along the nearly free
    // orientation mode of the fold pattern (with 1e-9 Y h^3 no relaxation at h = 0.01 ended).
    options.relaxation.decrement_tolerance = 1e-6 * Y * h * h * h;
    options.symmetric_before = contact_free_energies(model, cone_samples);
    const EconeBranchResult r =
        trace_econe_branches(model, proxy, start, start_phi, pinned, options);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double contact = r.first_contact ? r.first_contact->parameter : nan;
    // The stability loss lies on the contact-free cone if it was traced past it.
    const double stability = cone_stability_loss ? cone_stability_loss->parameter
                             : r.stability_loss  ? r.stability_loss->parameter
                                                 : nan;
    for (std::size_t k = 0; k < r.crossings.size(); ++k)
      std::printf("#   crossing at phi_e = %.7f: slope difference %.3e J/rad, skewed %s\n",
                  r.crossings[k].parameter, r.crossings[k].slope_difference,
                  r.crossing_skewed_stable[k] ? "stable" : "unstable");
    // phi_e^crit by energy: the first crossing with the stable part of the skewed branch.
    const EnergyCrossing* chosen = nullptr;
    for (std::size_t k = 0; k < r.crossings.size() && chosen == nullptr; ++k)
      if (r.crossing_skewed_stable[k]) chosen = &r.crossings[k];
    const double crossing = chosen ? chosen->parameter : nan;
    const double error = chosen ? chosen->error_estimate : nan;
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("%8.4f %12.6f %14.7f %14.7f %10.2e %6s %8.1f\n", h, contact, stability, crossing,
                error, r.skewed_found ? "yes" : "no", seconds);
    csv << h << ',' << number_or_nan(contact) << ',' << number_or_nan(stability) << ','
        << number_or_nan(crossing) << ',' << number_or_nan(error) << ',' << r.crossings.size()
        << ',' << (r.skewed_found ? 1 : 0) << ',' << r.symmetric.steps << ','
        << r.skewed_down.steps + r.skewed_up.steps << ',' << seconds << '\n';
    csv.flush();
  }
  std::printf("# wrote %s/crit_vs_h.csv\n", out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("crit_vs_h", run, argc, argv);
}
