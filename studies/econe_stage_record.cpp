#include "studies/econe_stage_record.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/content_hash.hpp"
#include "studies/atomic_file.hpp"

namespace growshell {
namespace {

using Json = nlohmann::ordered_json;

constexpr int kFormat = 1;

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json optional_number(const std::optional<double>& v) {
  return v ? number(*v) : Json(nullptr);
}

Json trace_end_json(bool reached_bound, const std::string& message) {
  Json j;
  j["reached_bound"] = reached_bound;
  j["message"] = message;
  return j;
}

Json top_json(const std::optional<EconeTopSample>& top) {
  if (!top) return nullptr;
  Json j;
  j["state"] = top->state;
  j["phi_e"] = number(top->phi_e);
  j["energy"] = number(top->energy);
  return j;
}

Json contact_branches_json(const EconeStageRecord::ContactBranches& b) {
  const EconeBranchResult& t = b.traced;
  Json j;
  j["symmetric"] = trace_end_json(t.symmetric.reached_bound, t.symmetric.message);
  j["skewed_down"] = trace_end_json(t.skewed_down.reached_bound, t.skewed_down.message);
  j["skewed_up"] = trace_end_json(t.skewed_up.reached_bound, t.skewed_up.message);
  j["first_contact"] = t.first_contact ? number(t.first_contact->parameter) : Json(nullptr);
  j["stability_loss"] = t.stability_loss ? number(t.stability_loss->parameter) : Json(nullptr);
  j["skewed_found"] = t.skewed_found;
  j["skewed_message"] = t.skewed_message;
  j["skewed_relaxed_energy"] = number(t.skewed_relaxed_energy);
  j["symmetric_top_energy"] = number(t.symmetric_top_energy);
  j["skew_search_parameter"] = number(t.skew_search_parameter);
  Json crossings = Json::array();
  for (std::size_t i = 0; i < t.crossings.size(); ++i) {
    Json c;
    c["parameter"] = number(t.crossings[i].parameter);
    c["energy"] = number(t.crossings[i].energy);
    c["slope_difference"] = number(t.crossings[i].slope_difference);
    c["error_estimate"] = number(t.crossings[i].error_estimate);
    c["skewed_stable"] = i < t.crossing_skewed_stable.size() && t.crossing_skewed_stable[i];
    crossings.push_back(std::move(c));
  }
  j["crossings"] = std::move(crossings);
  j["skewed_search_seconds"] = number(t.skewed_search_seconds);
  j["ipopt_checked"] = t.ipopt_checked;
  j["ipopt_converged"] = t.ipopt_converged;
  j["ipopt_message"] = t.ipopt_message;
  j["ipopt_energy"] = number(t.ipopt_energy);
  j["penalty_elastic_energy"] = number(t.penalty_elastic_energy);
  j["ipopt_state_difference"] = number(t.ipopt_state_difference);
  j["ipopt_min_distance"] = number(t.ipopt_min_distance);
  j["ipopt_seconds"] = number(t.ipopt_seconds);
  j["max_s4_defect_symmetric"] = optional_number(b.max_s4_defect_symmetric);
  j["top_skewed"] = top_json(b.top_skewed);
  return j;
}

Json turned_json(const EconeStageRecord::Turned& t) {
  Json j;
  j["down"] = trace_end_json(t.down.reached_bound, t.down.message);
  j["up"] = trace_end_json(t.up.reached_bound, t.up.message);
  j["lowest_phi_breaking_s4"] = optional_number(t.lowest_phi_breaking_s4);
  j["top"] = top_json(t.top);
  return j;
}

/// Reads the fields of a stage record, each named by its path in the document on error.
class Reader {
 public:
  explicit Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw std::runtime_error(origin_ + ": " + where + " " + what);
  }
  const Json& member(const Json& object, const std::string& where, const char* key) const {
    if (!object.is_object()) fail(where, "is not an object");
    const auto it = object.find(key);
    if (it == object.end()) fail(where + "." + key, "is missing");
    return *it;
  }
  double number(const Json& object, const std::string& where, const char* key) const {
    const Json& v = member(object, where, key);
    if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!v.is_number()) fail(where + "." + key, "is not a number");
    return v.get<double>();
  }
  std::optional<double> optional_number(const Json& object, const std::string& where,
                                        const char* key) const {
    const Json& v = member(object, where, key);
    if (v.is_null()) return std::nullopt;
    if (!v.is_number()) fail(where + "." + key, "is not a number or null");
    return v.get<double>();
  }
  long long integer(const Json& object, const std::string& where, const char* key) const {
    const Json& v = member(object, where, key);
    if (!v.is_number_integer()) fail(where + "." + key, "is not an integer");
    return v.get<long long>();
  }
  bool boolean(const Json& object, const std::string& where, const char* key) const {
    const Json& v = member(object, where, key);
    if (!v.is_boolean()) fail(where + "." + key, "is not true or false");
    return v.get<bool>();
  }
  std::string text(const Json& object, const std::string& where, const char* key) const {
    const Json& v = member(object, where, key);
    if (!v.is_string()) fail(where + "." + key, "is not a string");
    return v.get<std::string>();
  }

  EconeTraceEnd trace_end(const Json& object, const std::string& where, const char* key) const {
    const Json& j = member(object, where, key);
    const std::string at = where + "." + key;
    return {boolean(j, at, "reached_bound"), text(j, at, "message")};
  }
  std::optional<EconeTopSample> top(const Json& object, const std::string& where,
                                    const char* key) const {
    const Json& j = member(object, where, key);
    if (j.is_null()) return std::nullopt;
    const std::string at = where + "." + key;
    return EconeTopSample{text(j, at, "state"), number(j, at, "phi_e"), number(j, at, "energy")};
  }
  HardContactCheck check(const Json& j, const std::string& at) const {
    HardContactCheck c;
    c.phi_e = number(j, at, "phi_e");
    c.unknowns = static_cast<Eigen::Index>(integer(j, at, "unknowns"));
    c.converged = boolean(j, at, "converged");
    c.message = text(j, at, "message");
    c.seconds = number(j, at, "seconds");
    c.rounds = static_cast<int>(integer(j, at, "rounds"));
    c.iterations = static_cast<int>(integer(j, at, "iterations"));
    c.penalty_elastic_energy = number(j, at, "penalty_elastic_energy");
    c.hard_elastic_energy = number(j, at, "hard_elastic_energy");
    c.relative_energy_difference = number(j, at, "relative_energy_difference");
    c.state_difference_over_h = number(j, at, "state_difference_over_h");
    c.penalty_min_distance_over_h = number(j, at, "penalty_min_distance_over_h");
    c.hard_min_distance_over_h = number(j, at, "hard_min_distance_over_h");
    c.penalty_s4_defect = number(j, at, "penalty_s4_defect");
    c.hard_s4_defect = number(j, at, "hard_s4_defect");
    c.penalty_gamma = number(j, at, "penalty_gamma");
    c.hard_gamma = number(j, at, "hard_gamma");
    return c;
  }

  EconeStageRecord::ContactBranches contact_branches(const Json& j) const {
    const std::string at = "contact_branches";
    EconeStageRecord::ContactBranches b;
    EconeBranchResult& t = b.traced;
    const auto set_end = [](ContactBranchTrace& trace, const EconeTraceEnd& end) {
      trace.reached_bound = end.reached_bound;
      trace.message = end.message;
    };
    set_end(t.symmetric, trace_end(j, at, "symmetric"));
    set_end(t.skewed_down, trace_end(j, at, "skewed_down"));
    set_end(t.skewed_up, trace_end(j, at, "skewed_up"));
    if (const auto phi = optional_number(j, at, "first_contact")) {
      t.first_contact = LocatedEvent{};
      t.first_contact->parameter = *phi;
    }
    if (const auto phi = optional_number(j, at, "stability_loss")) {
      t.stability_loss = SpecialPoint{};
      t.stability_loss->parameter = *phi;
    }
    t.skewed_found = boolean(j, at, "skewed_found");
    t.skewed_message = text(j, at, "skewed_message");
    t.skewed_relaxed_energy = number(j, at, "skewed_relaxed_energy");
    t.symmetric_top_energy = number(j, at, "symmetric_top_energy");
    t.skew_search_parameter = number(j, at, "skew_search_parameter");
    const Json& crossings = member(j, at, "crossings");
    if (!crossings.is_array()) fail(at + ".crossings", "is not an array");
    for (std::size_t i = 0; i < crossings.size(); ++i) {
      const std::string ci = at + ".crossings[" + std::to_string(i) + "]";
      EnergyCrossing c{};
      c.parameter = number(crossings[i], ci, "parameter");
      c.energy = number(crossings[i], ci, "energy");
      c.slope_difference = number(crossings[i], ci, "slope_difference");
      c.error_estimate = number(crossings[i], ci, "error_estimate");
      t.crossings.push_back(c);
      t.crossing_skewed_stable.push_back(boolean(crossings[i], ci, "skewed_stable"));
    }
    t.skewed_search_seconds = number(j, at, "skewed_search_seconds");
    t.ipopt_checked = boolean(j, at, "ipopt_checked");
    t.ipopt_converged = boolean(j, at, "ipopt_converged");
    t.ipopt_message = text(j, at, "ipopt_message");
    t.ipopt_energy = number(j, at, "ipopt_energy");
    t.penalty_elastic_energy = number(j, at, "penalty_elastic_energy");
    t.ipopt_state_difference = number(j, at, "ipopt_state_difference");
    t.ipopt_min_distance = number(j, at, "ipopt_min_distance");
    t.ipopt_seconds = number(j, at, "ipopt_seconds");
    b.max_s4_defect_symmetric = optional_number(j, at, "max_s4_defect_symmetric");
    b.top_skewed = top(j, at, "top_skewed");
    return b;
  }

  EconeStageRecord::Turned turned(const Json& j) const {
    const std::string at = "turned";
    EconeStageRecord::Turned t;
    t.down = trace_end(j, at, "down");
    t.up = trace_end(j, at, "up");
    t.lowest_phi_breaking_s4 = optional_number(j, at, "lowest_phi_breaking_s4");
    t.top = top(j, at, "top");
    return t;
  }

 private:
  std::string origin_;
};

}  // namespace

const HardContactCheck* EconeStageRecord::hard_contact_at(const std::string& branch,
                                                          double at) const {
  for (const HardContactPoint& p : hard_contact)
    if (p.branch == branch && p.at == at) return &p.check;
  return nullptr;
}

std::uint64_t econe_stage_key(const Scene& scene, const BranchSample& start) {
  Scene stages = scene;
  stages.output = default_scene().output;
  stages.study.compare_modes.clear();
  stages.study.wind_to.reset();
  stages.study.wind_shapes_at.clear();
  stages.study.hard_contact_at.clear();
  stages.study.hard_contact_branches = default_scene().study.hard_contact_branches;
  std::string bytes = scene_to_json(stages);
  const auto append = [&bytes](const void* data, std::size_t size) {
    bytes.append(static_cast<const char*>(data), size);
  };
  append(&start.parameter, sizeof start.parameter);
  append(start.x.data(), sizeof(double) * static_cast<std::size_t>(start.x.size()));
  return fnv1a_64(bytes);
}

std::string econe_stage_record_json(const EconeStageRecord& record) {
  Json j;
  j["format"] = kFormat;
  char key[17];
  std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(record.key));
  j["key"] = key;
  j["contact_branches"] =
      record.contact_branches ? contact_branches_json(*record.contact_branches) : Json(nullptr);
  j["turned"] = record.turned ? turned_json(*record.turned) : Json(nullptr);
  Json points = Json::array();
  for (const EconeStageRecord::HardContactPoint& p : record.hard_contact) {
    Json e;
    e["branch"] = p.branch;
    e["at"] = number(p.at);
    e["check"] = Json::parse(hard_contact_check_json(p.check));
    points.push_back(std::move(e));
  }
  j["hard_contact"] = std::move(points);
  return j.dump(2) + "\n";
}

EconeStageRecord parse_econe_stage_record(const std::string& text, const std::string& origin) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(origin + ": not JSON (" + e.what() + ")");
  }
  const Reader read(origin);
  if (read.integer(j, "the record", "format") != kFormat)
    read.fail("format", "is " + j["format"].dump() + ", not " + std::to_string(kFormat));
  EconeStageRecord record;
  const std::string key = read.text(j, "the record", "key");
  std::size_t used = 0;
  try {
    record.key = std::stoull(key, &used, 16);
  } catch (const std::exception&) {
    used = 0;
  }
  if (key.size() != 16 || used != key.size())
    read.fail("key", "'" + key + "' is not 16 hexadecimal digits");
  if (const Json& b = read.member(j, "the record", "contact_branches"); !b.is_null())
    record.contact_branches = read.contact_branches(b);
  if (const Json& t = read.member(j, "the record", "turned"); !t.is_null())
    record.turned = read.turned(t);
  const Json& points = read.member(j, "the record", "hard_contact");
  if (!points.is_array()) read.fail("hard_contact", "is not an array");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::string at = "hard_contact[" + std::to_string(i) + "]";
    EconeStageRecord::HardContactPoint p;
    p.branch = read.text(points[i], at, "branch");
    p.at = read.number(points[i], at, "at");
    p.check = read.check(read.member(points[i], at, "check"), at + ".check");
    record.hard_contact.push_back(std::move(p));
  }
  return record;
}

std::optional<EconeStageRecord> read_econe_stage_record(const std::string& path) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw std::runtime_error("cannot read the stage record " + path);
  return parse_econe_stage_record(text.str(), "the stage record " + path);
}

void write_econe_stage_record(const std::string& path, const EconeStageRecord& record) {
  write_file_atomically(path, econe_stage_record_json(record));
}

}  // namespace growshell
