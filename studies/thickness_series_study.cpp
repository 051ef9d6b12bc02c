#include "studies/thickness_series_study.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"
#include "studies/json_number.hpp"
#include "studies/parameter_sweep.hpp"

namespace growshell {
namespace {

using Json = nlohmann::ordered_json;

Json fit_json(const std::optional<PowerLawFit>& fit) {
  if (!fit) return nullptr;
  return {{"limit", fit->limit},
          {"amplitude", json_number_or_null(fit->amplitude)},
          {"exponent", json_number_or_null(fit->exponent)},
          {"points", fit->points},
          {"max_relative_misfit", json_number_or_null(fit->max_relative_misfit)}};
}

std::optional<double> number_at(const Json& results, const char* key) {
  if (!results.contains(key) || !results[key].is_number()) return std::nullopt;
  return results[key].get<double>();
}

/// A sweep point's outcome as a point of the series.
ThicknessSeriesPoint series_point(double thickness, const SweepPoint& point,
                                  const SweepPointResult& result) {
  ThicknessSeriesPoint p;
  p.thickness = thickness;
  p.directory = point.directory;
  p.status = to_string(result.status);
  p.end = result.reason;
  if (result.results_json.empty()) return p;
  const Json r = Json::parse(result.results_json, nullptr, false);
  if (r.is_discarded() || !r.is_object()) return p;
  p.phi_branch = number_at(r, "phi_branch");
  p.phi_max = number_at(r, "phi_max");
  p.eb_hat_max = number_at(r, "eb_hat_max");
  if (r.contains("mesh") && r["mesh"].contains("unknowns") && r["mesh"]["unknowns"].is_number_integer())
    p.unknowns = r["mesh"]["unknowns"].get<long long>();
  return p;
}

}  // namespace

ThicknessSeriesResults summarize_thickness_series(std::vector<ThicknessSeriesPoint> points,
                                                  double radius, double phi_max_limit) {
  ThicknessSeriesResults s;
  s.radius = radius;
  s.phi_max_limit = phi_max_limit;
  std::vector<double> h_branch, phi_branch, h_max, phi_max;
  double c2_sum = 0.0;
  std::string unfinished;
  for (const ThicknessSeriesPoint& p : points) {
    if (p.phi_branch && std::isfinite(*p.phi_branch)) {
      h_branch.push_back(p.thickness);
      phi_branch.push_back(*p.phi_branch);
      const double c2 = *p.phi_branch * radius * radius / (p.thickness * p.thickness);
      s.c2_min = s.c2_min ? std::min(*s.c2_min, c2) : c2;
      s.c2_max = s.c2_max ? std::max(*s.c2_max, c2) : c2;
      c2_sum += c2;
    }
    if (p.status == "completed" && p.phi_max && std::isfinite(*p.phi_max)) {
      h_max.push_back(p.thickness);
      phi_max.push_back(*p.phi_max);
    }
    if (p.status != "completed") {
      std::ostringstream text;
      text << (unfinished.empty() ? "" : "; ") << "h = " << sweep_value_text(p.thickness) << " "
           << p.status << (p.end.empty() ? "" : " (" + p.end + ")");
      unfinished += text.str();
    }
  }
  if (!h_branch.empty()) s.c2_mean = c2_sum / static_cast<double>(h_branch.size());
  s.phi_branch_fit = fit_power_law(h_branch, phi_branch, 0.0);
  s.phi_max_fit = fit_power_law(h_max, phi_max, phi_max_limit);
  s.completed = !points.empty() && unfinished.empty();
  s.end = s.completed ? "completed" : unfinished;
  s.points = std::move(points);
  return s;
}

std::string thickness_series_results_json(const ThicknessSeriesResults& r) {
  Json j;
  j["study"] = "thickness_series";
  j["radius"] = r.radius;
  j["phi_max_limit"] = r.phi_max_limit;
  Json points = Json::array();
  for (const ThicknessSeriesPoint& p : r.points)
    points.push_back({{"thickness", p.thickness},
                      {"directory", p.directory},
                      {"status", p.status},
                      {"end", p.end},
                      {"unknowns", p.unknowns ? Json(*p.unknowns) : Json(nullptr)},
                      {"phi_branch", json_number_or_null(p.phi_branch)},
                      {"phi_max", json_number_or_null(p.phi_max)},
                      {"eb_hat_max", json_number_or_null(p.eb_hat_max)},
                      {"branch_csv", p.directory + "/branch.csv"},
                      {"results", p.directory + "/results.json"}});
  j["points"] = points;
  j["phi_branch_fit"] = fit_json(r.phi_branch_fit);
  j["phi_max_fit"] = fit_json(r.phi_max_fit);
  j["c2"] = r.c2_mean ? Json{{"mean", *r.c2_mean}, {"min", *r.c2_min}, {"max", *r.c2_max}}
                      : Json(nullptr);
  j["completed"] = r.completed;
  j["end"] = r.end;
  j["wall_seconds"] = json_number_or_null(r.wall_seconds);
  return j.dump(2) + "\n";
}

std::string thickness_series_csv(const ThicknessSeriesResults& r) {
  std::ostringstream csv;  // numbers in their shortest round-trip form
  csv << "thickness,status,unknowns,phi_branch,phi_branch_r2_over_h2,phi_max,eb_hat_max\n";
  const auto cell = [&](const std::optional<double>& v) {
    if (v && std::isfinite(*v)) csv << sweep_value_text(*v);
  };
  for (const ThicknessSeriesPoint& p : r.points) {
    csv << sweep_value_text(p.thickness) << ',' << p.status << ',';
    if (p.unknowns) csv << *p.unknowns;
    csv << ',';
    cell(p.phi_branch);
    csv << ',';
    if (p.phi_branch) cell(*p.phi_branch * r.radius * r.radius / (p.thickness * p.thickness));
    csv << ',';
    cell(p.phi_max);
    csv << ',';
    cell(p.eb_hat_max);
    csv << '\n';
  }
  return csv.str();
}

Scene thickness_series_base_scene(const Scene& scene) {
  Scene base = scene;
  base.study.kind = StudyKind::ConeBranch;
  base.study.thicknesses.clear();
  return base;
}

void check_thickness_series_directory(const std::string& directory, ExistingOutput existing) {
  check_key_sweep_directory(directory, existing);
}

ThicknessSeriesResults run_thickness_series_study(const Scene& scene, ExistingOutput existing,
                                                  const StudyProgress& progress) {
  validate_scene(scene);
  if (scene.study.kind != StudyKind::ThicknessSeries)
    throw std::invalid_argument("run_thickness_series_study: the scene's study.kind is " +
                                study_kind_name(scene.study.kind) + ", not thickness_series");
  const std::string& dir = scene.output.directory;
  const KeySweep sweep = run_key_sweep(
      thickness_series_base_scene(scene), "thickness", scene.study.thicknesses, dir, existing,
      {"results.json", "thickness_series.csv", "thickness_series.png"}, progress);
  const ParameterSweep& run = sweep.run;
  std::vector<ThicknessSeriesPoint> points;
  for (std::size_t i = 0; i < run.points.size(); ++i)
    points.push_back(series_point(scene.study.thicknesses[i], run.points[i], run.results[i]));
  ThicknessSeriesResults results =
      summarize_thickness_series(std::move(points), scene.geometry.radius, scene.study.phi_max_limit);
  results.wall_seconds = sweep.wall_seconds;
  write_file_atomically(dir + "/thickness_series.csv", thickness_series_csv(results));
  write_file_atomically(dir + "/results.json", thickness_series_results_json(results));
  if (progress) progress("# wrote " + dir + "/results.json and thickness_series.csv: " + results.end);
  return results;
}

}  // namespace growshell
