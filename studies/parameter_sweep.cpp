#include "studies/parameter_sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"
#include "studies/scene_study.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string settings_text(const SweepPoint& point) {
  std::string out;
  for (const auto& [key, value] : point.settings) out += (out.empty() ? "" : ", ") + key + "=" + value;
  return out;
}

/// A value as JSON where it parses as JSON, else as a string.
Json value_json(const std::string& value) {
  Json parsed = Json::parse(value, nullptr, false);
  return parsed.is_discarded() ? Json(value) : parsed;
}

/// The parameters as sweep_plan.json and sweep.json record them: [{"key", "values"}].
Json parameters_json(const std::vector<SweepParameter>& parameters) {
  Json out = Json::array();
  for (const SweepParameter& p : parameters) out.push_back({{"key", p.key}, {"values", p.values}});
  return out;
}

/// The plan a resumed sweep must match: the base scene (output directory = the sweep's) and
/// the parameters.
Json sweep_plan(const std::string& dir, const Scene& base,
                const std::vector<SweepParameter>& parameters) {
  Scene scene = base;
  scene.output.directory = dir;
  Json plan;
  plan["base_scene"] = Json::parse(scene_to_json(scene));
  plan["parameters"] = parameters_json(parameters);
  return plan;
}

/// Nested scalar keys of a results object, joined by '.', in their order.
void flatten(const Json& object, const std::string& prefix, std::vector<std::string>& keys,
             std::map<std::string, std::string>& values) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object()) {
      flatten(*it, key, keys, values);
      continue;
    }
    if (it->is_array()) continue;
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    if (it->is_null()) values[key] = "";
    else if (it->is_string()) values[key] = it->get<std::string>();
    else values[key] = it->dump();
  }
}

/// A CSV field, quoted where it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

SweepParameter parse_sweep_parameter(const std::string& text) {
  const auto fail = [&](const std::string& why) {
    throw std::invalid_argument("sweep parameter '" + text + "': " + why +
                                " (give KEY=V1,V2,..., e.g. thickness=0.04,0.02)");
  };
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) fail("no '='");
  SweepParameter p;
  p.key = text.substr(0, eq);
  if (p.key.empty()) fail("no key before '='");
  int depth = 0;
  std::string value;
  for (std::size_t i = eq + 1; i <= text.size(); ++i) {
    const char c = i < text.size() ? text[i] : ',';
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (c == ',' && depth <= 0) {
      if (value.empty()) fail("an empty value");
      p.values.push_back(value);
      value.clear();
    } else {
      value += c;
    }
  }
  return p;
}

const char* to_string(SweepPointResult::Status status) {
  switch (status) {
    case SweepPointResult::Status::Completed: return "completed";
    case SweepPointResult::Status::EndedEarly: return "ended_early";
    case SweepPointResult::Status::Failed: return "failed";
  }
  return "failed";
}

std::vector<SweepPoint> sweep_points(const std::vector<SweepParameter>& parameters) {
  if (parameters.empty()) throw std::invalid_argument("a sweep needs at least one parameter");
  std::set<std::string> keys;
  std::size_t count = 1;
  for (const SweepParameter& p : parameters) {
    if (!keys.insert(p.key).second)
      throw std::invalid_argument("sweep parameter " + p.key + " is given twice");
    if (p.values.empty()) throw std::invalid_argument("sweep parameter " + p.key + " has no value");
    count *= p.values.size();
    if (count > 10000)
      throw std::invalid_argument("the sweep has more than 10000 points");
  }
  std::vector<SweepPoint> points(count);
  for (std::size_t i = 0; i < count; ++i) {
    SweepPoint& point = points[i];
    point.index = static_cast<int>(i);
    std::size_t rest = i, stride = count;
    for (const SweepParameter& p : parameters) {
      stride /= p.values.size();
      point.settings.emplace_back(p.key, p.values[rest / stride]);
      rest %= stride;
    }
    char name[32];
    std::snprintf(name, sizeof name, "point_%03d", point.index);
    point.directory = name;
  }
  return points;
}

Scene sweep_point_scene(const Scene& base, const SweepPoint& point, const std::string& sweep_dir) {
  if (base.study.kind == StudyKind::ThicknessSeries)
    throw std::invalid_argument(
        "a thickness_series scene cannot be swept: it is itself a sweep over thickness; sweep "
        "the cone_branch study (study.kind = \"cone_branch\") instead");
  if (base.study.kind == StudyKind::Series)
    throw std::invalid_argument(
        "a series scene cannot be swept: it is itself a sweep over study.series_key; sweep the "
        "study it runs (study.kind = study.series_of) instead");
  Scene scene = base;
  try {
    for (const auto& [key, value] : point.settings) apply_override(scene, key, value);
    scene.output.directory = (fs::path(sweep_dir) / point.directory).string();
    validate_scene(scene);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("sweep point " + point.directory + " (" + settings_text(point) +
                                "): " + e.what());
  }
  return scene;
}

SweepPointResult run_sweep_point(const Scene& point_scene, const StudyProgress& progress) {
  SweepPointResult out;
  const std::string& dir = point_scene.output.directory;
  const std::string results = dir + "/results.json";
  try {
    if (!fs::exists(results)) {
      // A run that has begun (its record exists, e.g. cone/record.json of econe_contact)
      // goes on from its last committed state; anything else starts afresh.
      const bool recorded = fs::exists(dir + "/" + scene_study_record_file(point_scene));
      run_scene_study(point_scene, recorded ? ExistingOutput::Resume : ExistingOutput::Overwrite,
                      progress);
    }
    out.results_json = read_text(results);
    const Json r = Json::parse(out.results_json);
    out.status = r.value("completed", false) ? SweepPointResult::Status::Completed
                                             : SweepPointResult::Status::EndedEarly;
    out.reason = r.value("end", std::string());
  } catch (const std::exception& e) {
    out = SweepPointResult{};
    out.reason = e.what();
  }
  return out;
}

void open_sweep_directory(const std::string& dir, const Scene& base,
                          const std::vector<SweepParameter>& parameters, ExistingOutput existing) {
  const std::vector<SweepPoint> points = sweep_points(parameters);
  for (const SweepPoint& point : points) sweep_point_scene(base, point, dir);
  const Json plan = sweep_plan(dir, base, parameters);
  const std::string plan_file = dir + "/sweep_plan.json";
  std::error_code ec;
  if (fs::exists(dir) && !fs::is_directory(dir))
    throw std::invalid_argument("sweep directory " + dir + " exists and is not a directory");
  const bool empty = !fs::exists(dir) || fs::is_empty(dir, ec);
  if (!empty) {
    switch (existing) {
      case ExistingOutput::Refuse:
        throw std::invalid_argument("sweep directory " + dir +
                                    " is not empty: give --resume to go on with the sweep "
                                    "recorded there, or --overwrite to replace it");
      case ExistingOutput::Resume: {
        if (!fs::exists(plan_file))
          throw std::invalid_argument("sweep directory " + dir +
                                      " holds no sweep_plan.json: nothing to resume");
        const Json recorded = Json::parse(read_text(plan_file), nullptr, false);
        if (recorded.is_discarded())
          throw std::invalid_argument(plan_file + " is not valid JSON");
        if (recorded["parameters"] != plan["parameters"])
          throw std::invalid_argument("--resume: the parameters differ from those of " +
                                      plan_file + " (" + recorded["parameters"].dump() + ")");
        // Read through the scene reader, so that a key added since the plan was written
        // compares as its default (the value the recorded sweep ran with).
        // output.directory is where the sweep was started from, spelled as it was given
        // ("out/s" or its absolute path): it does not define the sweep (each point has its own
        // directory below DIR), so it is not compared.
        Json recorded_scene = Json::parse(scene_to_json(
            parse_scene(recorded["base_scene"].dump(), plan_file + ", base_scene")));
        Json wanted_scene = plan["base_scene"];
        recorded_scene["output"].erase("directory");
        wanted_scene["output"].erase("directory");
        if (recorded_scene != wanted_scene) {
          const Json diff = Json::diff(recorded_scene, wanted_scene);
          throw std::invalid_argument("--resume: the base scene differs from that of " +
                                      plan_file + " at " +
                                      diff.at(0).value("path", std::string("?")));
        }
        return;
      }
      case ExistingOutput::Overwrite:
        for (const auto& entry : fs::directory_iterator(dir)) {
          const std::string name = entry.path().filename().string();
          if (name.rfind("point_", 0) == 0 || name == "sweep.json" || name == "sweep.csv" ||
              name == "sweep_plan.json")
            fs::remove_all(entry.path());
        }
        break;
    }
  }
  fs::create_directories(dir);
  write_file_atomically(plan_file, plan.dump(2) + "\n");
}

void write_sweep_summary(const std::string& dir, const std::vector<SweepParameter>& parameters,
                         const std::vector<SweepPoint>& points,
                         const std::vector<std::optional<SweepPointResult>>& results) {
  Json summary;
  summary["parameters"] = parameters_json(parameters);
  summary["points"] = Json::array();
  std::vector<std::string> result_keys;
  std::vector<std::map<std::string, std::string>> flat(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SweepPoint& point = points[i];
    Json entry;
    entry["index"] = point.index;
    entry["directory"] = point.directory;
    Json params = Json::object();
    for (const auto& [key, value] : point.settings) params[key] = value_json(value);
    entry["params"] = params;
    const std::optional<SweepPointResult>& r = i < results.size() ? results[i] : std::nullopt;
    entry["status"] = r ? to_string(r->status) : "pending";
    entry["reason"] = r ? Json(r->reason) : Json(nullptr);
    entry["results"] = nullptr;
    if (r && !r->results_json.empty()) {
      const Json parsed = Json::parse(r->results_json, nullptr, false);
      if (!parsed.is_discarded()) {
        entry["results"] = parsed;
        flatten(parsed, "", result_keys, flat[i]);
      }
    }
    summary["points"].push_back(entry);
  }
  write_file_atomically(dir + "/sweep.json", summary.dump(2) + "\n");

  std::ostringstream csv;
  csv << "index,directory";
  for (const SweepParameter& p : parameters) csv << "," << csv_field(p.key);
  csv << ",status";
  // A result key that is also a parameter (e.g. thickness) has the parameter's column.
  std::vector<std::string> columns;
  for (const std::string& key : result_keys) {
    bool swept = false;
    for (const SweepParameter& p : parameters) swept = swept || p.key == key;
    if (!swept) columns.push_back(key);
  }
  for (const std::string& key : columns) csv << "," << csv_field(key);
  csv << "\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::optional<SweepPointResult>& r = i < results.size() ? results[i] : std::nullopt;
    csv << points[i].index << "," << points[i].directory;
    for (const auto& setting : points[i].settings) csv << "," << csv_field(setting.second);
    csv << "," << (r ? to_string(r->status) : "pending");
    for (const std::string& key : columns) {
      const auto it = flat[i].find(key);
      csv << "," << (it == flat[i].end() ? "" : csv_field(it->second));
    }
    csv << "\n";
  }
  write_file_atomically(dir + "/sweep.csv", csv.str());
}

bool ParameterSweep::all_completed() const {
  for (const SweepPointResult& r : results)
    if (r.status != SweepPointResult::Status::Completed) return false;
  return results.size() == points.size();
}

ParameterSweep run_parameter_sweep(const Scene& base, const std::vector<SweepParameter>& parameters,
                                   const std::string& dir, ExistingOutput existing,
                                   const StudyProgress& progress) {
  open_sweep_directory(dir, base, parameters, existing);
  ParameterSweep sweep;
  sweep.points = sweep_points(parameters);
  std::vector<std::optional<SweepPointResult>> known(sweep.points.size());
  write_sweep_summary(dir, parameters, sweep.points, known);
  for (const SweepPoint& point : sweep.points) {
    if (progress) progress("# point " + point.directory + " (" + settings_text(point) + ")");
    const SweepPointResult r = run_sweep_point(sweep_point_scene(base, point, dir), progress);
    if (progress)
      progress("# point " + point.directory + ": " + to_string(r.status) +
               (r.reason.empty() ? "" : " (" + r.reason + ")"));
    known[static_cast<std::size_t>(point.index)] = r;
    sweep.results.push_back(r);
    write_sweep_summary(dir, parameters, sweep.points, known);
  }
  return sweep;
}

std::string sweep_value_text(double v) { return Json(v).dump(); }

void check_key_sweep_directory(const std::string& directory, ExistingOutput existing) {
  check_output_directory(directory, existing, "series", "sweep_plan.json");
}

KeySweep run_key_sweep(const Scene& base, const std::string& key, const std::vector<double>& values,
                       const std::string& dir, ExistingOutput existing,
                       const std::vector<std::string>& own_files,
                       const StudyProgress& progress) {
  SweepParameter parameter{key, {}};
  for (double v : values) parameter.values.push_back(sweep_value_text(v));
  const std::vector<SweepParameter> parameters = {parameter};
  // Bad input is refused before anything is removed or written: every point's scene, then
  // the directory.
  for (const SweepPoint& point : sweep_points(parameters)) sweep_point_scene(base, point, dir);
  check_key_sweep_directory(dir, existing);
  if (existing == ExistingOutput::Overwrite) {
    std::error_code ec;
    for (const std::string& name : own_files) fs::remove(fs::path(dir) / name, ec);
  }
  const auto started = std::chrono::steady_clock::now();
  KeySweep out;
  out.run = run_parameter_sweep(base, parameters, dir, existing, progress);
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace growshell
