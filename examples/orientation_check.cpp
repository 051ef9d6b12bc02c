// orientation_check: does a traced cone depend on where its folds sit against the mesh?
//
// Reads a cone_branch study's directory (scene.json and states/, e.g. an econe_contact study's
// DIR/cone or a sweep point) or a branch of an econe_contact study (DIR/symmetric, DIR/skewed,
// DIR/turned: states/, with the scene one folder up), takes its saved state nearest --phi,
// turns the fold pattern over the material by each of --turns, relaxes it at the same excess
// angle with the contact penalty of the econe_contact study, and compares it with the traced state
// (studies/pattern_orientation_check.hpp): the continuum gives every turn the same state.
// Prints one line per turn and writes RUN_DIR/orientation_check_phi<P>.csv (atomically; P as
// given on the command line, so that checks at several excess angles do not overwrite each
// other).
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/branch_directory.hpp"
#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/atomic_file.hpp"
#include "studies/pattern_orientation_check.hpp"
#include "studies/scene_contact_penalty.hpp"

namespace {

using namespace growshell;

const char* kUsage = R"(usage: orientation_check RUN_DIR [options]
  --phi P          the saved state nearest this excess angle is checked (required)
  --turns A,B,...  turns of the fold pattern in degrees (default 22.5)
  --tolerance T    force tolerance of the relaxation relative to Y h^3 / R (default: the
                   scene's study.tolerance)
RUN_DIR: a cone_branch study's directory (scene.json, states/), or a branch of an
econe_contact study (DIR/symmetric, DIR/skewed, DIR/turned: states/, the scene in DIR). The
penalty and the relaxation are the studies' (scene_orientation_check_options): contact distance
and exclusion radius from the scene, stiffness study.penalty_stiffness_factor Y l^2 / h,
margin h.
Writes RUN_DIR/orientation_check_phi<P>.csv (P as given), one row per turn:
  phi_e, turn_deg, converged, fold_angle_deg (where the folds settled; the traced state's in
  traced_fold_angle_deg), energy_relative ((E_turned - E_traced) / E_traced, E = E_s + E_b + P),
  s4_defect (and traced_s4_defect), chord_up, chord_down, energy_change_core and
  energy_change_outside (J, inside and outside r = h), lowest_eigenvalue (N/m, pins held),
  turn_free_index
)";

int run(const std::string& dir, examples::CommandLine& cl) {
  const std::string phi_text = cl.text("--phi", "");
  const double phi = cl.number("--phi", std::numeric_limits<double>::quiet_NaN());
  const std::vector<double> turns_deg = cl.number_list("--turns", "22.5");
  const double tolerance = cl.number("--tolerance", -1.0);
  cl.reject_unknown();
  if (!std::isfinite(phi)) throw std::invalid_argument("--phi is required (a finite excess angle)");
  if (!(tolerance > 0.0 && std::isfinite(tolerance)) && tolerance != -1.0)
    throw std::invalid_argument("--tolerance must be finite and > 0");

  const Scene scene = read_scene(examples::branch_scene_file(dir));
  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const BranchSample state = examples::nearest_branch_state(dir, phi, scene, model.dimension());

  Scene checked = scene;
  checked.study.orientation_check_turns = turns_deg;
  if (tolerance != -1.0) checked.study.tolerance = tolerance;
  const ContactProxy proxy = scene_contact_proxy(scene, model);
  const PatternOrientationCheckOptions o = scene_orientation_check_options(checked, model, proxy);
  const Eigen::VectorXd& X = model.reference_positions();
  const std::vector<Eigen::Index> pins = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);

  const PatternOrientationCheck check =
      check_pattern_orientation(model, proxy, state.x, state.parameter, pins, o);
  constexpr double kDeg = 180.0 / std::numbers::pi;
  std::printf("# %s: phi_e = %.6f, %lld unknowns; traced folds at %.3f deg, S4 defect %.3g\n",
              dir.c_str(), check.phi_e, static_cast<long long>(model.dimension()),
              check.fold_angle * kDeg, check.s4_defect);
  std::printf("# %8s %9s %11s %9s %8s %8s %11s %11s %11s %3s\n", "turn", "settled", "dE/E", "S4",
              "chord_up", "chord_dn", "dE_core J", "dE_out J", "lowest", "idx");
  std::ostringstream csv;
  csv << std::setprecision(10)
      << "phi_e,turn_deg,converged,fold_angle_deg,traced_fold_angle_deg,energy_relative,"
         "s4_defect,traced_s4_defect,chord_up,chord_down,energy_change_core,"
         "energy_change_outside,lowest_eigenvalue,turn_free_index\n";
  for (const TurnedPatternState& t : check.turned) {
    if (!t.converged) {
      std::printf("  %8.3f relaxation failed: %s\n", t.turn * kDeg, t.message.c_str());
      csv << check.phi_e << ',' << t.turn * kDeg << ",0,nan," << check.fold_angle * kDeg
          << ",nan,nan," << check.s4_defect << ",nan,nan,nan,nan,nan,-1\n";
      continue;
    }
    std::printf("  %8.3f %9.3f %+11.4e %9.3e %8.4f %8.4f %+11.4e %+11.4e %+11.4e %3d\n",
                t.turn * kDeg, t.fold_angle * kDeg, t.energy_relative, t.s4_defect, t.chord_up,
                t.chord_down, t.energy_change_core, t.energy_change_outside, t.lowest_eigenvalue,
                t.turn_free_index);
    csv << check.phi_e << ',' << t.turn * kDeg << ",1," << t.fold_angle * kDeg << ','
        << check.fold_angle * kDeg << ',' << t.energy_relative << ',' << t.s4_defect << ','
        << check.s4_defect << ',' << t.chord_up << ',' << t.chord_down << ','
        << t.energy_change_core << ',' << t.energy_change_outside << ',' << t.lowest_eigenvalue
        << ',' << t.turn_free_index << '\n';
  }
  const std::string path = dir + "/orientation_check_phi" + phi_text + ".csv";
  write_file_atomically(path, csv.str());
  std::printf("# wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("orientation_check", kUsage, run, argc, argv);
}
