// trace_disc: trace an e-cone branch of a growing disc or ring by pseudo-arclength
// continuation in the excess angle phi_e.
//
// From the flat state the flat branch is followed until the branch point whose critical mode
// has the requested number of folds n (--mode); the trace switches onto the n-fold cone and
// follows it (through folds, stable or not) up to first contact or --phi-max. Each converged
// point is appended to branch.csv and saved under states/ as soon as it converges; --resume
// restarts from any saved point, forward or --backward. The study itself is library code
// (studies/cone_branch_study.hpp, also run by `growshell run`); this program maps its options
// onto the scene and prints the study's log.
#include <cstdio>
#include <string>

#include "examples/support/guarded_main.hpp"
#include "examples/support/scene_command_line.hpp"
#include "libshell/io/scene.hpp"
#include "studies/cone_branch_study.hpp"

namespace {

using namespace growshell;

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
  --resume FILE       restart from a saved point (states/point_NNNNN.state of an earlier run)
  --eigenmodes K      at each special point write the K lowest eigenmodes (default 2; 0 = off)
  --symmetric-subspace 0|1  trace the cone among the states with the mirrors of its folds
                      (y -> -y, and x -> -x for an even number of folds): the trace cannot turn
                      onto a branch that breaks them, e.g. at the symmetric cone's loss of
                      stability, nor let the pattern drift about the axis; the stability index
                      is still the full Hessian's (default 1; a mesh without the mirrors, e.g.
                      gmsh, or a resumed state off them is traced in the full space, with a note)
  --symmetry-threshold D  S4 defect (dimensionless, see below) above which the event
                      symmetry_lost is written, once, at the first such point (default 1e-3)
  --index-excludes-pattern-turn 0  count the cone's stability index with the pattern's turn
                      about the axis, a neutral mode that the mesh leaves nearly neutral of
                      either sign (default 1: without it)
  --out DIR           output directory (default: the scene's output.directory)
For the two-fold cone (--mode 2) branch.csv also holds s4_defect, the distance of the state
from its improper quarter-turn symmetry S4 (rms over the sheet vertices, over R; exact on a
mesh with the quarter-turn vertex symmetry, else with the image points interpolated over the
reference triangulation, which adds O(spacing^2)), and chord_up, chord_down, the gaps of the
two fold pairs over the generator length (equal for a symmetric cone); nan for other modes.
Writes DIR/branch.csv, DIR/events.json, DIR/scene.json, DIR/states/, DIR/branch.pvd and VTK
snapshots every output.snapshot_every points and at events.
)";

/// Sets a number key from a number option, if it is given (parsed as the option's number,
/// so that a malformed value is reported by the option's name).
void set_number(Scene& scene, examples::CommandLine& cl, const char* option, const char* key) {
  if (cl.text(option, "").empty()) return;
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", cl.number(option, 0.0));
  apply_override(scene, key, text);
}

/// Sets a boolean key from an integer option (0 = false, anything else = true), if given.
void set_flag(Scene& scene, examples::CommandLine& cl, const char* option, const char* key) {
  if (cl.text(option, "").empty()) return;
  apply_override(scene, key, cl.integer(option, 0) != 0 ? "true" : "false");
}

int run(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  auto [scene, cl] = examples::read_scene_command_line(argc, argv);
  if (cl.help()) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const auto set = [&](const char* option, const char* key) {
    examples::apply_option(scene, cl, option, key);
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
  set_flag(scene, cl, "--through-contact", "study.through_contact");
  set_number(scene, cl, "--tolerance", "study.tolerance");
  set_number(scene, cl, "--max-tangent-angle", "study.max_tangent_angle");
  set_number(scene, cl, "--core-radius", "study.core_radius");
  if (!cl.text("--eigenmodes", "").empty())
    apply_override(scene, "study.eigenmodes", std::to_string(cl.integer("--eigenmodes", 0)));
  set_flag(scene, cl, "--symmetric-subspace", "study.symmetric_subspace");
  set_number(scene, cl, "--symmetry-threshold", "study.symmetry_threshold");
  set_flag(scene, cl, "--index-excludes-pattern-turn", "study.index_excludes_pattern_turn");
  const std::string resume = cl.text("--resume", "");
  cl.reject_unknown();
  validate_scene(scene);

  ConeBranchStudyOptions options = cone_branch_study_options(scene);
  if (!resume.empty()) {
    options.start = ConeBranchStart::SavedState;
    options.resume_file = resume;
  }
  const ConeBranchStudy study =
      run_cone_branch_study(scene, options, scene.output.directory,
                            [](const std::string& line) { std::printf("%s\n", line.c_str()); });
  if (!study.entered_cone) {
    std::fprintf(stderr, "trace_disc: error: %s\n", study.results.end.c_str());
    return 3;
  }
  return study.results.completed ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::guarded_main("trace_disc", run, argc, argv);
}
