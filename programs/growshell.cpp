// growshell: the one driver of the paper's computations. `growshell run SCENE.json --out DIR`
// runs the study the scene names (study.kind; the studies are library code, studies/) and
// writes its record and results.json into DIR, then draws the study's figure with
// scripts/plot_study.py when Python can. Everything it computes is the library's; this file
// only reads the command line, prints the study's log and runs the figure script.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "heartbeat_log.hpp"
#include "libshell/io/scene.hpp"
#include "studies/parameter_sweep.hpp"
#include "studies/scene_study.hpp"
#include "studies/study_directory.hpp"
#ifdef GROWSHELL_WITH_MPI
#include "sweep_on_ranks.hpp"
#endif

extern char** environ;

namespace {

using namespace growshell;
namespace fs = std::filesystem;

const char* kUsage = R"(usage: growshell run SCENE.json [--out DIR] [--set KEY=VALUE ...] [--resume | --overwrite]
       growshell sweep SCENE.json --out DIR --param KEY=V1,V2,... [--param ...]
                       [--set KEY=VALUE ...] [--resume | --overwrite]
       growshell run --help | growshell sweep --help | growshell --help

Commands:
  run          run the study that SCENE.json names (its study.kind) and write its record,
               results.json and figure into DIR
  sweep        run that study at every point of the product of the --param values, each
               point into DIR/point_NNN, and gather DIR/sweep.json and DIR/sweep.csv

Studies (scene key study.kind):
  cone_branch  the flat sheet grows to its first branch point of the n-fold mode
               (continuation.mode), switches onto the n-fold cone and traces it by
               pseudo-arclength continuation, with its branch points, folds, contact,
               mid-surface contact, E_b-hat maximum and S4 symmetry loss
               (docs/guide/cone_branch.md)
  thickness_series
               the cone_branch study at each thickness of study.thicknesses, with phi_e at
               the first branch point against c2 h^2 and phi_e^max - 2.57 fitted as A h^p
               (the paper's Fig. 2; docs/guide/thickness_series.md)
  econe_contact
               the two-fold cone through self-contact: the cone_branch study up to first
               contact, the symmetric branch with the contact penalty, the skewed cone, and
               phi_e^crit by stability and by energy (the paper's Fig. 4 at one thickness;
               docs/guide/econe_contact.md)
  series       the cone_branch or econe_contact study at each value of one scene key, with
               chosen results against it (e.g. the rings' phi_e^kiss against their inner
               radius, the paper's Table 1; docs/guide/series.md)

Scene files: docs/scenes.md (every key); examples/scenes/disc_h002.json (the default scene).
)";

const char* kRunUsage = R"(usage: growshell run SCENE.json [--out DIR] [--set KEY=VALUE ...] [--resume | --overwrite]
Runs the study that SCENE.json names (study.kind) and writes into DIR.
  --out DIR    output directory (default: the scene's output.directory)
  --set KEY=VALUE  sets one scene key (any key of docs/scenes.md, e.g. mesh.min_spacing=0.01
               or thickness=0.02), after the file and in the order given; the value is JSON
               for a number, boolean or array key, the text as is for a string key, auto where
               the key has it. DIR/scene.json records the scene as run.
  --resume     continue the study recorded in DIR from its last complete saved state (the
               record goes on without repeating a row; the scene may differ from the recorded
               one only in continuation.phi_start, phi_min, phi_max, output.*,
               study.through_contact and study.eigenmodes)
  --overwrite  replace the study recorded in DIR
A DIR that exists and is not empty is refused unless --resume or --overwrite is given. Bad
input (a scene key out of range, an unknown key, a mesh that cannot be built) is refused by
name before anything is written.

Studies (study.kind):
  cone_branch  scene keys: the sheet, mesh and material keys, continuation.mode, phi_start,
               phi_min, phi_max, max_step, min_step, study.through_contact, study.tolerance,
               study.max_tangent_angle, study.eigenmodes, study.symmetric_subspace,
               study.index_excludes_pattern_turn, study.phase_condition, study.symmetry_threshold,
               study.core_radius, output.snapshot_every,
               output.write_vtk (docs/guide/cone_branch.md)
               writes DIR/results.json (the key values), branch.csv, events.json, states/,
               record.json, branch.pvd and VTK files, cost.json, scene.json and eb_hat.png
  thickness_series
               scene keys: those of cone_branch (its thickness replaced by each value),
               study.thicknesses (at least two, m), study.phi_max_limit (default 2.57 rad)
               (docs/guide/thickness_series.md)
               writes DIR/results.json (the points, the two fits, c2), thickness_series.csv,
               thickness_series.png, and DIR/point_NNN/, one cone_branch study per thickness
               (with DIR/sweep_plan.json, sweep.json and sweep.csv, as growshell sweep writes
               them); --resume goes on with the thicknesses not yet finished
  econe_contact
               scene keys: those of cone_branch, physics.contact_exclusion_radius,
               physics.contact_distance, study.skew_search_at, study.contact_max_step,
               study.penalty_stiffness_factor, study.contact_proxy_segments,
               study.contact_surface, study.ipopt_check, study.hard_contact_at,
               study.hard_contact_branches, study.wind_to, study.wind_shapes_at,
               study.compare_modes (docs/guide/econe_contact.md)
               writes DIR/results.json (first contact, phi_e^crit both ways, the skewed cone,
               the hard-contact checks, the energy ratio f), DIR/cone/ (the cone_branch study
               up to first contact), DIR/symmetric/, DIR/skewed/ and DIR/turned/ (branch
               records with contact), DIR/wound/ (the winding), scene.json, econe_contact.png
               and contact_angle.png; --resume goes on with the cone from its last state and
               takes each finished stage from DIR/stages.json
  series       scene keys: those of the study it runs, study.series_key (a scene key),
               study.series_values (numbers), study.series_of (cone_branch or
               econe_contact), study.series_report (keys of the points' results.json)
               (docs/guide/series.md)
               writes DIR/results.json (each point's reported values), series.csv,
               series.png, and DIR/point_NNN/, one study per value (with
               DIR/sweep_plan.json, sweep.json and sweep.csv); --resume goes on with the
               values not yet finished

The figure (DIR/eb_hat.png, plot_study.py; DIR/thickness_series.png, plot_thickness_series.py;
DIR/econe_contact.png, plot_econe_contact.py, and DIR/contact_angle.png, plot_contact_angle.py;
DIR/series.png, plot_series.py)
is drawn with /usr/bin/python3 (the environment variable GROWSHELL_PYTHON names another
interpreter) when it can import matplotlib; otherwise it is skipped with a note, and the study
stands.
Exit status: 0 the study completed, 3 its trace (for a series: one of its traces) ended early
(results.json "end" says why),
2 bad input.
)";

const char* kSweepUsage = R"(usage: growshell sweep SCENE.json --out DIR --param KEY=V1,V2,... [--param ...]
                       [--set KEY=VALUE ...] [--resume | --overwrite]
Runs the study that SCENE.json names at every point of the cartesian product of the --param
values (the first --param varying slowest): on one process point after point, or under
an MPI launcher (mpirun -n K growshell sweep ...) on K ranks, each taking the next point.
  --out DIR    the sweep's directory (required)
  --param KEY=V1,V2,...  a scene key and its values (commas inside [...] belong to a value)
  --set KEY=VALUE  sets a scene key of every point (as for growshell run)
  --resume     go on with the sweep recorded in DIR: the scene, --set and --param must be
               those of DIR/sweep_plan.json; a point with results.json is not run again, a
               point with a record and no results is resumed from its last saved state
  --overwrite  replace the sweep recorded in DIR
Writes DIR/sweep_plan.json, DIR/point_NNN/ (each a study directory, as growshell run writes
it, without the figure), and after every point DIR/sweep.json
({"parameters": [...], "points": [{"params", "status", "reason", "results"}]}, results being
the point's results.json) and DIR/sweep.csv (a row per point: its parameters, status and the
scalar results), and at the end the figure DIR/sweep.png (scripts/plot_sweep.py: the key
results against the first numeric parameter). Under MPI, sweep.json is written at the start
and at the end. A point that fails is reported with its reason and the others go on. Every
point's scene is checked before anything is written.
Exit status: 0 every point completed, 3 some point ended early or failed, 2 bad input.
)";

/// The parsed `growshell run` or `growshell sweep` command line.
struct RunCommand {
  std::string scene_file;
  std::string out;
  std::vector<std::pair<std::string, std::string>> overrides;  ///< --set KEY=VALUE, in order
  std::vector<SweepParameter> parameters;                       ///< --param (sweep only)
  ExistingOutput existing = ExistingOutput::Refuse;
  bool help = false;
};

RunCommand parse_run_command(int argc, char** argv, bool sweep) {
  RunCommand c;
  bool resume = false, overwrite = false;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      c.help = true;
    } else if (arg == "--out") {
      if (i + 1 >= argc) throw std::invalid_argument("option --out needs a directory");
      c.out = argv[++i];
    } else if (arg == "--set") {
      if (i + 1 >= argc) throw std::invalid_argument("option --set needs KEY=VALUE");
      const std::string kv = argv[++i];
      const std::size_t eq = kv.find('=');
      if (eq == std::string::npos || eq == 0)
        throw std::invalid_argument("option --set takes KEY=VALUE (got '" + kv + "')");
      c.overrides.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    } else if (sweep && arg == "--param") {
      if (i + 1 >= argc) throw std::invalid_argument("option --param needs KEY=V1,V2,...");
      c.parameters.push_back(parse_sweep_parameter(argv[++i]));
    } else if (arg == "--resume") {
      resume = true;
    } else if (arg == "--overwrite") {
      overwrite = true;
    } else if (arg.rfind("-", 0) == 0) {
      throw std::invalid_argument("unknown option " + arg + " (growshell " +
                                  (sweep ? "sweep" : "run") + " --help lists them)");
    } else if (c.scene_file.empty()) {
      c.scene_file = arg;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "' (one scene file only)");
    }
  }
  if (resume && overwrite) throw std::invalid_argument("give --resume or --overwrite, not both");
  if (resume) c.existing = ExistingOutput::Resume;
  if (overwrite) c.existing = ExistingOutput::Overwrite;
  const std::string name = sweep ? "sweep" : "run";
  if (!c.help && c.scene_file.empty())
    throw std::invalid_argument("growshell " + name + " needs a scene file (growshell " + name +
                                " --help)");
  if (sweep && !c.help && c.out.empty())
    throw std::invalid_argument("growshell sweep needs --out DIR");
  if (sweep && !c.help && c.parameters.empty())
    throw std::invalid_argument("growshell sweep needs at least one --param KEY=V1,V2,...");
  return c;
}

void say(const std::string& line) { std::printf("%s\n", line.c_str()); }

/// Runs `args` (args[0] a path) and returns its exit status, or -1 if it could not be started
/// or did not exit normally; quiet sends its output to /dev/null.
int run_process(const std::vector<std::string>& args, bool quiet) {
  std::fflush(stdout);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  pid_t pid = 0;
  const int started = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

/// The figure script `name` (plot_study.py, plot_sweep.py): the installed copy
/// (../share/growshell/ from this program's bin/), else the source tree's; empty if neither
/// exists.
std::string plot_script(const std::string& name) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share/growshell" / name;
    if (fs::is_regular_file(installed, ec)) return installed.string();
  }
#ifdef GROWSHELL_SOURCE_SCRIPTS_DIR
  const fs::path source = fs::path(GROWSHELL_SOURCE_SCRIPTS_DIR) / name;
  if (fs::is_regular_file(source, ec)) return source.string();
#endif
  return "";
}

/// DIR/FIGURE drawn by the script `script_name` (called with DIR), or a note why not; never
/// fails the study or the sweep.
void draw_figure(const std::string& script_name, const std::string& dir,
                 const std::string& figure) {
  const char* chosen = std::getenv("GROWSHELL_PYTHON");
  const std::string python = chosen && *chosen ? chosen : "/usr/bin/python3";
  if (::access(python.c_str(), X_OK) != 0) {
    say("# figure skipped: " + python + " is not an executable Python");
    return;
  }
  if (run_process({python, "-c", "import matplotlib"}, true) != 0) {
    say("# figure skipped: " + python +
        " cannot import matplotlib (on Debian: apt-get install python3-matplotlib)");
    return;
  }
  const std::string script = plot_script(script_name);
  if (script.empty()) {
    say("# figure skipped: " + script_name + " is neither installed nor in the source tree");
    return;
  }
  const int status = run_process({python, script, dir}, false);
  if (status != 0)
    say("# figure failed: " + script + " exited with status " + std::to_string(status) +
        "; the study's results stand");
  else
    say("# wrote " + dir + "/" + figure);
}

/// The scene file with the --set overrides applied.
Scene command_scene(const RunCommand& c) {
  Scene scene = read_scene(c.scene_file);
  for (const auto& [key, value] : c.overrides) apply_override(scene, key, value);
  return scene;
}

/// What to say when a study ran out of memory: the mesh's size (built again once the study's
/// memory is freed), and what to change.
std::string out_of_memory_message(const Scene& scene) {
  std::string size = "the mesh";
  try {
    const TriangleMesh mesh = scene_mesh(scene);
    size += " of " + std::to_string(mesh.vertices.rows()) + " vertices (about " +
            std::to_string(3 * mesh.vertices.rows()) + " unknowns)";
  } catch (const std::exception&) {
    // Not even the mesh fits: say so without its size.
  }
  return "out of memory: " + size +
         " is too large for this machine's memory; choose a coarser mesh (mesh.size_slope, "
         "mesh.min_spacing, mesh.rings) or a machine with more memory";
}

int run_study(const RunCommand& c) {
  Scene scene = command_scene(c);
  if (!c.out.empty()) apply_override(scene, "output.directory", c.out);
  validate_scene(scene);
  const std::string dir = scene.output.directory;
  check_scene_study_directory(scene, c.existing);
  say("# growshell run: study " + study_kind_name(scene.study.kind) + ", scene " + c.scene_file +
      ", output " + dir);
  SceneStudyOutcome outcome;
  {
    // A line at least every 10 s, also while the study is busy in one long computation.
    HeartbeatLog log;
    try {
      outcome =
          run_scene_study(scene, c.existing, [&log](const std::string& line) { log(line); });
    } catch (const std::bad_alloc&) {
      throw std::runtime_error(out_of_memory_message(scene));
    }
  }
  if (scene.study.kind == StudyKind::ThicknessSeries)
    draw_figure("plot_thickness_series.py", dir, "thickness_series.png");
  else if (scene.study.kind == StudyKind::EconeContact) {
    draw_figure("plot_econe_contact.py", dir, "econe_contact.png");
    draw_figure("plot_contact_angle.py", dir, "contact_angle.png");
  } else if (scene.study.kind == StudyKind::Series)
    draw_figure("plot_series.py", dir, "series.png");
  else
    draw_figure("plot_study.py", dir, "eb_hat.png");
  if (!outcome.completed) {
    std::fprintf(stderr, "growshell: the study ended early: %s\n", outcome.end.c_str());
    return 3;
  }
  return 0;
}

int run_sweep(const RunCommand& c) {
  const Scene base = command_scene(c);
#ifdef GROWSHELL_WITH_MPI
  if (launched_by_mpi_launcher()) {
    const RankedSweepOutcome outcome =
        run_sweep_on_ranks(base, c.parameters, c.out, c.existing, say);
    // After MPI_Finalize: the figure's process is not started from inside MPI.
    if (outcome.wrote_summary) draw_figure("plot_sweep.py", c.out, "sweep.png");
    return outcome.exit_code;
  }
#endif
  say("# growshell sweep: study " + study_kind_name(base.study.kind) + ", scene " +
      c.scene_file + ", " + std::to_string(sweep_points(c.parameters).size()) + " points, output " +
      c.out);
  ParameterSweep sweep;
  {
    HeartbeatLog log;  // a line at least every 10 s
    sweep = run_parameter_sweep(base, c.parameters, c.out, c.existing,
                                [&log](const std::string& line) { log(line); });
  }
  int completed = 0;
  for (const SweepPointResult& r : sweep.results)
    completed += r.status == SweepPointResult::Status::Completed;
  say("# wrote " + c.out + "/sweep.json and sweep.csv: " + std::to_string(completed) + " of " +
      std::to_string(sweep.points.size()) + " points completed");
  draw_figure("plot_sweep.py", c.out, "sweep.png");
  if (!sweep.all_completed()) {
    std::fprintf(stderr, "growshell: %zu of %zu sweep points did not complete (sweep.json says why)\n",
                 sweep.points.size() - static_cast<std::size_t>(completed), sweep.points.size());
    return 3;
  }
  return 0;
}

int dispatch(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (command != "run" && command != "sweep") {
    std::fputs(kUsage, stderr);
    if (!command.empty())
      std::fprintf(stderr, "growshell: error: unknown command '%s'\n", command.c_str());
    return 2;
  }
  const bool sweep = command == "sweep";
  const RunCommand c = parse_run_command(argc, argv, sweep);
  if (c.help) {
    std::fputs(sweep ? kSweepUsage : kRunUsage, stdout);
    return 0;
  }
  return sweep ? run_sweep(c) : run_study(c);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "growshell: error: %s\n", e.what());
    return 2;
  }
}
