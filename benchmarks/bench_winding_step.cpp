// bench_winding_step: what a step of the econe_contact study's winding (stage 8) costs, with
// and without the secant predictor and the adaptive Newton shift, on the states of a study that
// has wound.
//
// Reads STUDY_DIR/scene.json and the winding's record STUDY_DIR/wound (its saved states and
// pins.txt), and grows from the state of row --from (the state of row --from - 1 the one
// before it, for the predictor) by --steps steps with the study's winding settings
// (studies/econe_winding_options.hpp), once for each of the four combinations (--all 0: the
// study's alone). Prints per step
// its wall time and energy, and per combination the total, the steps taken from the
// prediction, and the largest relative difference of its energies from those of the first
// combination (the study's: predictor and adaptive shift on). A program, not a test: timings do
// not belong in the test suite.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "studies/econe_winding_options.hpp"
#include "studies/saved_state.hpp"
#include "studies/scene_contact_penalty.hpp"

namespace growshell {
namespace {

constexpr const char* kUsage =
    "usage: bench_winding_step --study DIR [--from 20] [--steps 4] [--all 1]\n"
    "  DIR: an econe_contact study that has wound (DIR/wound/states, DIR/wound/pins.txt)\n"
    "  --from: the row of DIR/wound the steps start from (>= 1)\n"
    "  --steps: winding steps per combination\n"
    "  --all: 1 for the four combinations of predictor and adaptive shift, 0 for the\n"
    "         study's alone";

int run(int argc, char** argv) {
  examples::CommandLine cl(argc, argv);
  if (cl.help()) {
    std::puts(kUsage);
    return 0;
  }
  const std::string dir = cl.text("--study", "");
  const int from = cl.integer("--from", 20);
  const int steps = cl.integer("--steps", 4);
  const bool all = cl.integer("--all", 1) != 0;
  cl.reject_unknown();
  if (dir.empty()) throw std::invalid_argument("--study DIR is required");
  if (from < 1 || steps < 1) throw std::invalid_argument("need --from >= 1 and --steps >= 1");
  const Scene scene = read_scene(dir + "/scene.json");
  const ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const std::uint64_t fingerprint = scene_model_fingerprint(scene);
  const ContactProxy proxy = scene_contact_proxy(scene, model);
  const std::vector<std::filesystem::path> saved = saved_state_files(dir + "/wound");
  if (static_cast<int>(saved.size()) <= from)
    throw std::invalid_argument(dir + "/wound holds " + std::to_string(saved.size()) +
                                " states; --from must be below that");
  const BranchSample before = load_branch_state(saved[from - 1].string(), model.dimension(),
                                                fingerprint);
  const BranchSample start = load_branch_state(saved[from].string(), model.dimension(),
                                               fingerprint);
  const std::vector<Eigen::Index> pins = read_winding_pins(dir + "/wound/pins.txt", model.dimension());
  const ContactGrowthOptions study = econe_winding_options(scene, model, proxy);
  const double target = start.parameter + steps * study.max_step;
  std::printf("# %s: %td unknowns, from row %d (phi_e = %.6f) by %d steps of %.3f\n",
              dir.c_str(), model.dimension(), from, start.parameter, steps, study.max_step);
  std::vector<double> reference;
  for (const bool predictor : {true, false})
    for (const bool adaptive : {true, false}) {
      if (!all && !(predictor && adaptive)) continue;
      ContactGrowthOptions o = study;
      o.secant_predictor = predictor;
      o.newton.adaptive_shift = adaptive;
      o.initial_step = o.max_step;
      std::vector<double> energies;
      auto last = std::chrono::steady_clock::now();
      const auto begin = last;
      const ContactGrowthResult r = grow_with_contact(
          model, proxy, start.x, start.parameter, target, pins, o,
          [&](const ContactGrowthPoint& p) {
            const auto now = std::chrono::steady_clock::now();
            const ContactBranchSample& s = p.sample;
            energies.push_back(s.stretching_energy + s.bending_energy + s.penalty_energy);
            const ContactStepWork& w = p.work;
            std::printf(
                "predictor %d adaptive %d  phi_e %.5f  E %.10e J  %6.2f s  tries %d halvings %d "
                "solves %d iterations %d factorisations %d eigensolves %d%s\n",
                predictor, adaptive, s.sample.parameter, energies.back(),
                std::chrono::duration<double>(now - last).count(), w.tries, w.halvings, w.solves,
                w.newton_iterations, w.factorizations, w.eigen_solves,
                p.from_prediction ? "  (from the prediction)" : "");
            std::fflush(stdout);
            last = now;
          },
          &before);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      if (reference.empty()) reference = energies;
      double differs = 0.0;
      for (std::size_t k = 0; k < energies.size() && k < reference.size(); ++k)
        differs = std::max(differs, std::abs(energies[k] / reference[k] - 1.0));
      std::printf(
          "predictor %d adaptive %d: %.1f s for %d steps (%.2f s a step), %d from the "
          "prediction, %d predictions discarded, %d failed; energies within %.1e of the first%s\n",
          predictor, adaptive, seconds, r.steps, seconds / std::max(1, r.steps), r.predicted_steps,
          r.discarded_predictions, r.failed_steps, differs,
          r.reached_target ? "" : ("; ended: " + r.message).c_str());
    }
  return 0;
}

}  // namespace
}  // namespace growshell

int main(int argc, char** argv) {
  try {
    return growshell::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_winding_step: %s\n", e.what());
    return 2;
  }
}
