// trace_contact: the e-cone branches of a growing disc through self-contact, and the critical
// excess angle where the skewed cone takes over from the symmetric one.
//
// 1. The flat disc (seeded as econe_at) grows without contact, in natural steps, to
//    --phi-contact-start (below first contact), or a saved state is loaded (--start).
// 2. The symmetric branch is followed by pseudo-arclength continuation with the contact penalty
//    (solvers/contact/contact_branch.hpp) up to --phi-max, also where it is unstable; first
//    contact and the loss of stability are located on it.
// 3. Where the symmetric branch loses stability at a branch point, the skewed branch is entered
//    along the critical mode and followed both through its fold and up to --phi-wind (beyond
//    4 pi). Without such a point, the state at --phi-max is pushed along its lowest mode and
//    relaxed; a lower-energy state found so is followed down to its end and up.
// 4. The energy crossing of the two branches (solvers/continuation/branch_crossing.hpp) is
//    phi_e^crit.
// Writes DIR/branch_symmetric.csv, DIR/branch_skewed.csv, DIR/events.json, DIR/cost.json,
// DIR/scene.json, VTK snapshots of the shell and of the contact proxy (contact flags and
// forces) with DIR/branch_<name>.pvd, and every sample under DIR/states_<name>/.
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
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"
#include "examples/support/disc_perturbation.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/analysis/self_intersection.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/io/contact_snapshot.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "libshell/io/vtk_writer.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/contact_zones.hpp"
#include "solvers/continuation/branch_crossing.hpp"
#include "solvers/continuation/growth_path.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace {

using namespace growshell;
using Clock = std::chrono::steady_clock;

const char* kUsage = R"(usage: trace_contact [SCENE.json] [options]
  SCENE.json              scene (default: the paper's disc, R = 1, h = 0.02, Y = 1e4, nu = 0.3)
  --h H                   thickness (overrides the scene)
  --rings N               mesh rings
  --phi-max P             end of the symmetric branch and start of the skewed one (default 10)
  --phi-wind P            follow the skewed branch forward up to P (default 13; 0 = skip)
  --phi-contact-start P   contact-free growth from flat up to P (default 5.5)
  --start STATE           start from a saved contact-free state instead (trace_disc's
                          DIR/states/point_NNNNN.txt of the same scene)
  --stiffness-factor F    penalty stiffness k = F Y l^2 / h (l: proxy spacing; default 10)
  --segments N            contact proxy: segments per element edge (default 1)
  --margin M              pairs within h + M enter a segment's penalty (default h)
  --max-step S            largest arclength step (default 0.05)
  --tolerance T           corrector force tolerance relative to Y h^3 / R (default 1e-6)
  --skewed 0              trace the symmetric branch only
  --out DIR               output directory (default out/contact)
)";

struct BranchOutput {
  std::string name;
  std::ofstream csv;
  std::vector<CollectionEntry> snapshots;
  std::vector<BranchEnergySample> energies;
  std::vector<ContactBranchSample> samples;  // states dropped (kept on disk)
  int index = 0;
};

double total_energy(const ContactBranchSample& s) {
  return s.stretching_energy + s.bending_energy + s.penalty_energy;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o << std::setprecision(12) << v;
  return o.str();
}

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  Scene scene = default_scene();
  int first_option = 1;
  if (argc > 1 && argv[1][0] != '-') {
    scene = read_scene(argv[1]);
    first_option = 2;
  }
  std::vector<char*> rest(argv + first_option, argv + argc);
  rest.insert(rest.begin(), argv[0]);
  examples::CommandLine cl(static_cast<int>(rest.size()), rest.data());
  if (cl.help()) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const std::string h_text = cl.text("--h", "");
  if (!h_text.empty()) apply_override(scene, "thickness", h_text);
  const std::string rings = cl.text("--rings", "");
  if (!rings.empty()) apply_override(scene, "mesh.rings", rings);
  const double phi_max = cl.number("--phi-max", 10.0);
  const double phi_wind = cl.number("--phi-wind", 13.0);
  const double phi_contact_start = cl.number("--phi-contact-start", 5.5);
  const std::string start_file = cl.text("--start", "");
  const double stiffness_factor = cl.number("--stiffness-factor", 10.0);
  const int segments = cl.integer("--segments", 1);
  const double margin_option = cl.number("--margin", -1.0);
  const double max_step = cl.number("--max-step", 0.05);
  const double tolerance = cl.number("--tolerance", 1e-6);
  const bool skewed = cl.integer("--skewed", 1) != 0;
  const std::string out_dir = cl.text("--out", "out/contact");
  cl.reject_unknown();
  validate_scene(scene);
  if (!(stiffness_factor > 0.0)) throw std::invalid_argument("--stiffness-factor must be > 0");
  if (!(max_step > 0.0)) throw std::invalid_argument("--max-step must be > 0");
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance must be > 0");
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
  std::printf("# disc R = %g, h = %g, %lld unknowns, proxy %lld vertices (spacing %.4g), "
              "penalty k = %.4g N/m\n",
              R, h, static_cast<long long>(model.dimension()),
              static_cast<long long>(proxy.num_vertices()), spacing, stiffness);
  const auto wall_start = Clock::now();

  // 1. Contact-free growth to the start of the contact trace.
  Eigen::VectorXd x;
  double phi = 0.0;
  NewtonOptions newton_options;
  newton_options.gradient_tolerance = tolerance * model.natural_force_scale();
  newton_options.decrement_tolerance = 1e-6 * Y * h * h * h;
  if (!start_file.empty()) {
    const BranchSample s = examples::load_point(start_file, model.dimension());
    x = s.x;
    phi = s.parameter;
    std::printf("# start: %s at phi_e = %.6f\n", start_file.c_str(), phi);
  } else {
    std::mt19937 rng(scene.continuation.seed);
    const double amplitude = scene.continuation.perturbation_amplitude;
    const Eigen::VectorXd x_start =
        X + examples::disc_perturbation(model, amplitude, rng, R);
    GrowthPathOptions path_options;
    path_options.max_step = 0.25;
    const GrowthPathResult path = grow_along_path(
        model, x_start, 0.0, phi_contact_start, pinned, NewtonSolver(newton_options),
        [&](int) { return examples::disc_perturbation(model, amplitude, rng, R); }, path_options);
    if (!path.reached_target)
      throw std::runtime_error("the contact-free growth ended at phi_e = " +
                               std::to_string(path.last.excess_angle) + ": " + path.message);
    x = path.last.x;
    phi = path.last.excess_angle;
    std::printf("# grown without contact to phi_e = %.4f in %d steps (%.1f s)\n", phi, path.steps,
                std::chrono::duration<double>(Clock::now() - wall_start).count());
  }

  ContactBranchOptions options;
  options.contact_distance = scene.physics.contact_distance.value_or(h);
  options.exclusion_radius = 0.5 * std::numbers::pi * h;
  options.candidate_margin = margin_option > 0.0 ? margin_option : h;
  options.stiffness = stiffness;
  options.violation_tolerance = 0.25 * h;
  options.arclength.initial_step = max_step / 4;
  options.arclength.max_step = max_step;
  options.arclength.min_step = 1e-6;
  options.arclength.gradient_tolerance = tolerance * model.natural_force_scale();
  options.arclength.max_tangent_angle = 0.5;
  // The penalty's Hessian jumps where a pair enters contact, so the tangent may jump by a
  // finite angle over any step: short steps are accepted on a converged corrector alone.
  options.arclength.angle_test_max_step = 0.02 * max_step;

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
  const auto write_sample = [&](BranchOutput& b, const ContactBranchSample& s) {
    double gamma = std::numeric_limits<double>::quiet_NaN(), force = 0.0;
    std::unique_ptr<ContactGapConstraints> gaps;
    if (!s.pairs.empty()) {
      gaps = std::make_unique<ContactGapConstraints>(proxy, s.pairs, options.contact_distance,
                                                     model.dimension(), options.gap);
      if (s.active_pairs > 0) {
        const std::vector<ContactZone> zones = contact_zones(*gaps, s.sample.x, s.forces, 0.1 * R);
        gamma = contact_plane_angle(zones);
      }
      force = s.forces.sum();
    }
    std::printf("%-9s %9.5f %12.5e %12.5e %8.4f %10.3e %3d %7.4f %5d %10.3e %3d\n", b.name.c_str(),
                s.sample.parameter, s.stretching_energy, s.bending_energy, s.normalized_bending,
                s.min_distance, s.sample.negative_eigenvalues, gamma, s.active_pairs, force,
                s.sample.corrector_iterations);
    b.csv << s.sample.parameter << ',' << s.stretching_energy << ',' << s.bending_energy << ','
          << s.normalized_bending << ',' << s.current_area << ',' << s.min_distance << ','
          << s.sample.negative_eigenvalues << ',' << gamma << ',' << s.active_pairs << ','
          << force << ',' << s.penalty_energy << ',' << s.energy_slope << ','
          << s.sample.arclength << ',' << s.sample.corrector_iterations << ','
          << s.pairs.vertex_triangle.rows() + s.pairs.edge_edge.rows() << '\n';
    b.csv.flush();
    std::ostringstream name;
    name << std::setw(5) << std::setfill('0') << b.index++;
    examples::save_point(out_dir + "/states_" + b.name + "/point_" + name.str() + ".txt", s.sample);
    if (scene.output.write_vtk && (b.index - 1) % scene.output.snapshot_every == 0) {
      const std::string shell_file = b.name + "_" + name.str() + ".vtu";
      write_vtu(out_dir + "/" + shell_file, shell_snapshot(model, s.sample.x, 2));
      if (gaps)
        write_vtu(out_dir + "/" + b.name + "_contact_" + name.str() + ".vtu",
                  contact_snapshot(proxy, *gaps, s.sample.x, s.forces));
      b.snapshots.push_back({s.sample.parameter, shell_file});
      write_pvd(out_dir + "/branch_" + b.name + ".pvd", b.snapshots);
    }
    b.energies.push_back({s.sample.parameter, total_energy(s), s.energy_slope});
    ContactBranchSample light = s;
    light.sample.x.resize(0);
    light.sample.tangent_state.resize(0);
    b.samples.push_back(std::move(light));
  };
  std::printf("%-9s %9s %12s %12s %8s %10s %3s %7s %5s %10s %3s\n", "branch", "phi_e",
              "E_stretch", "E_bend", "Eb_hat", "min_gap", "neg", "gamma", "n_c", "force", "it");

  // The first-contact event: the smallest distance of near pairs reaches the contact distance.
  const double h_c = options.contact_distance;
  bool contact_found = false;  // after the event, the (costly) test function is not needed
  BranchEvent contact_event;
  contact_event.kind = "contact";
  contact_event.value = [&](const BranchSample& s) {
    if (contact_found) return -h_c;
    const ContactCandidates near =
        near_contact_pairs(proxy, s.x, 2.0 * h_c, options.exclusion_radius, options.selection);
    if (near.empty()) return h_c;
    ContactGapConstraints gaps(proxy, near, h_c, model.dimension(), options.gap);
    double d = 2.0 * h_c;
    for (Eigen::Index k = 0; k < gaps.count(); ++k) d = std::min(d, gaps.pair_geometry(s.x, k).distance);
    return d - h_c;
  };

  // 2. The symmetric branch.
  BranchOutput symmetric;
  open_branch(symmetric, "symmetric");
  bool stability_lost = false;
  std::optional<SpecialPoint> branch_point;  // where the symmetric branch loses stability
  const auto on_special_symmetric = [&](const SpecialPoint& sp) {
    std::ostringstream extra;
    extra << ", \"negative_before\": " << sp.negative_before << ", \"negative_after\": "
          << sp.negative_after << ", \"multiplicity\": " << sp.multiplicity
          << ", \"bracket\": " << json_number(sp.bracket_width) << ", \"branch\": \"symmetric\"";
    add_event(to_string(sp.kind), sp.parameter, extra.str());
    if (!stability_lost && sp.negative_before == 0 && sp.negative_after > 0) {
      stability_lost = true;
      add_event("stability_loss", sp.parameter, extra.str());
      if (sp.kind == SpecialPoint::Kind::BranchPoint) branch_point = sp;
    }
  };
  const auto on_event = [&](const LocatedEvent& e) {
    if (e.kind == "contact") contact_found = true;
    add_event(e.kind, e.parameter, ", \"bracket\": " + json_number(e.bracket_width));
  };
  ContactBranchOptions symmetric_options = options;
  symmetric_options.arclength.parameter_max = phi_max;
  symmetric_options.arclength.parameter_min = phi - 1.0;
  const ContactBranchTrace sym = trace_contact_branch(
      model, proxy, x, phi, Eigen::VectorXd::Zero(model.dimension()), 1.0, pinned,
      symmetric_options, [&](const ContactBranchSample& s) { write_sample(symmetric, s); },
      on_special_symmetric, {contact_event}, on_event);
  std::printf("# symmetric branch: %s (%d steps, %d failed, %d segments, %d rebuilds)\n",
              sym.message.c_str(), sym.steps, sym.failed_steps, sym.cost.segments,
              sym.cost.rebuilds_after_violation);
  if (!stability_lost)
    std::printf("# the symmetric branch stays stable up to phi_e = %.4f\n", sym.last.sample.parameter);

  // 3. The skewed branch. Where the symmetric branch loses stability at a branch point, the
  //    skewed branch is entered there along the critical mode (the eigenvector of the
  //    penalised Hessian whose eigenvalue is nearest zero) and followed wherever it goes: back
  //    down to its fold and up again (subcritical), or straight up. Otherwise the last
  //    symmetric state is pushed along its lowest mode and relaxed, and a lower-energy state
  //    found that way is followed down and up.
  BranchOutput skew;
  ContactBranchTrace skew_down, skew_up;
  bool have_skewed = false;
  double skew_search_seconds = 0.0;
  const auto on_special_skewed = [&](const SpecialPoint& sp) {
    std::ostringstream extra;
    extra << ", \"negative_before\": " << sp.negative_before << ", \"negative_after\": "
          << sp.negative_after << ", \"multiplicity\": " << sp.multiplicity
          << ", \"bracket\": " << json_number(sp.bracket_width) << ", \"branch\": \"skewed\"";
    add_event(to_string(sp.kind), sp.parameter, extra.str());
  };
  const double phi_top = phi_wind > phi_max ? phi_wind : phi_max;
  // The mode nearest zero (or the lowest) of the penalised Hessian at (y, phi_y).
  const auto critical_direction = [&](const Eigen::VectorXd& y, double phi_y, bool nearest_zero,
                                      double* eigenvalue) {
    model.set_excess_angle(phi_y);
    const ContactCandidates pairs = near_contact_pairs(
        proxy, y, h_c + options.candidate_margin, options.exclusion_radius, options.selection);
    ContactPenalty penalty(proxy, pairs, h_c, stiffness, model.dimension(), options.gap);
    PenalizedEnergy energy(model, penalty);
    EigenpairOptions eig;
    eig.count = 1;
    if (nearest_zero) eig.shift = 0.0;
    const Eigenpairs modes = lowest_eigenpairs(energy, y, pinned, eig);
    *eigenvalue = modes.values[0];
    return Eigen::VectorXd(modes.vectors.col(0));
  };
  if (skewed && branch_point.has_value()) {
    const auto t_search = Clock::now();
    double lambda = 0.0;
    const Eigen::VectorXd mode =
        critical_direction(branch_point->x, branch_point->parameter, true, &lambda);
    skew_search_seconds = std::chrono::duration<double>(Clock::now() - t_search).count();
    std::printf("# switching branches at phi_e = %.7f along the critical mode (eigenvalue %.3g)\n",
                branch_point->parameter, lambda);
    have_skewed = true;
    open_branch(skew, "skewed");
    ContactBranchOptions along = options;
    along.arclength.parameter_min = phi - 1.0;
    along.arclength.parameter_max = phi_top;
    along.arclength.max_steps = 600;
    // Off the branch point by h / 4 at the mode's largest entry: far enough for the corrector
    // to stay off the symmetric branch, close enough to land on the bifurcating one.
    const double offset = 0.25 * h / mode.cwiseAbs().maxCoeff();
    skew_up = trace_contact_branch(
        model, proxy, branch_point->x + offset * mode, branch_point->parameter, mode, 0.0, pinned,
        along, [&](const ContactBranchSample& s) { write_sample(skew, s); }, on_special_skewed);
    std::printf("# skewed branch: %s (%d steps)\n", skew_up.message.c_str(), skew_up.steps);
  } else if (skewed) {
    const auto t_search = Clock::now();
    const BranchSample& top = sym.last.sample;
    double lambda = 0.0;
    const Eigen::VectorXd mode = critical_direction(top.x, top.parameter, false, &lambda);
    const ContactCandidates top_pairs = near_contact_pairs(
        proxy, top.x, h_c + options.candidate_margin, options.exclusion_radius, options.selection);
    ContactPenalty top_penalty(proxy, top_pairs, h_c, stiffness, model.dimension(), options.gap);
    PenalizedEnergy top_energy(model, top_penalty);
    const double e_sym = top_energy.evaluate(top.x, nullptr, nullptr);
    std::printf("# lowest eigenvalue at phi_e = %.4f: %.4g\n", top.parameter, lambda);
    double best_energy = e_sym;
    Eigen::VectorXd best;
    for (int sign : {1, -1}) {
      // A push of h / 2 at the largest entry along the mode (small enough that no layer is
      // pushed through another), then relaxation with pair sets rebuilt until no pair outside
      // the set comes closer than allowed; the shifted Newton descends along negative
      // curvature.
      Eigen::VectorXd y = top.x + sign * (0.5 * h / mode.cwiseAbs().maxCoeff()) * mode;
      for (int round = 0; round < 6; ++round) {
        const ContactCandidates round_pairs = near_contact_pairs(
            proxy, y, h_c + options.candidate_margin, options.exclusion_radius, options.selection);
        ContactPenalty round_penalty(proxy, round_pairs, h_c, stiffness, model.dimension(),
                                     options.gap);
        PenalizedEnergy round_energy(model, round_penalty);
        NewtonOptions relax = newton_options;
        relax.max_iterations = 400;
        const NewtonResult r = NewtonSolver(relax).minimize(round_energy, y, pinned);
        y = r.x;
        const ContactCandidates close =
            near_contact_pairs(proxy, y, h_c - options.violation_tolerance,
                               options.exclusion_radius, options.selection);
        bool inside = true;
        for (Eigen::Index i = 0; i < close.vertex_triangle.rows() && inside; ++i) {
          bool found = false;
          for (Eigen::Index j = 0; j < round_pairs.vertex_triangle.rows() && !found; ++j)
            found = round_pairs.vertex_triangle(j, 0) == close.vertex_triangle(i, 0);
          inside = found;
        }
        if (r.converged() && inside) {
          SelfIntersectionOptions si;
          si.exclusion_radius = options.exclusion_radius;
          const bool crossed = find_self_intersection(model, y, si).intersects;
          std::printf("# relaxed the push %+d along the lowest mode: energy %.9e (symmetric "
                      "%.9e), %d Newton iterations%s\n",
                      sign, r.energy, e_sym, r.iterations,
                      crossed ? "; rejected: the sheet passes through itself" : "");
          if (!crossed && r.energy < best_energy - 1e-4 * std::abs(e_sym)) {
            best_energy = r.energy;
            best = y;
          }
          break;
        }
      }
    }
    skew_search_seconds = std::chrono::duration<double>(Clock::now() - t_search).count();
    if (best.size() == 0) {
      std::printf("# no state clearly below the symmetric one at phi_e = %.4f: no skewed "
                  "branch found\n", top.parameter);
    } else {
      have_skewed = true;
      open_branch(skew, "skewed");
      ContactBranchOptions down = options;
      down.arclength.parameter_min = phi - 1.0;
      down.arclength.parameter_max = phi_top;
      down.arclength.max_steps = 400;
      skew_down = trace_contact_branch(
          model, proxy, best, top.parameter, Eigen::VectorXd::Zero(model.dimension()), -1.0,
          pinned, down, [&](const ContactBranchSample& s) { write_sample(skew, s); },
          on_special_skewed);
      std::printf("# skewed branch, downwards: %s (%d steps)\n", skew_down.message.c_str(),
                  skew_down.steps);
      if (phi_wind > top.parameter) {
        ContactBranchOptions up = options;
        up.arclength.parameter_max = phi_wind;
        up.arclength.parameter_min = top.parameter - 1.0;
        skew_up = trace_contact_branch(
            model, proxy, best, top.parameter, Eigen::VectorXd::Zero(model.dimension()), 1.0,
            pinned, up, [&](const ContactBranchSample& s) { write_sample(skew, s); },
            on_special_skewed);
        std::printf("# skewed branch, upwards: %s (%d steps)\n", skew_up.message.c_str(),
                    skew_up.steps);
      }
    }
  }

  // 4. phi_e^crit: equal total energy. A skewed branch born at a branch point touches the
  //    symmetric one there (energy difference ~ (phi - phi_b)^2): that tangency is not a
  //    crossing and is dropped.
  if (have_skewed && skew.energies.size() >= 2 && symmetric.energies.size() >= 2) {
    // The downward trace (if any) comes first in skew.energies, then the upward one; they share
    // only their start, so each part is crossed with the symmetric branch separately.
    const std::size_t n_first = std::min(skew.energies.size(),
                                         static_cast<std::size_t>(skew_down.steps) + 1);
    std::vector<std::vector<BranchEnergySample>> parts;
    if (skew_down.steps > 0)
      parts.emplace_back(skew.energies.begin(), skew.energies.begin() + n_first);
    parts.emplace_back(skew.energies.begin() + (skew_down.steps > 0 ? n_first : 0),
                       skew.energies.end());
    int found = 0;
    for (const auto& part : parts) {
      if (part.size() < 2) continue;
      for (const EnergyCrossing& c : energy_crossings(symmetric.energies, part)) {
        if (branch_point && std::abs(c.parameter - branch_point->parameter) < 1e-3) continue;
        std::ostringstream extra;
        extra << ", \"energy\": " << json_number(c.energy) << ", \"slope_difference\": "
              << json_number(c.slope_difference) << ", \"error_estimate\": "
              << json_number(c.error_estimate);
        add_event("energy_crossing", c.parameter, extra.str());
        ++found;
      }
    }
    if (found == 0) std::printf("# the branches' energies do not cross in the traced range\n");
  }

  // Cost.
  const double wall = std::chrono::duration<double>(Clock::now() - wall_start).count();
  std::ofstream cost(out_dir + "/cost.json");
  const auto cost_json = [&](const ContactBranchTrace& t) {
    std::ostringstream o;
    const TraceCost& c = t.cost.continuation;
    o << "{\"steps\": " << t.steps << ", \"failed_steps\": " << t.failed_steps
      << ", \"segments\": " << t.cost.segments << ", \"rebuilds\": "
      << t.cost.rebuilds_after_violation << ", \"linearizations\": " << c.linearizations
      << ", \"factorizations\": " << c.factorizations << ", \"solves\": " << c.solves
      << ", \"assembly_seconds\": " << c.assembly_seconds
      << ", \"factorization_seconds\": " << c.factorization_seconds
      << ", \"solve_seconds\": " << c.solve_seconds << ", \"event_seconds\": " << c.event_seconds
      << ", \"continuation_seconds\": " << c.total_seconds
      << ", \"pair_search_seconds\": " << t.cost.pair_search_seconds
      << ", \"sample_seconds\": " << t.cost.sample_seconds << "}";
    return o.str();
  };
  cost << "{\n  \"wall_seconds\": " << wall << ",\n  \"symmetric\": " << cost_json(sym)
       << ",\n  \"skew_search_seconds\": " << skew_search_seconds
       << ",\n  \"skewed_down\": " << cost_json(skew_down)
       << ",\n  \"skewed_up\": " << cost_json(skew_up) << "\n}\n";
  std::printf("# %.1f s wall; wrote %s/branch_symmetric.csv%s, events.json, cost.json\n", wall,
              out_dir.c_str(), have_skewed ? ", branch_skewed.csv" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("trace_contact", run, argc, argv);
}
