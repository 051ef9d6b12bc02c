// hard_contact_at: a penalty-traced state re-solved under Ipopt's hard contact constraints.
//
// The studies trace their branches through contact with the penalty (h - d)_+^2, which lets
// pairs come a little closer than the contact distance. Here the saved state nearest --phi of a
// traced branch is solved again with the gaps as inequality constraints (gap >= contact
// distance on vertex-triangle and edge-edge pairs, Ipopt; hard_contact_solve_options), from the
// penalty's state, and the two are compared: the elastic energies E_s + E_b, the largest
// difference of the states, the smallest pair distance, and the S4 defect of each. That is the
// contact solver of record at a reported point.
//
// Reads a cone_branch study's directory (scene.json, states/) or a branch of an econe_contact
// study (DIR/symmetric, DIR/skewed, DIR/turned: states/, with the scene one folder up). Writes
// RUN_DIR/hard_contact_phi<P>.json (P as given on the command line; atomically; an existing file
// is refused, so no earlier check is lost).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "examples/support/branch_directory.hpp"
#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/json_number.hpp"
#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/contact_zones.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/hard_contact_solve_options.hpp"
#include "solvers/contact/penalty_warm_start.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/atomic_file.hpp"
#include "studies/pattern_orientation_check.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: hard_contact_at RUN_DIR --phi P
  --phi P    the saved state nearest this excess angle is re-solved (required)
  --ipopt-print-level N
             Ipopt's own iteration log on stdout, 0..12 (default 0: none; 5 shows each
             iteration's objective, infeasibilities and barrier parameter)
RUN_DIR: a cone_branch study's directory (scene.json, states/), or a branch of an
econe_contact study (DIR/symmetric, DIR/skewed, DIR/turned: states/, the scene in DIR).
The hard constraints use the scene's contact distance and exclusion radius, with edge-edge
pairs as well as vertex-triangle ones; the Newton settings are the studies' relaxation
(scene_orientation_check_options). Prints the comparison and writes
RUN_DIR/hard_contact_phi<P>.json with:
  phi_e, unknowns, converged, message, seconds,
  rounds, iterations (Ipopt's, over the rounds of pair sets),
  penalty_elastic_energy, hard_elastic_energy (J, E_s + E_b),
  relative_energy_difference ((penalty - hard) / hard),
  state_difference_over_h (max |x_hard - x_penalty| / h),
  penalty_min_distance_over_h, hard_min_distance_over_h (smallest pair distance beyond the
  exclusion radius, over h),
  penalty_s4_defect, hard_s4_defect,
  penalty_gamma, hard_gamma (radians: the angle between the planes of the two largest
  contact zones, from the penalty's pair forces k (h - d)_+ and from Ipopt's multipliers;
  null with fewer than two zones)
)";

// The smallest distance over the vertex-triangle and edge-edge pairs of `x` nearer than
// `reach` and farther apart in the reference than the exclusion radius, or +infinity.
double smallest_distance(const ContactProxy& proxy, const Eigen::VectorXd& x,
                         double exclusion_radius, double reach) {
  return smallest_pair_distance(proxy, near_contact_pairs(proxy, x, reach, exclusion_radius), x);
}

int run(const std::string& dir, examples::CommandLine& cl) {
  const std::string phi_text = cl.text("--phi", "");
  const double phi = cl.number("--phi", std::numeric_limits<double>::quiet_NaN());
  const int print_level = cl.integer("--ipopt-print-level", 0);
  cl.reject_unknown();
  if (print_level < 0 || print_level > 12)
    throw std::invalid_argument("--ipopt-print-level must lie in 0..12");
  if (!std::isfinite(phi)) throw std::invalid_argument("--phi is required (a finite excess angle)");
  const std::string path = dir + "/hard_contact_phi" + phi_text + ".json";
  if (std::filesystem::exists(path))
    throw std::invalid_argument(path + " exists: move it away to check again");

  const Scene scene = read_scene(examples::branch_scene_file(dir));
  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const BranchSample state = examples::nearest_branch_state(dir, phi, scene, model.dimension());

  const ContactProxy proxy = make_contact_proxy(model, 1);
  const PatternOrientationCheckOptions studies = scene_orientation_check_options(scene, model, proxy);
  const ContactBranchOptions& penalty = studies.contact;
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  ContactSolveOptions options =
      hard_contact_solve_options(model, h, penalty.contact_distance, penalty.exclusion_radius,
                                 penalty.candidate_margin, studies.relaxation);
  options.minimizer.print_level = print_level;
  const Eigen::VectorXd& X = model.reference_positions();
  const auto pinned = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);
  const std::vector<Eigen::Index> pins = analysis_pins(
      model, state.x, pinned, TurnFreeStabilityIndex::kDefaultMaxPinCondition);

  std::printf("# %s: phi_e = %.6f, %lld unknowns; Ipopt under gap >= %.4g m beyond %.4g m\n",
              dir.c_str(), state.parameter, static_cast<long long>(model.dimension()),
              options.contact_distance, options.exclusion_radius);
  const auto start = std::chrono::steady_clock::now();
  // The penalty's own pairs and pair forces seed the constraints' multipliers.
  const ContactSolveResult warm =
      penalty_warm_start(proxy, near_penalty_pairs(proxy, state.x, penalty), state.x,
                         penalty.contact_distance, penalty.stiffness);
  const ContactSolveResult hard =
      solve_contact_equilibrium(model, state.parameter, proxy, state.x, pins, options, &warm);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const ShellEnergyBreakdown at_penalty = model.energy_breakdown(state.x, state.parameter);
  const ShellEnergyBreakdown at_hard = model.energy_breakdown(hard.x, state.parameter);
  const double e_penalty = at_penalty.stretching + at_penalty.bending;
  const double e_hard = at_hard.stretching + at_hard.bending;
  const double reach = 2.0 * penalty.contact_distance;
  const double d_penalty = smallest_distance(proxy, state.x, penalty.exclusion_radius, reach);
  const double d_hard = smallest_distance(proxy, hard.x, penalty.exclusion_radius, reach);
  // gamma from each solution's own pair forces: the penalty's k (h - d)_+, Ipopt's multipliers.
  const double gamma_penalty = cone_contact_plane_angle(
      ContactGapConstraints(proxy, warm.pairs, penalty.contact_distance, model.dimension()),
      state.x, warm.forces, scene.geometry.radius);
  const double gamma_hard =
      hard.forces.size() == 0
          ? std::numeric_limits<double>::quiet_NaN()
          : cone_contact_plane_angle(ContactGapConstraints(proxy, hard.pairs,
                                                           options.contact_distance,
                                                           model.dimension(), options.gap),
                                     hard.x, hard.forces, scene.geometry.radius);
  const auto s4 = [&](const Eigen::VectorXd& x) {
    try {
      return measure_cone_symmetry(model, x).s4.defect;
    } catch (const std::exception&) {
      return std::numeric_limits<double>::quiet_NaN();
    }
  };

  using examples::json_number;
  std::ostringstream json;
  json << std::setprecision(10) << "{\n"
       << "  \"phi_e\": " << json_number(state.parameter) << ",\n"
       << "  \"unknowns\": " << model.dimension() << ",\n"
       << "  \"converged\": " << (hard.converged ? "true" : "false") << ",\n"
       << "  \"message\": \"" << hard.message << "\",\n"
       << "  \"seconds\": " << json_number(seconds) << ",\n"
       << "  \"rounds\": " << hard.rounds << ",\n"
       << "  \"iterations\": " << hard.iterations << ",\n"
       << "  \"penalty_elastic_energy\": " << json_number(e_penalty) << ",\n"
       << "  \"hard_elastic_energy\": " << json_number(e_hard) << ",\n"
       << "  \"relative_energy_difference\": " << json_number((e_penalty - e_hard) / e_hard) << ",\n"
       << "  \"state_difference_over_h\": "
       << json_number((hard.x - state.x).cwiseAbs().maxCoeff() / h) << ",\n"
       << "  \"penalty_min_distance_over_h\": " << json_number(d_penalty / h) << ",\n"
       << "  \"hard_min_distance_over_h\": " << json_number(d_hard / h) << ",\n"
       << "  \"penalty_s4_defect\": " << json_number(s4(state.x)) << ",\n"
       << "  \"hard_s4_defect\": " << json_number(s4(hard.x)) << ",\n"
       << "  \"penalty_gamma\": " << json_number(gamma_penalty) << ",\n"
       << "  \"hard_gamma\": " << json_number(gamma_hard) << "\n}\n";
  write_file_atomically(path, json.str());
  std::printf("%s", json.str().c_str());
  std::printf("# wrote %s\n", path.c_str());
  return hard.converged ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("hard_contact_at", kUsage, run, argc, argv);
}
