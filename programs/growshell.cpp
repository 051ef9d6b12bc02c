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
#include <stdexcept>
#include <string>
#include <vector>

#include "libshell/io/scene.hpp"
#include "studies/cone_branch_study.hpp"
#include "studies/study_directory.hpp"

extern char** environ;

namespace {

using namespace growshell;
namespace fs = std::filesystem;

const char* kUsage = R"(usage: growshell run SCENE.json [--out DIR] [--resume | --overwrite]
       growshell run --help
       growshell --help

Commands:
  run          run the study that SCENE.json names (its study.kind) and write its record,
               results.json and figure into DIR

Studies (scene key study.kind):
  cone_branch  the flat sheet grows to its first branch point of the n-fold mode
               (continuation.mode), switches onto the n-fold cone and traces it by
               pseudo-arclength continuation, with its branch points, folds, contact,
               mid-surface contact, E_b-hat maximum and S4 symmetry loss
               (docs/guide/cone_branch.md)

Scene files: docs/scenes.md (every key); examples/scenes/disc_h002.json (the default scene).
)";

const char* kRunUsage = R"(usage: growshell run SCENE.json [--out DIR] [--resume | --overwrite]
Runs the study that SCENE.json names (study.kind) and writes into DIR.
  --out DIR    output directory (default: the scene's output.directory)
  --resume     continue the study recorded in DIR from its last complete saved state (the
               record goes on without repeating a row; the scene may differ from the recorded
               one only in continuation.phi_min, continuation.phi_max, output.*,
               study.through_contact and study.eigenmodes)
  --overwrite  replace the study recorded in DIR
A DIR that exists and is not empty is refused unless --resume or --overwrite is given. Bad
input (a scene key out of range, an unknown key, a mesh that cannot be built) is refused by
name before anything is written.

Studies (study.kind):
  cone_branch  scene keys: the sheet, mesh and material keys, continuation.mode, phi_start,
               phi_min, phi_max, max_step, min_step, study.through_contact, study.tolerance,
               study.max_tangent_angle, study.eigenmodes, study.symmetric_subspace,
               study.symmetry_threshold, study.core_radius, output.snapshot_every,
               output.write_vtk (docs/guide/cone_branch.md)
               writes DIR/results.json (the key values), branch.csv, events.json, states/,
               record.json, branch.pvd and VTK files, cost.json, scene.json and eb_hat.png

The figure DIR/eb_hat.png is drawn by plot_study.py with /usr/bin/python3 (the environment
variable GROWSHELL_PYTHON names another interpreter) when it can import matplotlib; otherwise
it is skipped with a note, and the study stands.
Exit status: 0 the study completed, 3 its trace ended early (results.json "end" says why),
2 bad input.
)";

/// The parsed `growshell run` command line.
struct RunCommand {
  std::string scene_file;
  std::string out;
  ExistingOutput existing = ExistingOutput::Refuse;
  bool help = false;
};

RunCommand parse_run_command(int argc, char** argv) {
  RunCommand c;
  bool resume = false, overwrite = false;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      c.help = true;
    } else if (arg == "--out") {
      if (i + 1 >= argc) throw std::invalid_argument("option --out needs a directory");
      c.out = argv[++i];
    } else if (arg == "--resume") {
      resume = true;
    } else if (arg == "--overwrite") {
      overwrite = true;
    } else if (arg.rfind("-", 0) == 0) {
      throw std::invalid_argument("unknown option " + arg + " (growshell run --help lists them)");
    } else if (c.scene_file.empty()) {
      c.scene_file = arg;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "' (one scene file only)");
    }
  }
  if (resume && overwrite) throw std::invalid_argument("give --resume or --overwrite, not both");
  if (resume) c.existing = ExistingOutput::Resume;
  if (overwrite) c.existing = ExistingOutput::Overwrite;
  if (!c.help && c.scene_file.empty())
    throw std::invalid_argument("growshell run needs a scene file (growshell run --help)");
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

/// plot_study.py: the installed copy (../share/growshell/ from this program's bin/), else the
/// source tree's; empty if neither exists.
std::string plot_script() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share/growshell/plot_study.py";
    if (fs::is_regular_file(installed, ec)) return installed.string();
  }
#ifdef GROWSHELL_SOURCE_PLOT_SCRIPT
  if (fs::is_regular_file(GROWSHELL_SOURCE_PLOT_SCRIPT, ec)) return GROWSHELL_SOURCE_PLOT_SCRIPT;
#endif
  return "";
}

/// DIR/eb_hat.png by plot_study.py, or a note why not; never fails the study.
void draw_figure(const std::string& dir) {
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
  const std::string script = plot_script();
  if (script.empty()) {
    say("# figure skipped: plot_study.py is neither installed nor in the source tree");
    return;
  }
  const int status = run_process({python, script, dir}, false);
  if (status != 0)
    say("# figure failed: " + script + " exited with status " + std::to_string(status) +
        "; the study's results stand");
  else
    say("# wrote " + dir + "/eb_hat.png");
}

int run_study(const RunCommand& c) {
  Scene scene = read_scene(c.scene_file);
  if (!c.out.empty()) apply_override(scene, "output.directory", c.out);
  validate_scene(scene);
  const std::string dir = scene.output.directory;
  check_study_directory(dir, c.existing);
  switch (scene.study.kind) {
    case StudyKind::ConeBranch: {
      ConeBranchStudyOptions options = cone_branch_study_options(scene);
      if (c.existing == ExistingOutput::Resume) options.start = ConeBranchStart::LastState;
      say("# growshell run: study " + study_kind_name(scene.study.kind) + ", scene " +
          c.scene_file + ", output " + dir);
      const ConeBranchStudy study = run_cone_branch_study(scene, options, dir, say);
      draw_figure(dir);
      if (!study.results.completed) {
        std::fprintf(stderr, "growshell: the study ended early: %s\n", study.results.end.c_str());
        return 3;
      }
      return 0;
    }
  }
  throw std::logic_error("a study kind without a runner");
}

int dispatch(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (command != "run") {
    std::fputs(kUsage, stderr);
    if (!command.empty())
      std::fprintf(stderr, "growshell: error: unknown command '%s'\n", command.c_str());
    return 2;
  }
  const RunCommand c = parse_run_command(argc, argv);
  if (c.help) {
    std::fputs(kRunUsage, stdout);
    return 0;
  }
  return run_study(c);
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
