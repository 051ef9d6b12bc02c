#pragma once
/// \file
/// The series study: one study (study.series_of: cone_branch or econe_contact) at each value of
/// one scene key (study.series_key, study.series_values), and chosen key values of its results
/// (study.series_report) against that key. The paper's Table 1, the rings' phi_e^kiss against
/// their inner radius, is one: scenes/paper/table1_rings_kiss.json.
///
/// DIR is a parameter sweep over the key (studies/parameter_sweep.hpp: sweep_plan.json,
/// point_NNN/, sweep.json, sweep.csv) plus the series' own DIR/results.json and
/// DIR/series.csv. A killed series resumes as a sweep does: a finished point is never run
/// again, an unfinished one goes on from its last committed state. docs/guide/series.md is the
/// user's page.

#include <optional>
#include <string>
#include <vector>

#include "libshell/io/scene.hpp"
#include "studies/study_directory.hpp"
#include "studies/study_progress.hpp"

namespace growshell {

/// One value of the series: what its study's results.json says.
struct SeriesPoint {
  double value = 0.0;     ///< the varying key's value
  std::string directory;  ///< its study directory, relative to DIR ("point_000", ...)
  std::string status;     ///< "completed", "ended_early" or "failed"
  std::string end;        ///< why its study ended, or why it failed
  std::optional<long long> unknowns;
  /// The value of each study.series_report key, in that order; unset where the results lack
  /// it, hold null or a non-number, or the study failed.
  std::vector<std::optional<double>> reported;
};

/// The series' outcome.
struct SeriesResults {
  std::string key;                  ///< study.series_key
  std::string of;                   ///< the study run at each value ("cone_branch", ...)
  std::vector<std::string> report;  ///< study.series_report
  std::vector<SeriesPoint> points;  ///< in the order of study.series_values
  bool completed = false;           ///< every point completed
  std::string end;                  ///< "completed", or which points did not and why
  double wall_seconds = 0.0;
};

/// DIR/results.json's text: a JSON object with, in this order, study ("series"), of, key,
/// report, points [{value, directory, status, end, unknowns, one entry per report key,
/// results ("point_NNN/results.json")}], completed, end, wall_seconds. Non-finite and unset
/// values are null.
std::string series_results_json(const SeriesResults& results);

/// DIR/series.csv's text: a header (the key, status, unknowns, the report keys), then one row
/// per point; empty cells where a value is missing.
std::string series_csv(const SeriesResults& results);

/// The scene each point runs, before the key is set: `scene` with study.kind = series_of and
/// no series keys (the sweep's base scene).
Scene series_base_scene(const Scene& scene);

/// Runs the series of `scene` (study.kind series) into scene.output.directory: the sweep over
/// study.series_key (run_key_sweep; each point's log lines to `progress`), then
/// DIR/results.json and DIR/series.csv, each written atomically. Under Overwrite the earlier
/// series' summaries are removed first. Validates the scene, every point's scene and the
/// directory (check_key_sweep_directory) before anything is written (std::invalid_argument naming the key or what differs from the recorded series);
/// a point that fails is reported in the results, and the others go on.
SeriesResults run_series_study(const Scene& scene, ExistingOutput existing,
                               const StudyProgress& progress = {});

}  // namespace growshell
