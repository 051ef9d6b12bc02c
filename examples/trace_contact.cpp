// trace_contact: follow a growing disc through self-contact. From a saved state of trace_disc
// (before first contact), the excess angle is stepped up to --phi-max and every step is an
// energy minimum under the constraints gap >= h (Ipopt, libshell/contact and
// solvers/contact), or under the paper's quadratic penalty (--penalty K). Writes
// DIR/branch_contact.csv (the columns of trace_disc plus gamma, n_contacts, contact_force),
// DIR/events.json (first contact) and VTK snapshots with a branch.pvd collection.
#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "libshell/io/vtk_writer.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_zones.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: trace_contact SCENE.json --start STATE [options]
  SCENE.json          the scene of the trace_disc run that saved STATE (its DIR/scene.json)
  --start STATE       a saved point of that run (DIR/states/point_NNNNN.txt) before contact
  --phi-max P         last excess angle (default 10)
  --step S            step in phi_e (default 0.05; halved on failure down to 1e-4)
  --segments N        contact proxy: segments per element edge (default 1)
  --margin M          pairs within h + M become constraints (default h / 2)
  --penalty K         use the quadratic penalty with stiffness K (N/m) instead of Ipopt
  --out DIR           output directory (default out/contact)
)";

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (argc < 2 || argv[1][0] == '-') {
    const bool help = argc >= 2 && std::string(argv[1]) == "--help";
    std::fputs(kUsage, help ? stdout : stderr);
    return help ? 0 : 2;
  }
  Scene scene = read_scene(argv[1]);
  std::vector<char*> rest(argv + 2, argv + argc);
  rest.insert(rest.begin(), argv[0]);
  examples::CommandLine cl(static_cast<int>(rest.size()), rest.data());
  const std::string start_file = cl.text("--start", "");
  const double phi_max = cl.number("--phi-max", 10.0);
  const double max_step = cl.number("--step", 0.05);
  double step = max_step;
  const int segments = cl.integer("--segments", 1);
  const std::string out_dir = cl.text("--out", "out/contact");
  const double penalty = cl.number("--penalty", 0.0);
  const double margin_option = cl.number("--margin", -1.0);
  cl.reject_unknown();
  if (start_file.empty()) throw std::invalid_argument("--start STATE is required");
  if (!(step > 0.0)) throw std::invalid_argument("--step must be > 0");
  validate_scene(scene);

  std::filesystem::create_directories(out_dir);
  std::ofstream(out_dir + "/scene.json") << scene_to_json(scene);
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  const double contact_distance = scene.physics.contact_distance.value_or(h);
  const BranchSample start = examples::load_point(start_file, model.dimension());
  const ContactProxy proxy = make_contact_proxy(model, segments);
  const Eigen::VectorXd& X = model.reference_positions();
  const auto pinned = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);

  ContactSolveOptions options;
  options.contact_distance = contact_distance;
  options.exclusion_radius = 0.5 * std::acos(-1.0) * h;
  options.candidate_margin = margin_option > 0.0 ? margin_option : 0.5 * h;
  options.violation_tolerance = 1e-2 * h;
  options.minimizer.length_scale = h;
  options.minimizer.force_scale = model.natural_force_scale();
  options.minimizer.tolerance = 1e-6;
  options.minimizer.constraint_violation_tolerance = 1e-3 * h;
  options.minimizer.complementarity_tolerance = 1e-6 * model.natural_force_scale() * h;
  options.newton.gradient_tolerance = 1e-6 * model.natural_force_scale();
  options.newton.decrement_tolerance =
      1e-6 * scene.material.youngs_modulus * h * h * h;
  std::printf("# %s, h = %g, %lld unknowns, proxy %lld vertices, contact distance %g, %s\n",
              argv[1], h, static_cast<long long>(model.dimension()),
              static_cast<long long>(proxy.num_vertices()), contact_distance,
              penalty > 0.0 ? "penalty" : "Ipopt");

  std::ofstream csv(out_dir + "/branch_contact.csv");
  csv << std::setprecision(12)
      << "phi_e,E_stretch,E_bend,Eb_hat,area,min_gap,n_negative,gamma,n_contacts,contact_force,"
         "iterations,rounds,pairs,seconds\n";
  std::vector<CollectionEntry> snapshots;
  std::vector<std::string> events;
  std::printf("%9s %13s %13s %9s %10s %7s %4s %11s %5s %6s\n", "phi_e", "E_stretch", "E_bend",
              "Eb_hat", "min_gap", "gamma", "n_c", "force", "iter", "pairs");

  Eigen::VectorXd x = start.x;
  double phi = start.parameter;
  ContactSolveResult previous;
  bool have_previous = false, touched = false;
  int index = 0;
  while (phi < phi_max - 1e-12) {
    const double next_phi = std::min(phi_max, phi + step);
    model.set_excess_angle(next_phi);
    const auto t0 = std::chrono::steady_clock::now();
    ContactSolveResult r;
    if (penalty > 0.0) {
      // The paper's repulsion on the pairs near the current state, minimised by Newton.
      r.x = x;
      NearPairSelection selection;
      selection.edge_edge_pairs = options.edge_edge_pairs;
      selection.nearest_triangle_only = options.nearest_triangle_only;
      const ContactCandidates near = near_contact_pairs(
          proxy, x, contact_distance + options.candidate_margin, options.exclusion_radius, selection);
      ContactPenalty repulsion(proxy, near, contact_distance, penalty, model.dimension());
      PenalizedEnergy energy(model, repulsion);
      const NewtonResult n = NewtonSolver(options.newton).minimize(energy, x, pinned);
      r.converged = n.converged();
      r.message = n.message;
      r.x = n.x;
      r.iterations = n.iterations;
      r.rounds = 1;
      r.pairs = near;
      r.used_contact = !near.empty();
      if (!near.empty()) {
        ContactGapConstraints gaps(proxy, near, contact_distance, model.dimension());
        Eigen::VectorXd g;
        gaps.evaluate(r.x, g, nullptr);
        r.forces = (penalty * (-g.array()).max(0.0)).matrix();  // k * overlap per pair
        r.min_distance = contact_distance + g.minCoeff();
      } else {
        r.min_distance = std::numeric_limits<double>::infinity();
      }
    } else {
      r = solve_contact_equilibrium(model, proxy, x, pinned, options, have_previous ? &previous : nullptr);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.converged) {
      std::printf("# step to phi_e = %.5f failed (%s); halving the step\n", next_phi, r.message.c_str());
      step /= 2;
      if (step < 1e-4) {
        std::fprintf(stderr, "trace_contact: error: step below 1e-4 at phi_e = %g; results up to "
                     "there are in %s\n", phi, out_dir.c_str());
        return 3;
      }
      continue;
    }
    phi = next_phi;
    x = r.x;
    previous = r;
    have_previous = true;
    const ShellEnergyBreakdown e = model.energy_breakdown(x);
    double gamma = std::numeric_limits<double>::quiet_NaN(), total_force = 0.0;
    int contacts = 0;
    if (r.used_contact && r.forces.size() > 0) {
      ContactGapConstraints gaps(proxy, r.pairs, contact_distance, model.dimension());
      const std::vector<ContactZone> zones = contact_zones(gaps, x, r.forces, 0.1 * scene.geometry.radius);
      gamma = contact_plane_angle(zones);
      for (const ContactZone& z : zones) {
        contacts += static_cast<int>(z.pairs.size());
        total_force += z.force;
      }
    }
    if (contacts > 0 && !touched) {
      touched = true;
      std::ostringstream j;
      j << std::setprecision(10) << "{\"kind\": \"contact_active\", \"phi_e\": " << phi
        << ", \"bracket\": " << step << "}";
      events.push_back(j.str());
      std::ofstream ev(out_dir + "/events.json");
      ev << "[\n  " << events.back() << "\n]\n";
    }
    std::printf("%9.5f %13.6e %13.6e %9.4f %10.3e %7.4f %4d %11.4e %5d %6lld\n", phi, e.stretching,
                e.bending, e.normalized_bending(), r.min_distance, gamma, contacts, total_force,
                r.iterations, static_cast<long long>(r.pairs.vertex_triangle.rows() + r.pairs.edge_edge.rows()));
    csv << phi << ',' << e.stretching << ',' << e.bending << ',' << e.normalized_bending() << ','
        << e.current_area << ',' << r.min_distance << ",-1," << gamma << ',' << contacts << ','
        << total_force << ',' << r.iterations << ',' << r.rounds << ','
        << r.pairs.vertex_triangle.rows() + r.pairs.edge_edge.rows() << ',' << seconds << '\n';
    csv.flush();
    std::ostringstream name;
    name << "contact_" << std::setw(5) << std::setfill('0') << index++ << ".vtu";
    write_vtu(out_dir + "/" + name.str(), shell_snapshot(model, x, 2));
    snapshots.push_back({phi, name.str()});
    write_pvd(out_dir + "/branch.pvd", snapshots);
    BranchSample saved;
    saved.parameter = phi;
    saved.x = x;
    saved.tangent_state = Eigen::VectorXd::Zero(x.size());
    std::filesystem::create_directories(out_dir + "/states");
    examples::save_point(out_dir + "/states/" + name.str().substr(0, name.str().size() - 4) + ".txt", saved);
    step = std::min(step * 1.5, max_step);
  }
  std::printf("# reached phi_e = %g; wrote %s/branch_contact.csv\n", phi, out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("trace_contact", run, argc, argv);
}
