#include "studies/series_study.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"
#include "studies/parameter_sweep.hpp"

namespace growshell {
namespace {

using Json = nlohmann::ordered_json;

Json number_or_null(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? Json(*v) : Json(nullptr);
}

SeriesPoint series_point(double value, const std::vector<std::string>& report,
                         const SweepPoint& point, const SweepPointResult& result) {
  SeriesPoint p;
  p.value = value;
  p.directory = point.directory;
  p.status = to_string(result.status);
  p.end = result.reason;
  p.reported.assign(report.size(), std::nullopt);
  if (result.results_json.empty()) return p;
  const Json r = Json::parse(result.results_json, nullptr, false);
  if (r.is_discarded() || !r.is_object()) return p;
  for (std::size_t i = 0; i < report.size(); ++i)
    if (r.contains(report[i]) && r[report[i]].is_number()) p.reported[i] = r[report[i]].get<double>();
  if (r.contains("mesh") && r["mesh"].is_object() && r["mesh"].contains("unknowns") &&
      r["mesh"]["unknowns"].is_number_integer())
    p.unknowns = r["mesh"]["unknowns"].get<long long>();
  return p;
}

}  // namespace

std::string series_results_json(const SeriesResults& r) {
  Json j;
  j["study"] = "series";
  j["of"] = r.of;
  j["key"] = r.key;
  j["report"] = r.report;
  Json points = Json::array();
  for (const SeriesPoint& p : r.points) {
    Json point = {{"value", p.value},
                  {"directory", p.directory},
                  {"status", p.status},
                  {"end", p.end},
                  {"unknowns", p.unknowns ? Json(*p.unknowns) : Json(nullptr)}};
    for (std::size_t i = 0; i < r.report.size() && i < p.reported.size(); ++i)
      point[r.report[i]] = number_or_null(p.reported[i]);
    point["results"] = p.directory + "/results.json";
    points.push_back(point);
  }
  j["points"] = points;
  j["completed"] = r.completed;
  j["end"] = r.end;
  j["wall_seconds"] = number_or_null(r.wall_seconds);
  return j.dump(2) + "\n";
}

std::string series_csv(const SeriesResults& r) {
  std::ostringstream csv;
  csv << r.key << ",status,unknowns";
  for (const std::string& k : r.report) csv << ',' << k;
  csv << '\n';
  for (const SeriesPoint& p : r.points) {
    csv << sweep_value_text(p.value) << ',' << p.status << ',';
    if (p.unknowns) csv << *p.unknowns;
    for (std::size_t i = 0; i < r.report.size(); ++i) {
      csv << ',';
      if (i < p.reported.size() && p.reported[i] && std::isfinite(*p.reported[i]))
        csv << sweep_value_text(*p.reported[i]);
    }
    csv << '\n';
  }
  return csv.str();
}

Scene series_base_scene(const Scene& scene) {
  Scene base = scene;
  base.study.kind = scene.study.series_of;
  base.study.series_key.clear();
  base.study.series_values.clear();
  base.study.series_of = StudyKind::ConeBranch;
  base.study.series_report.clear();
  return base;
}

SeriesResults run_series_study(const Scene& scene, ExistingOutput existing,
                               const StudyProgress& progress) {
  validate_scene(scene);
  if (scene.study.kind != StudyKind::Series)
    throw std::invalid_argument("run_series_study: the scene's study.kind is " +
                                study_kind_name(scene.study.kind) + ", not series");
  const std::string& dir = scene.output.directory;
  const KeySweep sweep =
      run_key_sweep(series_base_scene(scene), scene.study.series_key, scene.study.series_values,
                    dir, existing, {"results.json", "series.csv", "series.png"}, progress);
  const ParameterSweep& run = sweep.run;
  SeriesResults results;
  results.key = scene.study.series_key;
  results.of = study_kind_name(scene.study.series_of);
  results.report = scene.study.series_report;
  std::string unfinished;
  for (std::size_t i = 0; i < run.points.size(); ++i) {
    results.points.push_back(series_point(scene.study.series_values[i], results.report,
                                          run.points[i], run.results[i]));
    const SeriesPoint& p = results.points.back();
    if (p.status != "completed")
      unfinished += (unfinished.empty() ? "" : "; ") + results.key + " = " +
                    sweep_value_text(p.value) + " " + p.status +
                    (p.end.empty() ? "" : " (" + p.end + ")");
  }
  results.completed = !results.points.empty() && unfinished.empty();
  results.end = results.completed ? "completed" : unfinished;
  results.wall_seconds = sweep.wall_seconds;
  write_file_atomically(dir + "/series.csv", series_csv(results));
  write_file_atomically(dir + "/results.json", series_results_json(results));
  if (progress) progress("# wrote " + dir + "/results.json and series.csv: " + results.end);
  return results;
}

}  // namespace growshell
