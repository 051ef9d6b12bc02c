#pragma once
/// \file
/// A parameter sweep: one study (the base scene's study.kind) at every point of the cartesian
/// product of some scene keys' values, each point a study directory of its own, gathered into
/// DIR/sweep.json and DIR/sweep.csv. `growshell sweep` is its program; a mesh convergence
/// study or phi_e^crit(h) is one sweep. Points are independent, so a program may run them in
/// any order or on several processes; this file runs them in order, on one.
///
/// DIR holds sweep_plan.json (the base scene and the parameters: what a resume must match),
/// point_NNN/ (one study directory per point, NNN its index) and the summaries. A point whose
/// directory holds results.json is done and is never run again; one with a record but no
/// results (a killed run) is resumed from its last committed state; a point that fails is
/// reported with its reason and the others go on.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libshell/io/scene.hpp"
#include "studies/study_directory.hpp"
#include "studies/study_progress.hpp"

namespace growshell {

/// One swept scene key and its values, in the order given.
struct SweepParameter {
  std::string key;                  ///< a scene key of docs/scenes.md, e.g. "thickness"
  std::vector<std::string> values;  ///< as apply_override takes them (JSON, or text)
};

/// "KEY=V1,V2,...": a comma inside [...] or {...} belongs to its value, e.g.
/// "growth.center=[0,0,0],[0.1,0,0]". Throws std::invalid_argument, quoting the text, without
/// '=', with an empty key, or with an empty value.
SweepParameter parse_sweep_parameter(const std::string& text);

/// One point of a sweep.
struct SweepPoint {
  int index = 0;  ///< 0-based, in the order of sweep_points
  /// One (key, value) per parameter, in the parameters' order.
  std::vector<std::pair<std::string, std::string>> settings;
  std::string directory;  ///< "point_NNN" (NNN = index, zero-padded to 3 digits or more)
};

/// The cartesian product of the parameters' values, the first parameter varying slowest.
/// Throws std::invalid_argument if there is no parameter, a key is swept twice, or the
/// product has more than 10000 points.
std::vector<SweepPoint> sweep_points(const std::vector<SweepParameter>& parameters);

/// The scene of a point: `base` with the point's settings applied (apply_override) and
/// output.directory = sweep_dir/point.directory, validated. Throws std::invalid_argument
/// naming the point's settings and the key at fault, or saying that a thickness_series base
/// scene or a series scene (each a sweep itself) cannot be swept.
Scene sweep_point_scene(const Scene& base, const SweepPoint& point, const std::string& sweep_dir);

/// How a point ended.
struct SweepPointResult {
  enum class Status {
    Completed,   ///< its study completed
    EndedEarly,  ///< its study ended before its end (results.json says why)
    Failed,      ///< its study threw: no results
  };
  Status status = Status::Failed;
  std::string reason;        ///< results.json "end", or the error's message
  std::string results_json;  ///< the text of its results.json; empty if Failed
};

/// "completed", "ended_early" or "failed".
const char* to_string(SweepPointResult::Status status);

/// Runs one point whose scene is `point_scene` (sweep_point_scene): reads the results of a
/// point already done (its directory holds results.json), resumes one with a record and no
/// results, runs any other from the start. Never throws for a study that fails: that is
/// Status::Failed with the message.
SweepPointResult run_sweep_point(const Scene& point_scene, const StudyProgress& progress = {});

/// Prepares DIR for a sweep of `base` over `parameters` (nothing runs yet): a missing or empty
/// DIR gets sweep_plan.json. Under ExistingOutput::Refuse a DIR that holds anything is refused;
/// under Resume DIR must hold a sweep_plan.json equal to this sweep's (the base scene and the
/// parameters), else std::invalid_argument says what differs; under Overwrite the earlier
/// sweep's plan, summaries and point directories are removed first. Also builds and validates
/// every point's scene first, so that a bad value is refused (std::invalid_argument, naming
/// it) before anything is written.
void open_sweep_directory(const std::string& dir, const Scene& base,
                          const std::vector<SweepParameter>& parameters, ExistingOutput existing);

/// Writes DIR/sweep.json and DIR/sweep.csv, each atomically, from the points and the results
/// known so far (none for a point not yet run). sweep.json: {"parameters": [{"key", "values"}],
/// "points": [{"index", "directory", "params": {KEY: VALUE}, "status", "reason", "results"}]}
/// with VALUE as JSON where it parses (else a string), status "pending" for a point not yet
/// run, results the point's results.json object (null if none). sweep.csv: one row per point
/// with index, directory, the parameters, status, and every scalar key of the results
/// (nested keys joined by '.', e.g. mesh.unknowns; empty where null or absent) that is not
/// also a parameter's key.
void write_sweep_summary(const std::string& dir, const std::vector<SweepParameter>& parameters,
                         const std::vector<SweepPoint>& points,
                         const std::vector<std::optional<SweepPointResult>>& results);

/// What run_parameter_sweep returns: one result per point, in point order.
struct ParameterSweep {
  std::vector<SweepPoint> points;
  std::vector<SweepPointResult> results;
  /// Every point completed.
  bool all_completed() const;
};

/// The whole sweep on one process: open_sweep_directory, then every point in order
/// (run_sweep_point, its log lines to `progress` behind a "# point NNN (settings)" line),
/// rewriting the summaries after each. Throws as open_sweep_directory for bad input.
ParameterSweep run_parameter_sweep(const Scene& base, const std::vector<SweepParameter>& parameters,
                                   const std::string& dir, ExistingOutput existing,
                                   const StudyProgress& progress = {});

/// The shortest text that reads back as v (how a one-key sweep sets a numeric key, and how
/// the series write its values).
std::string sweep_value_text(double v);

/// Throws std::invalid_argument, naming the directory and what to do, if a series (a study
/// that is one sweep over one key: thickness_series, series) may not use `directory` under
/// `existing` (check_output_directory, with DIR/sweep_plan.json the record a resume needs).
void check_key_sweep_directory(const std::string& directory, ExistingOutput existing);

/// What run_key_sweep returns.
struct KeySweep {
  ParameterSweep run;
  double wall_seconds = 0.0;  ///< of the points' runs (those of a resume only, when resumed)
};

/// The sweep of a series study: `base` at each of `values` of the scene key `key`, into DIR.
/// Refuses bad input before anything is removed or written (every point's scene, then
/// check_key_sweep_directory); under Overwrite removes the series' own summaries `own_files`
/// (names in DIR) first, so that none outlives the points it summarised; then
/// run_parameter_sweep.
KeySweep run_key_sweep(const Scene& base, const std::string& key, const std::vector<double>& values,
                       const std::string& dir, ExistingOutput existing,
                       const std::vector<std::string>& own_files,
                       const StudyProgress& progress = {});

}  // namespace growshell
