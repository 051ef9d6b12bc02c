#pragma once
/// \file
/// DIR/contact_cost.json: what one run of the econe_contact study spent on its branches with
/// contact, trace by trace (the symmetric branch, the skewed cone down and up, the turned cone
/// down and up), with the skewed search, the hard-contact checks and the winding: the numbers
/// that say where the time of the paper's scene goes, and how many factorisations a step takes
/// (issue #16's measure; docs/performance.md). The contact-free cone's own cost is in
/// DIR/cone/cost.json. A stage that a resumed run takes from DIR/stages.json costs nothing and
/// is absent, so the file always describes the work of the run that wrote it.

#include <optional>
#include <string>
#include <vector>

#include "solvers/contact/contact_branch.hpp"

namespace growshell {

/// One trace with contact: its steps and what they cost.
struct EconeTraceWork {
  std::string trace;  ///< "symmetric", "skewed_down", "skewed_up", "turned_down", "turned_up"
  int steps = 0;
  int failed_steps = 0;
  ContactBranchCost cost;
};

/// The winding's work (study.wind_to), summed over this run's steps.
struct EconeWindingWork {
  int steps = 0;
  int minimisations = 0;  ///< ContactStepWork::tries
  int newton_iterations = 0;
  int factorizations = 0;  ///< Newton's plus one per stability test
  int eigen_solves = 0;
  double seconds = 0.0;
};

struct EconeContactCost {
  std::vector<EconeTraceWork> traces;  ///< in the order traced
  /// The relaxations of the skewed search (stage 3), if this run made it.
  std::optional<double> skewed_search_seconds;
  int hard_contact_checks = 0;  ///< Ipopt solves of stage 6 made by this run
  double hard_contact_seconds = 0.0;
  std::optional<EconeWindingWork> winding;  ///< if this run took winding steps
  double wall_seconds = 0.0;                ///< of the whole run, the cone's stage included
};

/// The traces' work summed: steps, failed steps and every cost (trace "all").
EconeTraceWork all_traces(const EconeContactCost& cost);

/// contact_cost.json's text: {"traces": [{trace, steps, failed_steps, stalled_correctors,
/// rejected_steps, tangent_angle_rejections, segments,
/// linearizations, factorizations, factorizations_per_step, stability_evaluations,
/// stability_evaluations_per_step, assembly_seconds, factorization_seconds, stability_seconds,
/// pair_search_seconds, sample_seconds, total_seconds, rebuilds_after_violation,
/// safeguarded_starts, relaxed_starts}], "all_traces": {the same sums over the traces, without
/// trace}, "skewed_search_seconds", "hard_contact_checks", "hard_contact_seconds", "winding":
/// {steps, minimisations, newton_iterations, factorizations, factorizations_per_step,
/// eigen_solves, seconds} or null, "wall_seconds"}, 2-space indent, trailing newline. A per-step
/// ratio is null without steps.
std::string econe_contact_cost_json(const EconeContactCost& cost);

}  // namespace growshell
