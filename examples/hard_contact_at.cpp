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
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>

#include "examples/support/branch_directory.hpp"
#include "examples/support/directory_command_line.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "studies/atomic_file.hpp"
#include "studies/hard_contact_check.hpp"
#include "studies/scene_contact_penalty.hpp"

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
  const ContactProxy proxy = scene_contact_proxy(scene, model);
  std::printf("# %s: phi_e = %.6f, %lld unknowns; Ipopt under gap >= contact distance\n",
              dir.c_str(), state.parameter, static_cast<long long>(model.dimension()));
  const HardContactCheck check = check_hard_contact(scene, model, proxy, state, print_level);
  const std::string json = hard_contact_check_json(check);
  write_file_atomically(path, json);
  std::printf("%s", json.c_str());
  std::printf("# wrote %s\n", path.c_str());
  return check.converged ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("hard_contact_at", kUsage, run, argc, argv);
}
