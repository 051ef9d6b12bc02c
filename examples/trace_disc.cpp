// trace_disc: trace an e-cone branch of a growing disc or ring by pseudo-arclength
// continuation in the excess angle phi_e.
//
// From the flat state the flat branch is followed until the branch point whose critical mode
// has the requested number of folds n (--mode); the trace switches onto the n-fold cone and
// follows it (through folds, stable or not) up to first contact or --phi-max. Each converged
// point is appended to branch.csv and saved under states/ as soon as it converges; --resume
// restarts from any saved point, forward or --backward.
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "examples/support/guarded_main.hpp"
#include "examples/support/mirror_subspace_option.hpp"
#include "examples/support/saved_point.hpp"
#include "examples/support/scene_command_line.hpp"
#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/core_radius.hpp"
#include "libshell/analysis/rim_folds.hpp"
#include "libshell/analysis/self_distance.hpp"
#include "libshell/analysis/self_intersection.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "libshell/io/vtk_writer.hpp"
#include "solvers/continuation/cone_branch_entry.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/continuation/subspace_branch_trace.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace {

using namespace growshell;
using examples::load_point;
using examples::save_point;

const char* kUsage = R"(usage: trace_disc [scene.json] [options]
  --h H               thickness (overrides the scene)
  --inner-radius RI   make the sheet a ring with this inner radius
  --mode N            number of folds of the traced cone (default 2)
  --phi-max P         largest excess angle (default 3.73 in the default scene)
  --backward 1        trace towards decreasing phi_e (with --resume)
  --mesh FAMILY       mesh family: rings (default), gmsh or lattice (mesh.family)
  --size-slope C      element size per distance from the centre, rings and gmsh families
                      (mesh.size_slope, default 0.1)
  --rings N           resolution of the lattice family (rings of a disc, radial layers of a ring)
  --through-contact 1 do not stop at first contact
  --core-radius RC    ignore the sheet within RC of the centre when measuring the gap
                      (default 0; see docs/validation.md)
  --tolerance T       corrector force tolerance relative to Y h^3 / R (default 1e-6)
  --min-step S        smallest continuation step before the trace gives up (default 1e-4)
  --max-tangent-angle A  largest angle between successive tangents (rad, default 0.3);
                      raise it where a nearly broken symmetry bends the branch sharply
  --resume FILE       restart from a saved point (states/point_NNNNN.txt of an earlier run)
  --eigenmodes K      at each special point write the K lowest eigenmodes (default 2; 0 = off)
  --symmetric-subspace 1  trace the cone among the states with the mirrors of its folds (y -> -y,
                      and x -> -x for an even number of folds): the trace cannot turn onto a
                      branch that breaks them, e.g. at the symmetric cone's loss of stability;
                      the stability index is still the full Hessian's (default 0; a mesh
                      without the mirrors, e.g. a ring, or a resumed state off them is traced
                      in the full space, with a note)
  --symmetry-threshold D  S4 defect (dimensionless, see below) above which the event
                      symmetry_lost is written, once, at the first such point (default 1e-3)
  --out DIR           output directory (default: the scene's output.directory)
For the two-fold cone (--mode 2) branch.csv also holds s4_defect, the distance of the state
from its improper quarter-turn symmetry S4 (rms over the sheet vertices, over R; exact on a
mesh with the quarter-turn vertex symmetry, else with the image points interpolated over the
reference triangulation, which adds O(spacing^2)), and chord_up, chord_down, the gaps of the
two fold pairs over the generator length (equal for a symmetric cone); nan for other modes.
Writes DIR/branch.csv, DIR/events.json, DIR/scene.json, DIR/states/, DIR/branch.pvd and VTK
snapshots every output.snapshot_every points and at events.
)";

/// d/dalpha of Q(alpha) x(Q(alpha)^T X) at alpha = 0 (Q: rotation about the growth axis):
/// e_z x x - F (e_z x X), with the deformation gradient F of each vertex fitted by least
/// squares over its one-ring; pinned dofs zeroed.
Eigen::VectorXd pattern_rotation(const ShellModel& model, const Eigen::VectorXd& x,
                                 const std::vector<Eigen::Index>& pinned) {
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::Vector3d c = model.settings().growth.center;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const auto& ring = model.topology().one_ring(static_cast<int>(v));
    if (ring.size() < 2) continue;
    Eigen::Matrix2d XtX = Eigen::Matrix2d::Zero();
    Eigen::Matrix<double, 3, 2> xtX = Eigen::Matrix<double, 3, 2>::Zero();
    for (const int u : ring) {
      const Eigen::Vector2d dX = X.segment<2>(3 * u) - X.segment<2>(3 * v);
      const Eigen::Vector3d dx = x.segment<3>(3 * u) - x.segment<3>(3 * v);
      XtX += dX * dX.transpose();
      xtX += dx * dX.transpose();
    }
    const Eigen::Matrix<double, 3, 2> F = xtX * XtX.inverse();
    const Eigen::Vector2d R = X.segment<2>(3 * v) - c.head<2>();
    const Eigen::Vector3d r = x.segment<3>(3 * v) - c;
    out.segment<3>(3 * v) = Eigen::Vector3d(-r.y(), r.x(), 0.0) - F * Eigen::Vector2d(-R.y(), R.x());
  }
  for (const Eigen::Index d : pinned) out(d) = 0.0;
  return out;
}

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  auto [scene, cl] = examples::read_scene_command_line(argc, argv);
  if (cl.help()) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const auto set = [&](const char* option, const char* key) {
    const std::string v = cl.text(option, "");
    if (!v.empty()) apply_override(scene, key, v);
  };
  const std::string inner = cl.text("--inner-radius", "");
  if (!inner.empty()) {
    apply_override(scene, "geometry.shape", "ring");
    apply_override(scene, "geometry.inner_radius", inner);
  }
  set("--h", "thickness");
  set("--mode", "continuation.mode");
  set("--phi-max", "continuation.phi_max");
  set("--min-step", "continuation.min_step");
  set("--out", "output.directory");
  examples::apply_mesh_options(scene, cl);
  if (cl.integer("--backward", 0) != 0) apply_override(scene, "continuation.direction", "backward");
  const bool through_contact = cl.integer("--through-contact", 0) != 0;
  const std::string resume = cl.text("--resume", "");
  const double tolerance = cl.number("--tolerance", 1e-6);
  const double max_tangent_angle = cl.number("--max-tangent-angle", 0.3);
  const double core_radius = cl.number("--core-radius", 0.0);
  const int eigenmodes = cl.integer("--eigenmodes", 2);
  const bool symmetric_subspace = cl.integer("--symmetric-subspace", 0) != 0;
  const double symmetry_threshold = cl.number("--symmetry-threshold", 1e-3);
  cl.reject_unknown();
  if (!(symmetry_threshold > 0.0 && std::isfinite(symmetry_threshold)))
    throw std::invalid_argument("--symmetry-threshold must be finite and > 0");
  validate_scene(scene);

  // The model first: a mesh that cannot be built (e.g. a missing mesh.file) writes nothing.
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const std::string out_dir = scene.output.directory;
  std::filesystem::create_directories(out_dir + "/states");
  std::ofstream(out_dir + "/scene.json") << scene_to_json(scene);
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  const double contact_distance = scene.physics.contact_distance.value_or(h);
  std::printf("# %s R = %g%s, h = %g, mode %d, %lld elements, %lld unknowns\n",
              scene.geometry.shape == SceneShape::Ring ? "ring" : "disc", scene.geometry.radius,
              scene.geometry.shape == SceneShape::Ring
                  ? (", R_i = " + std::to_string(scene.geometry.inner_radius)).c_str()
                  : "",
              h, scene.continuation.mode, static_cast<long long>(model.num_elements()),
              static_cast<long long>(model.dimension()));

  // Rigid motions: pins on the mesh's mirror axes, so that symmetric states stay symmetric.
  const Eigen::VectorXd& X = model.reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  const auto pinned =
      mirror_axis_pinned_dofs(P, model.sheet_vertices(), model.settings().growth.center);
  ShellGrowthFamily family(model);
  std::shared_ptr<const SymmetricSubspace> subspace = examples::mirror_subspace_option(
      model, scene.geometry.radius, symmetric_subspace, scene.continuation.mode);
  // The cone branch, in the subspace if there is one (full states in and out either way).
  const auto trace_cone = [&](const Eigen::VectorXd& x0, double phi0, const Eigen::VectorXd& dx,
                              double dphi, const ArclengthOptions& o, const auto& on_sample,
                              const auto& on_special, const auto& events, const auto& on_event) {
    return subspace ? trace_branch_in_subspace(family, *subspace, x0, phi0, dx, dphi, pinned, o,
                                               on_sample, on_special, events, on_event)
                    : trace_branch_along(family, x0, phi0, dx, dphi, pinned, o, on_sample,
                                         on_special, events, on_event);
  };
  ArclengthOptions options;
  options.initial_step = scene.continuation.max_step / 4;
  options.max_step = scene.continuation.max_step;
  options.min_step = scene.continuation.min_step;
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance must be > 0");
  options.gradient_tolerance = tolerance * model.natural_force_scale();
  if (!(max_tangent_angle > 0.0 && max_tangent_angle < std::acos(-1.0)))
    throw std::invalid_argument("--max-tangent-angle must be in (0, pi)");
  options.max_tangent_angle = max_tangent_angle;
  options.parameter_min = scene.continuation.phi_min;
  options.parameter_max = scene.continuation.phi_max;

  // Output files.
  std::ofstream branch(out_dir + "/branch.csv", resume.empty() ? std::ios::trunc : std::ios::app);
  branch << std::setprecision(12);
  if (resume.empty())
    branch << "phi_e,E_stretch,E_bend,Eb_hat,area,min_gap,n_negative,corrector_iterations,"
              "arclength,folds,core_radius,s4_defect,chord_up,chord_down\n";
  std::vector<std::string> events_json;
  std::vector<CollectionEntry> snapshots;
  int point_index = 0;
  while (std::filesystem::exists(out_dir + "/states/point_" +
                                 (std::ostringstream() << std::setw(5) << std::setfill('0')
                                                       << point_index)
                                     .str() +
                                 ".txt"))
    ++point_index;
  SelfDistanceOptions gap_options;
  gap_options.exclusion_radius = 0.5 * std::acos(-1.0) * h;
  gap_options.core_radius = core_radius;
  gap_options.core_center = model.settings().growth.center;
  SelfIntersectionOptions crossing_options;
  crossing_options.exclusion_radius = gap_options.exclusion_radius;
  crossing_options.core_radius = gap_options.core_radius;
  crossing_options.core_center = gap_options.core_center;
  // The event functions and the progress line all need the gap of the same accepted sample:
  // the spatial search runs once per state.
  Eigen::VectorXd gap_state;
  double gap_value = 0.0;
  const auto gap_of = [&](const Eigen::VectorXd& x) {
    if (gap_state.size() != x.size() || gap_state != x) {
      gap_value = smallest_self_distance(model, x, gap_options).distance;
      gap_state = x;
    }
    return gap_value;
  };
  const auto snapshot = [&](const BranchSample& s, const std::string& name) {
    if (!scene.output.write_vtk) return;
    model.set_excess_angle(s.parameter);
    write_vtu(out_dir + "/" + name, shell_snapshot(model, s.x, 2));
    snapshots.push_back({s.parameter, name});
    write_pvd(out_dir + "/branch.pvd", snapshots);
  };
  int samples_on_cone = 0;
  // The S4 defect and fold-pair chords of the two-fold cone (nan otherwise, or where the
  // state has no fold directions); symmetry_lost once, at the first point above the threshold.
  const bool measure_symmetry = scene.continuation.mode == 2;
  bool symmetry_lost = false;
  double previous_phi = std::numeric_limits<double>::quiet_NaN();
  double previous_defect = std::numeric_limits<double>::quiet_NaN();
  const auto write_events = [&] {
    std::ofstream ev(out_dir + "/events.json");
    ev << "[\n";
    for (std::size_t i = 0; i < events_json.size(); ++i)
      ev << "  " << events_json[i] << (i + 1 < events_json.size() ? ",\n" : "\n");
    ev << "]\n";
  };
  const auto on_sample = [&](const BranchSample& s) {
    model.set_excess_angle(s.parameter);
    const ShellEnergyBreakdown e = model.energy_breakdown(s.x);
    const double gap = gap_of(s.x);
    const int folds = analyze_rim_folds(model, s.x).folds;
    // R_c: the radius about the growth centre holding half the stretching energy.
    const double core = e.stretching > 0.0
                            ? stretching_core_radius(model, s.x, 0.5, model.settings().growth.center).radius
                            : 0.0;
    std::printf("%9.5f %13.6e %13.6e %10.5f %10.3e %4d %3d %5d\n", s.parameter, e.stretching,
                e.bending, e.normalized_bending(), gap, s.negative_eigenvalues,
                s.corrector_iterations, folds);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    double defect = nan, chord_up = nan, chord_down = nan;
    if (measure_symmetry) {
      try {
        const ConeSymmetry sym = measure_cone_symmetry(model, s.x);
        defect = sym.s4.defect;
        chord_up = sym.chords.chord_up;
        chord_down = sym.chords.chord_down;
      } catch (const std::invalid_argument& err) {
        std::printf("# no S4 defect at phi_e = %.7f: %s\n", s.parameter, err.what());
      }
    }
    branch << s.parameter << ',' << e.stretching << ',' << e.bending << ','
           << e.normalized_bending() << ',' << e.current_area << ',' << gap << ','
           << s.negative_eigenvalues << ',' << s.corrector_iterations << ',' << s.arclength << ','
           << folds << ',' << core << ',' << defect << ',' << chord_up << ',' << chord_down << '\n';
    branch.flush();
    std::ostringstream name;
    name << "point_" << std::setw(5) << std::setfill('0') << point_index;
    if (!symmetry_lost && defect > symmetry_threshold) {
      symmetry_lost = true;
      std::ostringstream j;
      j << std::setprecision(10) << "{\"kind\": \"symmetry_lost\", \"phi_e\": " << s.parameter
        << ", \"s4_defect\": " << defect << ", \"chord_up\": " << chord_up
        << ", \"chord_down\": " << chord_down << ", \"threshold\": " << symmetry_threshold
        << ", \"state\": \"states/" << name.str() << ".txt\"";
      // The previous point (below the threshold) and the linear estimate of the crossing.
      if (std::isfinite(previous_defect))
        j << ", \"previous_phi_e\": " << previous_phi << ", \"previous_s4_defect\": "
          << previous_defect << ", \"phi_e_crossing\": "
          << previous_phi + (symmetry_threshold - previous_defect) / (defect - previous_defect) *
                                (s.parameter - previous_phi);
      j << "}";
      events_json.push_back(j.str());
      write_events();
      std::printf("# event symmetry_lost at phi_e = %.7f (S4 defect %.3e > %.3e, chords %.5f up, "
                  "%.5f down)\n",
                  s.parameter, defect, symmetry_threshold, chord_up, chord_down);
    }
    previous_phi = s.parameter;
    previous_defect = defect;
    save_point(out_dir + "/states/" + name.str() + ".txt", s);
    if (samples_on_cone++ % scene.output.snapshot_every == 0) snapshot(s, name.str() + ".vtu");
    ++point_index;
  };
  int special_index = 0;
  const auto on_special = [&](const SpecialPoint& sp) {
    std::ostringstream j;
    j << std::setprecision(10) << "{\"kind\": \"" << to_string(sp.kind) << "\", \"phi_e\": "
      << sp.parameter << ", \"multiplicity\": " << sp.multiplicity
      << ", \"negative_before\": " << sp.negative_before
      << ", \"negative_after\": " << sp.negative_after << ", \"bracket\": " << sp.bracket_width;
    if (eigenmodes > 0) {
      // The lowest eigenpairs of the pinned Hessian there, and their mode shapes (the state
      // displaced along each mode by 5 % of R at its largest) as VTK files.
      model.set_excess_angle(sp.parameter);
      EigenpairOptions eo;
      eo.count = eigenmodes;
      const Eigenpairs pairs = lowest_eigenpairs(model, sp.x, pinned, eo);
      // How much each mode is the fold pattern turning about the axis over the material
      // (x(X) -> Q x(Q^T X), Q a rotation about the growth axis): on a perfect disc that costs
      // nothing; on the discrete disc its eigenvalue is only nearly zero and changes sign
      // along the branch, so a special point whose critical mode is this (overlap near 1) is
      // the mesh's orientation mode, not a bifurcation of the continuum problem.
      const Eigen::VectorXd rotation = pattern_rotation(model, sp.x, pinned);
      j << ", \"orientation_overlap\": [";
      for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
        const Eigen::VectorXd v = pairs.vectors.col(k);
        j << (k ? ", " : "") << std::abs(v.dot(rotation)) / (v.norm() * rotation.norm());
      }
      j << "]";
      j << ", \"eigenvalues\": [";
      for (Eigen::Index k = 0; k < pairs.values.size(); ++k) {
        j << (k ? ", " : "") << pairs.values(k);
        if (scene.output.write_vtk) {
          const Eigen::VectorXd v = pairs.vectors.col(k);
          const double scale = 0.05 * scene.geometry.radius / v.lpNorm<Eigen::Infinity>();
          std::ostringstream name;
          name << "special_" << special_index << "_mode_" << k << ".vtu";
          write_vtu(out_dir + "/" + name.str(), shell_snapshot(model, sp.x + scale * v, 1));
        }
      }
      j << "]";
    }
    ++special_index;
    j << "}";
    events_json.push_back(j.str());
    write_events();
    std::printf("# %s at phi_e = %.7f (multiplicity %d, negative %d -> %d)\n", to_string(sp.kind),
                sp.parameter, sp.multiplicity, sp.negative_before, sp.negative_after);
  };
  const auto on_event = [&](const LocatedEvent& e) {
    std::ostringstream j;
    j << std::setprecision(10) << "{\"kind\": \"" << e.kind << "\", \"phi_e\": " << e.parameter
      << ", \"bracket\": " << e.bracket_width << "}";
    events_json.push_back(j.str());
    write_events();
    std::printf("# event %s at phi_e = %.7f\n", e.kind.c_str(), e.parameter);
    BranchSample s;
    s.parameter = e.parameter;
    s.x = e.x;
    snapshot(s, "event_" + e.kind + ".vtu");
  };
  // Test functions: gap minus the contact distance, the signed gap (negative once the
  // mid-surface has passed through itself), and dEb_hat/dphi_e.
  const auto eb_hat = [&](const Eigen::VectorXd& x, double phi) {
    model.set_excess_angle(phi);
    return model.energy_breakdown(x).normalized_bending();
  };
  const std::vector<BranchEvent> events = {
      {"contact", [&](const BranchSample& s) { return gap_of(s.x) - contact_distance; },
       !through_contact},
      {"midsurface_contact",
       [&](const BranchSample& s) {
         return signed_gap(find_self_intersection(model, s.x, crossing_options), gap_of(s.x));
       },
       false},
      {"eb_max",
       [&](const BranchSample& s) {
         const double eps = 1e-4;
         const double d = (eb_hat(s.x + eps * s.tangent_state, s.parameter + eps * s.tangent_parameter) -
                           eb_hat(s.x - eps * s.tangent_state, s.parameter - eps * s.tangent_parameter)) /
                          (2 * eps);
         return s.tangent_parameter >= 0 ? d : -d;
       },
       false}};

  std::printf("%9s %13s %13s %10s %10s %4s %3s %5s\n", "phi_e", "E_stretch", "E_bend", "Eb_hat",
              "min_gap", "neg", "it", "folds");
  BranchTrace trace;
  TraceCost flat_cost;
  const auto wall_start = std::chrono::steady_clock::now();
  if (!resume.empty()) {
    const BranchSample start = load_point(resume, model.dimension());
    const double sign = scene.continuation.direction == ContinuationDirection::Backward
                            ? (start.tangent_parameter > 0 ? -1.0 : 1.0)
                            : (start.tangent_parameter >= 0 ? 1.0 : -1.0);
    std::printf("# resuming from %s at phi_e = %.6f\n", resume.c_str(), start.parameter);
    subspace = examples::subspace_for_start(subspace, start.x, 0.1 * h);
    trace = trace_cone(start.x, start.parameter, sign * start.tangent_state,
                       sign * start.tangent_parameter, options, on_sample, on_special, events,
                       on_event);
  } else {
    ConeEntryOptions entry_options;
    entry_options.folds = scene.continuation.mode;
    entry_options.phi_start = scene.continuation.phi_start;
    entry_options.thickness = h;
    entry_options.radius = scene.geometry.radius;
    const ConeBranchEntry entry =
        enter_cone_branch(family, model, entry_options, pinned, options, on_special);
    flat_cost = entry.flat.cost;
    if (!entry.found) {
      std::fprintf(stderr, "trace_disc: error: %s\n", entry.message.c_str());
      return 3;
    }
    std::printf("# switching onto the %d-fold cone at phi_e = %.7f\n", scene.continuation.mode,
                entry.branch_point.parameter);
    trace = trace_cone(entry.start, entry.branch_point.parameter, entry.mode, 0.0, options,
                       on_sample, on_special, events, on_event);
  }
  snapshot(trace.last, "last.vtu");
  // Where the time went (flat branch + cone), also written to DIR/cost.json.
  TraceCost c = flat_cost;
  c += trace.cost;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::printf("# cost: %.1f s wall, %d linearisations (assembly %.1f s), %d LDL^T factorisations "
              "with inertia (%.1f s), %d solves (%.1f s), events %.1f s, output %.1f s\n",
              wall, c.linearizations, c.assembly_seconds, c.factorizations,
              c.factorization_seconds, c.solves, c.solve_seconds, c.event_seconds,
              c.callback_seconds);
  std::ofstream(out_dir + "/cost.json")
      << std::setprecision(6) << "{\"wall_seconds\": " << wall
      << ", \"cone_steps\": " << trace.steps << ", \"failed_steps\": " << trace.failed_steps
      << ", \"linearizations\": " << c.linearizations
      << ", \"factorizations\": " << c.factorizations << ", \"solves\": " << c.solves
      << ", \"assembly_seconds\": " << c.assembly_seconds
      << ", \"factorization_seconds\": " << c.factorization_seconds
      << ", \"solve_seconds\": " << c.solve_seconds << ", \"event_seconds\": " << c.event_seconds
      << ", \"output_seconds\": " << c.callback_seconds << "}\n";
  std::printf("# trace ended: %s (%d steps, %d failed)\n", trace.message.c_str(), trace.steps,
              trace.failed_steps);
  std::printf("# wrote %s/branch.csv, events.json, states/, branch.pvd\n", out_dir.c_str());
  return trace.reached_bound ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("trace_disc", run, argc, argv);
}
