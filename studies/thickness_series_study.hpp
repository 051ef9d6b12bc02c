#pragma once
/// \file
/// The thickness_series study (the paper's Fig. 2): the cone_branch study of one scene at
/// several thicknesses h (study.thicknesses), and how its key values depend on h: phi_e at the
/// first branch point against the linear threshold c2 h^2 / R^2, and the approach of phi_e^max
/// to its h -> 0 value (study.phi_max_limit) as the power law phi_e^max - L = A h^p.
///
/// DIR is a parameter sweep over `thickness` (studies/parameter_sweep.hpp: sweep_plan.json,
/// point_NNN/, sweep.json, sweep.csv) plus the series' own DIR/results.json and
/// DIR/thickness_series.csv. A killed series resumes as a sweep does: a finished thickness is
/// never traced again, an unfinished one goes on from its last committed state.
/// docs/guide/thickness_series.md is the user's page.

#include <optional>
#include <string>
#include <vector>

#include "libshell/io/scene.hpp"
#include "studies/power_law_fit.hpp"
#include "studies/study_directory.hpp"
#include "studies/study_progress.hpp"

namespace growshell {

/// One thickness of the series: what its cone_branch study's results.json says.
struct ThicknessSeriesPoint {
  double thickness = 0.0;  ///< h (m)
  std::string directory;   ///< its study directory, relative to DIR ("point_000", ...)
  std::string status;      ///< "completed", "ended_early" or "failed"
  std::string end;         ///< why its trace ended, or why it failed
  std::optional<double> phi_branch, phi_max, eb_hat_max;
  std::optional<long long> unknowns;
};

/// The key values of a thickness series. Angles in radians, thicknesses in metres.
struct ThicknessSeriesResults {
  std::vector<ThicknessSeriesPoint> points;  ///< in the order of study.thicknesses
  double radius = 1.0;                       ///< R of the disc (m)
  double phi_max_limit = 2.57;               ///< L of the phi_e^max fit
  /// phi_branch = A h^p (limit 0) over the points that have phi_branch; the linear theory has
  /// p = 2 and A = c2 / R^2.
  std::optional<PowerLawFit> phi_branch_fit;
  /// phi_max - L = A h^p over the completed points that have phi_max.
  std::optional<PowerLawFit> phi_max_fit;
  /// phi_branch R^2 / h^2 of each point with phi_branch: its mean, smallest and largest (c2
  /// of ../shared/docs/physics.md is 10.6020 for nu = 0.3).
  std::optional<double> c2_mean, c2_min, c2_max;
  bool completed = false;  ///< every point completed
  std::string end;         ///< "completed", or which points did not and why
  double wall_seconds = 0.0;
};

/// The series' results from its points (the fits and c2 computed here).
ThicknessSeriesResults summarize_thickness_series(std::vector<ThicknessSeriesPoint> points,
                                                  double radius, double phi_max_limit);

/// DIR/results.json's text: a JSON object with, in this order, study ("thickness_series"),
/// radius, phi_max_limit, points [{thickness, directory, status, end, unknowns, phi_branch,
/// phi_max, eb_hat_max, branch_csv ("point_NNN/branch.csv"), results
/// ("point_NNN/results.json")}], phi_branch_fit and phi_max_fit ({limit, amplitude, exponent,
/// points, max_relative_misfit}, or null), c2 {mean, min, max} (or null), completed, end,
/// wall_seconds. Non-finite and unset values are null.
std::string thickness_series_results_json(const ThicknessSeriesResults& results);

/// DIR/thickness_series.csv's text: a header, then one row per point: thickness, status,
/// unknowns, phi_branch, phi_branch / h^2 (R = 1 units: times R^2), phi_max, eb_hat_max; empty
/// cells where a value is missing.
std::string thickness_series_csv(const ThicknessSeriesResults& results);

/// The cone_branch scene that the series of `scene` traces at each thickness: `scene` with
/// study.kind cone_branch and no study.thicknesses (the sweep's base scene).
Scene thickness_series_base_scene(const Scene& scene);

/// Throws std::invalid_argument, naming the directory and what to do, if the series may not
/// use `directory` under `existing`: a path that is not a directory; a non-empty directory
/// under Refuse; a non-empty directory without sweep_plan.json under Resume.
void check_thickness_series_directory(const std::string& directory, ExistingOutput existing);

/// Runs the series of `scene` (study.kind thickness_series) into scene.output.directory: the
/// sweep over study.thicknesses (each point a cone_branch study, its log lines to `progress`),
/// then DIR/results.json and DIR/thickness_series.csv, each written atomically. Under
/// Overwrite the earlier series' results are removed first, so that none outlives the points
/// it summarised. Validates the scene and the directory before anything is written (throws
/// std::invalid_argument naming the key or what differs from the recorded series); a point
/// that fails is reported in the results, and the others go on.
ThicknessSeriesResults run_thickness_series_study(const Scene& scene, ExistingOutput existing,
                                                  const StudyProgress& progress = {});

}  // namespace growshell
