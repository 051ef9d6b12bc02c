// trace_contact: the e-cone branches of a growing disc through self-contact, and the critical
// excess angle where the skewed cone takes over from the symmetric one.
//
// 1. The flat disc is followed by continuation to its n = 2 branch point and the cone born there
//    (solvers/contact/contact_free_cone.hpp) up to --phi-contact-start (below first
//    contact), or a saved state is loaded (--start).
// 2. The symmetric branch is followed by pseudo-arclength continuation with the contact penalty
//    (solvers/contact/contact_branch.hpp) up to --phi-max, also where it is unstable; first
//    contact and the loss of stability are located on it.
// 3. The symmetric state at --skew-at is pushed along its lowest modes and relaxed; a
//    lower-energy state found so is the skewed cone, followed down in phi_e to where its branch
//    ends and up to --phi-wind (beyond 4 pi). (--skew-from branch-point instead enters the
//    branch born at the symmetric branch's stability loss.)
// 4. The energy crossing of the two branches (solvers/continuation/branch_crossing.hpp) is
//    phi_e^crit.
// 5. Beyond the skewed branch's upper end the sheet is grown on up to --phi-wind by minimising at
//    every step (solvers/contact/contact_growth_path.hpp): the wound-up shapes.
// Writes DIR/branch_symmetric.csv, DIR/branch_skewed.csv, DIR/branch_grown.csv, DIR/events.json,
// DIR/cost.json, DIR/scene.json, VTK snapshots of the shell and of the contact proxy (contact flags
// and forces) with DIR/branch_<name>.pvd, and every sample under DIR/states_<name>/.
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/contact_free_cone_options.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/json_number.hpp"
#include "examples/support/mirror_subspace_option.hpp"
#include "examples/support/saved_point.hpp"
#include "examples/support/scene_command_line.hpp"
#include "libshell/analysis/contact_zones.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/io/contact_snapshot.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "libshell/io/vtk_writer.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/hard_contact_solve_options.hpp"
#include "solvers/contact/contact_free_cone.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/econe_branches.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace {

using namespace growshell;
using Clock = std::chrono::steady_clock;

const char* kUsage = R"(usage: trace_contact [SCENE.json] [options]
  SCENE.json              scene (default: the paper's disc, R = 1, h = 0.02, Y = 1e4, nu = 0.3)
  --h H                   thickness (overrides the scene)
  --mesh FAMILY           mesh family: rings (default), gmsh or lattice (mesh.family)
  --size-slope C          element size per distance from the centre, rings and gmsh families
                          (mesh.size_slope, default 0.1)
  --rings N               resolution of the lattice family (rings of a disc, radial layers of a ring)
  --phi-max P             end of the symmetric branch (default 10)
  --skew-at P             the skewed search starts from the symmetric state at P (default 6.6,
                          past the stability loss of every thickness traced so far; from the
                          state at 10 the skewed cone is a winding away, see docs/contact.md)
  --phi-wind P            follow the skewed branch forward up to P, and beyond its end grow
                          on by minimisation (DIR/branch_grown.csv; default 13; 0 = skip)
  --phi-contact-start P   contact-free cone traced from flat up to P; its samples head
                          branch_symmetric.csv and count for the crossing (default 5.2: at h = 0.02
                          the trace from there passes the stability loss on the symmetric
                          branch; from 5.5 it turns onto the bifurcating one, see
                          docs/validation.md; an event symmetry_lost reports such a switch)
  --start STATE           start from a saved contact-free state instead (trace_disc's
                          DIR/states/point_NNNNN.state of the same scene)
  --stiffness-factor F    penalty stiffness k = F Y l^2 / h (l: proxy spacing; default 10)
  --segments N            contact proxy: segments per element edge (default 1)
  --exclusion-radius R    pairs closer than R (m) in the reference are neighbours, not
                          contact (physics.contact_exclusion_radius; default auto = 8 h;
                          it decides whether the fold at the apex counts as contact, see
                          docs/contact.md)
  --margin M              pairs within h + M enter a segment's penalty (default h)
  --max-step S            largest arclength step (default 0.05)
  --tolerance T           corrector force tolerance relative to Y h^3 / R (default 1e-6)
  --grow-from STATE       only stage 5: grow on from a saved stable state of an earlier run
                          (e.g. DIR/states_skewed/point_NNNNN.state) up to --phi-wind
  --wind-pairs WHICH      pairs penalised while growing beyond the skewed branch (stage 5):
                          triangles (default: every near triangle of each proxy vertex, which
                          keeps a vertex between two layers off both while the layers slide
                          past each other as the sheet winds) or nearest (per proxy vertex its
                          nearest triangle, as on the branches; stalls at phi_e = 7.95 for
                          h = 0.04, see docs/contact.md)
  --wind-step-bound B     largest motion of any dof in one Newton step of stage 5, in units
                          of h (default 0.25; 0 = unbounded), so no layer passes through another
                          within one step
  --ipopt-check 0         skip the Ipopt check of the relaxed skewed state (hard constraints)
  --skewed 0              trace the symmetric branch only
  --skew-from WHERE       top (default): relax the symmetric state at --skew-at pushed along
                          its lowest modes and follow what it finds down and up;
                          branch-point: enter the branch born at the symmetric branch's
                          stability loss along its critical mode
  --symmetric-subspace 0  trace the symmetric branch in the full space instead of among the
                          states symmetric under both mirrors x -> -x, y -> -y (default 1: the
                          trace cannot turn onto the symmetry-breaking branches at the
                          symmetric branch's branch points; its stability index is still the
                          full Hessian's; a mesh without the mirrors, e.g. a ring, or a start
                          off them is traced in the full space, with a note)
  --index-excludes-pattern-turn 0
                          count the stability index (column neg, the special points) with the
                          fold pattern's turn about the axis, a mode the disc leaves neutral and
                          a mesh only nearly so (default 1: without it, as the cone_branch study
                          counts it, docs/guide/cone_branch.md, "Stability index")
  --out DIR               output directory (default out/contact)
)";

struct BranchOutput {
  std::string name;
  std::ofstream csv;
  std::vector<CollectionEntry> snapshots;
  int index = 0;
};

using examples::json_number;

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  auto [scene, cl] = examples::read_scene_command_line(argc, argv);
  if (cl.help()) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const std::string h_text = cl.text("--h", "");
  if (!h_text.empty()) apply_override(scene, "thickness", h_text);
  examples::apply_mesh_options(scene, cl);
  const std::string exclusion_text = cl.text("--exclusion-radius", "");
  if (!exclusion_text.empty())
    apply_override(scene, "physics.contact_exclusion_radius", exclusion_text);
  const double phi_max = cl.number("--phi-max", 10.0);
  const double skew_at = cl.number("--skew-at", 6.6);
  const double phi_wind = cl.number("--phi-wind", 13.0);
  const double phi_contact_start = cl.number("--phi-contact-start", 5.2);
  const std::string start_file = cl.text("--start", "");
  const double stiffness_factor = cl.number("--stiffness-factor", 10.0);
  const int segments = cl.integer("--segments", 1);
  const double margin_option = cl.number("--margin", -1.0);
  const double max_step = cl.number("--max-step", 0.05);
  const double tolerance = cl.number("--tolerance", 1e-6);
  const bool skewed = cl.integer("--skewed", 1) != 0;
  const std::string skew_from = cl.text("--skew-from", "top");
  const std::string grow_from = cl.text("--grow-from", "");
  const bool ipopt_check = cl.integer("--ipopt-check", 1) != 0;
  const std::string wind_pairs = cl.text("--wind-pairs", "triangles");
  const double wind_step_bound = cl.number("--wind-step-bound", 0.25);
  const bool symmetric_subspace = cl.integer("--symmetric-subspace", 1) != 0;
  const bool index_excludes_turn = cl.integer("--index-excludes-pattern-turn", 1) != 0;
  const std::string out_dir = cl.text("--out", "out/contact");
  cl.reject_unknown();
  validate_scene(scene);
  if (skew_from != "branch-point" && skew_from != "top")
    throw std::invalid_argument("--skew-from must be branch-point or top, not '" + skew_from + "'");
  if (wind_pairs != "nearest" && wind_pairs != "triangles")
    throw std::invalid_argument("--wind-pairs must be nearest or triangles, not '" + wind_pairs +
                                "'");
  if (!(wind_step_bound >= 0.0)) throw std::invalid_argument("--wind-step-bound must be >= 0");
  if (!(stiffness_factor > 0.0)) throw std::invalid_argument("--stiffness-factor must be > 0");
  if (!(max_step > 0.0)) throw std::invalid_argument("--max-step must be > 0");
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance must be > 0");
  if (!(skew_at > 0.0)) throw std::invalid_argument("--skew-at must be > 0");
  if (!(phi_contact_start > 0.0 && phi_contact_start < phi_max))
    throw std::invalid_argument("--phi-contact-start must be in (0, phi-max)");
  if (scene.geometry.shape != SceneShape::Disc && start_file.empty())
    throw std::invalid_argument("rings need --start (a saved state of trace_disc)");

  std::filesystem::create_directories(out_dir);
  std::ofstream(out_dir + "/scene.json") << scene_to_json(scene);
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const double R = scene.geometry.radius;
  const double h = thickness_at_radius(scene.thickness, 0.0, R);
  const double Y = scene.material.youngs_modulus;
  const ContactProxy proxy = make_contact_proxy(model, segments);
  const double spacing = proxy_mean_edge_length(proxy);
  const double stiffness = stiffness_factor * contact_stiffness_scale(Y, h, spacing);
  const Eigen::VectorXd& X = model.reference_positions();
  const auto pinned = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);
  std::printf(
      "# disc R = %g, h = %g, %lld unknowns, proxy %lld vertices (spacing %.4g), "
      "penalty k = %.4g N/m\n",
      R, h, static_cast<long long>(model.dimension()), static_cast<long long>(proxy.num_vertices()),
      spacing, stiffness);
  const auto wall_start = Clock::now();

  if (!grow_from.empty() && !(phi_wind > 0.0))
    throw std::invalid_argument("--grow-from needs --phi-wind P > 0");
  // 1. The contact-free cone up to the start of the contact trace.
  Eigen::VectorXd x;
  double phi = 0.0;
  // The contact-free cone's samples (from flat only): written at the head of the symmetric
  // branch and joined to it for the energy crossing, which can lie below the contact trace's
  // start (docs/contact.md, "Exclusion radius").
  std::vector<BranchSample> cone_samples;
  std::vector<SpecialPoint> cone_special_points;
  NewtonOptions newton_options;
  newton_options.gradient_tolerance = tolerance * model.natural_force_scale();
  // Relaxations (skewed search, growth beyond the skewed branch): the decrement test stops
  // Newton's crawl along the nearly free orientation mode of the fold pattern (as in econe_at).
  newton_options.decrement_tolerance = 1e-6 * Y * h * h * h;
  if (!start_file.empty() || !grow_from.empty()) {
    const std::string file = grow_from.empty() ? start_file : grow_from;
    const BranchSample s = examples::load_point(file, model.dimension());
    x = s.x;
    phi = s.parameter;
    std::printf("# start: %s at phi_e = %.6f\n", file.c_str(), phi);
  } else {
    // The flat branch up to the n = 2 branch point and the mirror-symmetric cone born there,
    // by continuation as in trace_disc: the cone keeps the orientation of the critical mode
    // (folds on the mesh's mirror axes). Natural growth steps from a perturbed flat disc let
    // the fold pattern creep round instead and stop wherever Newton's decrement test stops the
    // crawl, on a saddle of the orientation (docs/validation.md).
    const ContactFreeConeOptions cone_options =
        examples::contact_free_cone_options(scene, model, tolerance, phi_contact_start);
    ContactFreeCone cone = trace_contact_free_cone(model, proxy, pinned, cone_options);
    if (!cone.found) throw std::runtime_error(cone.message);
    if (cone.stopped_before_contact)
      std::printf(
          "# --phi-contact-start %g lies past first contact: starting from the cone's last "
          "contact-free sample\n",
          phi_contact_start);
    x = cone.start.x;
    phi = cone.start.parameter;
    cone_samples = std::move(cone.samples);
    cone_special_points = std::move(cone.special_points);
    std::printf(
        "# buckled at phi_e = %.7f; cone traced without contact to phi_e = %.4f in %d "
        "steps (%.1f s)\n",
        cone.buckling_parameter, phi, cone.steps,
        std::chrono::duration<double>(Clock::now() - wall_start).count());
  }

  ContactBranchOptions options;
  options.contact_distance = scene.physics.contact_distance.value_or(h);
  options.exclusion_radius = resolved_exclusion_radius(scene);
  options.candidate_margin = margin_option > 0.0 ? margin_option : h;
  options.stiffness = stiffness;
  options.violation_tolerance = 0.25 * h;
  // Rim vertices pinned on the reference come round next to the pinning axis as the cone
  // grows (see ContactBranchOptions::repin_above_condition).
  options.repin_above_condition = 20.0;
  options.arclength.initial_step = max_step / 4;
  options.arclength.max_step = max_step;
  options.arclength.min_step = 1e-6;
  options.arclength.gradient_tolerance = tolerance * model.natural_force_scale();
  options.arclength.max_tangent_angle = 0.5;
  // The penalty's Hessian jumps where a pair enters contact, so the tangent may jump by a
  // finite angle over any step: short steps are accepted on a converged corrector alone.
  options.arclength.angle_test_max_step = 0.02 * max_step;
  // The stability index without the fold pattern's turn, as the cone_branch study counts it
  // (study.index_excludes_pattern_turn): the turn is neutral for an axisymmetric disc with or
  // without contact, and only nearly so on a mesh, where its sign is the mesh's.
  if (index_excludes_turn)
    options.stability_index = [&model, &pinned](const ParametrizedObjective& energy,
                                                const BranchSample& s) {
      TurnFreeStabilityIndex index(energy, model, pinned);
      return index.at(s.x, s.parameter);
    };

  // Output.
  std::vector<std::string> events;
  const auto write_events = [&] {
    std::ofstream ev(out_dir + "/events.json");
    ev << "[\n";
    for (std::size_t i = 0; i < events.size(); ++i)
      ev << "  " << events[i] << (i + 1 < events.size() ? ",\n" : "\n");
    ev << "]\n";
  };
  const auto add_event = [&](const std::string& kind, double at, const std::string& extra) {
    std::ostringstream j;
    j << "{\"kind\": \"" << kind << "\", \"phi_e\": " << json_number(at) << extra << "}";
    events.push_back(j.str());
    write_events();
    std::printf("# event %s at phi_e = %.7f%s\n", kind.c_str(), at, extra.c_str());
  };
  const auto open_branch = [&](BranchOutput& b, const std::string& name) {
    b.name = name;
    b.csv.open(out_dir + "/branch_" + name + ".csv");
    b.csv << std::setprecision(12)
          << "phi_e,E_stretch,E_bend,Eb_hat,area,min_gap,n_negative,gamma,n_contacts,"
             "contact_force,E_penalty,dE_dphi,arclength,corrector_iterations,pairs\n";
    std::filesystem::create_directories(out_dir + "/states_" + name);
  };
  bool symmetry_lost = false;
  const auto write_sample = [&](BranchOutput& b, const ContactBranchSample& s) {
    double gamma = std::numeric_limits<double>::quiet_NaN(), force = 0.0;
    std::unique_ptr<ContactGapConstraints> gaps;
    if (!s.pairs.empty()) {
      gaps = std::make_unique<ContactGapConstraints>(proxy, s.pairs, options.contact_distance,
                                                     model.dimension(), options.gap);
      if (s.active_pairs > 0) {
        // Zones: pairs within 0.1 R of each other whose normals differ by less than 30
        // degrees, so that the upper and lower contact of the cone, which meet at the apex,
        // stay apart.
        const std::vector<ContactZone> zones =
            contact_zones(*gaps, s.sample.x, s.forces, 0.1 * R, 1e-3, std::numbers::pi / 6);
        gamma = contact_plane_angle(zones);
      }
      // The symmetric branch keeps gamma = pi/2; a trace that turned onto the bifurcating
      // branch at a branch point shows it here first.
      if (b.name == "symmetric" && !symmetry_lost && std::isfinite(gamma) &&
          std::abs(gamma - 0.5 * std::numbers::pi) > 0.05) {
        symmetry_lost = true;
        add_event("symmetry_lost", s.sample.parameter, ", \"gamma\": " + json_number(gamma));
      }
      force = s.forces.sum();
    }
    std::printf("%-9s %9.5f %12.5e %12.5e %8.4f %10.3e %3d %7.4f %5d %10.3e %3d\n", b.name.c_str(),
                s.sample.parameter, s.stretching_energy, s.bending_energy, s.normalized_bending,
                s.min_distance, s.sample.negative_eigenvalues, gamma, s.active_pairs, force,
                s.sample.corrector_iterations);
    b.csv << s.sample.parameter << ',' << s.stretching_energy << ',' << s.bending_energy << ','
          << s.normalized_bending << ',' << s.current_area << ',' << s.min_distance << ','
          << s.sample.negative_eigenvalues << ',' << gamma << ',' << s.active_pairs << ',' << force
          << ',' << s.penalty_energy << ',' << s.energy_slope << ',' << s.sample.arclength << ','
          << s.sample.corrector_iterations << ',' << s.pairs.size() << '\n';
    b.csv.flush();
    std::ostringstream name;
    name << std::setw(5) << std::setfill('0') << b.index++;
    examples::save_point(out_dir + "/states_" + b.name + "/" + saved_state_name(b.index - 1),
                         s.sample);
    if (scene.output.write_vtk && scene.output.snapshot_every > 0 &&
        (b.index - 1) % scene.output.snapshot_every == 0) {
      const std::string shell_file = b.name + "_" + name.str() + ".vtu";
      write_vtu(out_dir + "/" + shell_file, shell_snapshot(model, s.sample.x, s.sample.parameter, 2));
      if (gaps)
        write_vtu(out_dir + "/" + b.name + "_contact_" + name.str() + ".vtu",
                  contact_snapshot(proxy, *gaps, s.sample.x, s.forces));
      b.snapshots.push_back({s.sample.parameter, shell_file});
      write_pvd(out_dir + "/branch_" + b.name + ".pvd", b.snapshots);
    }
  };
  std::printf("%-9s %9s %12s %12s %8s %10s %3s %7s %5s %10s %3s\n", "branch", "phi_e", "E_stretch",
              "E_bend", "Eb_hat", "min_gap", "neg", "gamma", "n_c", "force", "it");

  // 2-4. The symmetric branch, the skewed branch and the energy crossing.
  EconeBranchOptions branches;
  branches.contact = options;
  branches.symmetric_end = phi_max;
  branches.skewed_end = phi_wind > phi_max ? phi_wind : phi_max;
  branches.skewed_start = skew_from == "top" ? SkewedStart::Top : SkewedStart::BranchPoint;
  branches.skew_search_at = skew_at;
  branches.trace_skewed = skewed;
  // Starts further than h / 10 from symmetric (a grown fold pattern turned against the mesh)
  // are traced in the full space.
  branches.contact.symmetric_subspace = examples::subspace_for_start(
      examples::mirror_subspace_option(model, R, symmetric_subspace), x, 0.1 * h);
  // Ipopt verifies the relaxed skewed state under the hard constraints gap >= h.
  const ContactSolveOptions ipopt = hard_contact_solve_options(
      model, h, options.contact_distance, options.exclusion_radius, options.candidate_margin,
      newton_options);
  if (ipopt_check) branches.verify_with_ipopt = ipopt;
  branches.relaxation = newton_options;
  branches.relaxation.max_iterations = 400;
  BranchOutput symmetric, skew;
  open_branch(symmetric, "symmetric");
  EconeBranchCallbacks callbacks;
  // The highest stable skewed state: where the growth towards --phi-wind starts.
  Eigen::VectorXd top_skewed;
  double top_skewed_phi = -1.0;
  callbacks.on_sample = [&](EconeBranch which, const ContactBranchSample& s) {
    if (which == EconeBranch::Skewed && s.sample.negative_eigenvalues == 0 &&
        s.sample.parameter > top_skewed_phi) {
      top_skewed_phi = s.sample.parameter;
      top_skewed = s.sample.x;
    }
    BranchOutput& b = which == EconeBranch::Symmetric ? symmetric : skew;
    if (!b.csv.is_open()) open_branch(b, to_string(which));
    write_sample(b, s);
  };
  bool stability_lost = false;
  callbacks.on_special = [&](EconeBranch which, const SpecialPoint& sp) {
    std::ostringstream extra;
    extra << ", \"negative_before\": " << sp.negative_before
          << ", \"negative_after\": " << sp.negative_after
          << ", \"multiplicity\": " << sp.multiplicity
          << ", \"bracket\": " << json_number(sp.bracket_width) << ", \"branch\": \""
          << to_string(which) << "\"";
    add_event(to_string(sp.kind), sp.parameter, extra.str());
    if (which == EconeBranch::Symmetric && !stability_lost && sp.negative_before == 0 &&
        sp.negative_after > 0) {
      stability_lost = true;
      add_event("stability_loss", sp.parameter, extra.str());
    }
  };
  // The contact-free cone (from flat): its samples head the symmetric branch, and its special
  // points are the symmetric branch's (the subcritical stability loss can lie below the start
  // of the trace with contact, e.g. with an exclusion radius that covers the apex core).
  if (!cone_samples.empty()) cone_samples.pop_back();  // the start of the trace with contact
  // The descriptions written out carry the energies and slopes the crossing needs: one
  // evaluation per sample.
  for (const BranchSample& c : cone_samples) {
    const ContactBranchSample described =
        describe_contact_sample(model, proxy, c, ContactCandidates{}, options);
    branches.symmetric_before.push_back({c.parameter,
                                         described.stretching_energy + described.bending_energy,
                                         described.energy_slope});
    write_sample(symmetric, described);
  }
  cone_samples.clear();
  for (const SpecialPoint& p : cone_special_points) callbacks.on_special(EconeBranch::Symmetric, p);
  callbacks.on_event = [&](const LocatedEvent& e) {
    add_event(e.kind, e.parameter, ", \"bracket\": " + json_number(e.bracket_width));
  };
  callbacks.on_note = [](const std::string& text) { std::printf("# %s\n", text.c_str()); };
  EconeBranchResult result;
  if (grow_from.empty()) {
    result = trace_econe_branches(model, proxy, x, phi, pinned, branches, callbacks);
    // A saved start (--start) converged at a looser tolerance, or by a decrement test, can sit
    // further from equilibrium (along the nearly free orientation mode) than the corrector's
    // force tolerance: loosen it tenfold while no sample has converged, down to 1e-4.
    for (double t = 10.0 * tolerance; result.symmetric.steps == 0 && t <= 1e-4 * 1.0001;
         t *= 10.0) {
      std::printf("# the trace could not start at tolerance %.0e (%s); retrying at %.0e\n",
                  t / 10.0, result.symmetric.message.c_str(), t);
      branches.contact.arclength.gradient_tolerance = t * model.natural_force_scale();
      options.arclength.gradient_tolerance = branches.contact.arclength.gradient_tolerance;
      result = trace_econe_branches(model, proxy, x, phi, pinned, branches, callbacks);
    }
  } else {
    result.skewed_found = true;
    top_skewed = x;
    top_skewed_phi = phi;
  }
  if (grow_from.empty() && !result.stability_loss && !stability_lost)
    std::printf("# the symmetric branch stays stable up to phi_e = %.4f\n",
                result.symmetric.last.sample.parameter);
  if (result.ipopt_checked) {
    std::ostringstream extra;
    extra << ", \"converged\": " << (result.ipopt_converged ? "true" : "false")
          << ", \"elastic_energy_ipopt\": " << json_number(result.ipopt_energy)
          << ", \"elastic_energy_penalty\": " << json_number(result.penalty_elastic_energy)
          << ", \"max_state_difference\": " << json_number(result.ipopt_state_difference)
          << ", \"min_distance\": " << json_number(result.ipopt_min_distance)
          << ", \"seconds\": " << json_number(result.ipopt_seconds);
    add_event("ipopt_check", result.skew_search_parameter, extra.str());
  }
  for (std::size_t k = 0; k < result.crossings.size(); ++k) {
    const EnergyCrossing& c = result.crossings[k];
    std::ostringstream extra;
    extra << ", \"skewed_stable\": " << (result.crossing_skewed_stable[k] ? "true" : "false")
          << ", \"energy\": " << json_number(c.energy)
          << ", \"slope_difference\": " << json_number(c.slope_difference)
          << ", \"error_estimate\": " << json_number(c.error_estimate);
    add_event("energy_crossing", c.parameter, extra.str());
  }
  if (grow_from.empty() && result.skewed_found && result.crossings.empty())
    std::printf("# the branches' energies do not cross in the traced range\n");
  // 5. Beyond the skewed branch's upper end: grow on, minimising at every step, so that the path
  //    drops onto whatever stable state follows (the wound-up cones), up to --phi-wind.
  BranchOutput grown;
  std::string growth_message = "not needed";
  int growth_steps = 0, growth_failed = 0;
  double growth_seconds = 0.0;
  if (result.skewed_found && phi_wind > top_skewed_phi + 1e-9 && top_skewed.size() > 0) {
    ContactGrowthOptions growth;
    growth.contact = options;
    growth.newton = branches.relaxation;
    if (wind_step_bound > 0.0) growth.newton.max_step_inf_norm = wind_step_bound * h;
    // Where a stable state ends the sheet slides a long way (layers over layers) to the next
    // one: 75 bounded solves and 493 Newton steps at h = 0.04 (16 rings), phi_e = 8.91.
    growth.newton.max_iterations = 5000;
    if (wind_pairs == "triangles") growth.contact.selection = NearPairSelection{false, false};
    growth.max_step = 0.05;
    std::printf("# growing from the %s state at phi_e = %.5f to %.4f\n",
                grow_from.empty() ? "highest stable skewed" : "given", top_skewed_phi, phi_wind);
    open_branch(grown, "grown");
    const auto on_point = [&](const ContactGrowthPoint& p) {
      if (p.jumped) {
        std::ostringstream extra;
        extra << ", \"branch\": \"grown\", \"saddle_escapes\": " << p.saddle_escapes;
        add_event("jump", p.sample.sample.parameter, extra.str());
      }
      write_sample(grown, p.sample);
    };
    // The paper's wound-up shape is shown at phi_e = 4 pi: the growth stops there once, and that
    // state is written as wound_4pi.vtu (shell) and wound_4pi_contact.vtu (proxy, forces).
    const double four_pi = 4.0 * std::numbers::pi;
    const auto growth_start = Clock::now();
    ContactGrowthResult g;
    if (top_skewed_phi < four_pi && phi_wind > four_pi) {
      g = grow_with_contact(model, proxy, top_skewed, top_skewed_phi, four_pi, pinned, growth,
                            on_point);
      if (g.reached_target) {
        const ContactBranchSample& w = g.last.sample;
        write_vtu(out_dir + "/wound_4pi.vtu", shell_snapshot(model, w.sample.x, four_pi, 2));
        const ContactGapConstraints gaps(proxy, w.pairs, options.contact_distance,
                                         model.dimension(), options.gap);
        write_vtu(out_dir + "/wound_4pi_contact.vtu",
                  contact_snapshot(proxy, gaps, w.sample.x, w.forces));
        std::printf("# wrote the state at phi_e = 4 pi: %s/wound_4pi.vtu, wound_4pi_contact.vtu\n",
                    out_dir.c_str());
        const ContactGrowthResult rest = grow_with_contact(model, proxy, w.sample.x, four_pi,
                                                           phi_wind, pinned, growth, on_point);
        const int steps = g.steps + rest.steps, failed = g.failed_steps + rest.failed_steps;
        g = rest;
        g.steps = steps;
        g.failed_steps = failed;
      }
    } else {
      g = grow_with_contact(model, proxy, top_skewed, top_skewed_phi, phi_wind, pinned, growth,
                            on_point);
    }
    growth_message = g.reached_target ? "reached phi_e = " + std::to_string(phi_wind) : g.message;
    growth_steps = g.steps;
    growth_failed = g.failed_steps;
    growth_seconds = std::chrono::duration<double>(Clock::now() - growth_start).count();
    std::printf("# growth: %s (%d steps, %d failed)\n", growth_message.c_str(), g.steps,
                g.failed_steps);
  }
  const ContactBranchTrace& sym = result.symmetric;
  const ContactBranchTrace& skew_down = result.skewed_down;
  const ContactBranchTrace& skew_up = result.skewed_up;
  const double skew_search_seconds = result.skewed_search_seconds;
  const bool have_skewed = result.skewed_found;

  // Cost.
  const double wall = std::chrono::duration<double>(Clock::now() - wall_start).count();
  std::ofstream cost(out_dir + "/cost.json");
  const auto cost_json = [&](const ContactBranchTrace& t) {
    std::ostringstream o;
    const TraceCost& c = t.cost.continuation;
    o << "{\"steps\": " << t.steps << ", \"failed_steps\": " << t.failed_steps
      << ", \"segments\": " << t.cost.segments
      << ", \"rebuilds\": " << t.cost.rebuilds_after_violation
      << ", \"repinnings\": " << t.cost.repinnings << ", \"linearizations\": " << c.linearizations
      << ", \"factorizations\": " << c.factorizations << ", \"solves\": " << c.solves
      << ", \"assembly_seconds\": " << c.assembly_seconds
      << ", \"factorization_seconds\": " << c.factorization_seconds
      << ", \"solve_seconds\": " << c.solve_seconds << ", \"event_seconds\": " << c.event_seconds
      << ", \"stability_evaluations\": " << c.stability_evaluations
      << ", \"stability_seconds\": " << c.stability_seconds
      << ", \"continuation_seconds\": " << c.total_seconds
      << ", \"pair_search_seconds\": " << t.cost.pair_search_seconds
      << ", \"sample_seconds\": " << t.cost.sample_seconds << "}";
    return o.str();
  };
  cost << "{\n  \"wall_seconds\": " << wall << ",\n  \"symmetric\": " << cost_json(sym)
       << ",\n  \"skew_search_seconds\": " << skew_search_seconds
       << ",\n  \"skewed_down\": " << cost_json(skew_down)
       << ",\n  \"skewed_up\": " << cost_json(skew_up)
       << ",\n  \"grown\": {\"steps\": " << growth_steps << ", \"failed_steps\": " << growth_failed
       << ", \"seconds\": " << growth_seconds << "}\n}\n";
  std::printf("# %.1f s wall; wrote %s/branch_symmetric.csv%s, events.json, cost.json\n", wall,
              out_dir.c_str(), have_skewed ? ", branch_skewed.csv" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("trace_contact", run, argc, argv);
}
