#include "studies/branch_record.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"
#include "studies/saved_state.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

const char* const kRecordFile = BranchRecord::kRecordFileName;
const char* const kBranchFile = "branch.csv";
const char* const kEventsFile = "events.json";
const char* const kCollectionFile = "branch.pvd";

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string join(const std::vector<std::string>& items, const char* separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

std::vector<double> parse_row(const std::string& line, std::size_t columns,
                              const std::string& where) {
  std::vector<double> values;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) {
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (field.empty() || *end != '\0')
      throw std::runtime_error(where + ": '" + field + "' is not a number");
    values.push_back(v);
  }
  if (values.size() != columns)
    throw std::runtime_error(where + " has " + std::to_string(values.size()) +
                             " fields, the header " + std::to_string(columns));
  return values;
}

/// The objects of an events.json as written by rewrite_events: one per line.
std::vector<std::string> read_event_lines(const std::string& path) {
  std::vector<std::string> entries;
  for (std::string line : read_lines(path)) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] != '{') continue;
    line = line.substr(first);
    while (!line.empty() && (line.back() == ',' || line.back() == ' ')) line.pop_back();
    entries.push_back(line);
  }
  return entries;
}

/// Kind and phi_e of an event line written by a study ({"kind": "...", "phi_e": ..., ...}).
RecordedEvent summary_of_line(const std::string& line) {
  RecordedEvent e;
  const std::string kind_key = "\"kind\": \"", phi_key = "\"phi_e\": ";
  const std::size_t k = line.find(kind_key);
  if (k != std::string::npos) {
    const std::size_t begin = k + kind_key.size();
    e.kind = line.substr(begin, line.find('"', begin) - begin);
  }
  const std::size_t p = line.find(phi_key);
  e.phi_e = p == std::string::npos ? std::nan("")
                                   : std::strtod(line.c_str() + p + phi_key.size(), nullptr);
  return e;
}

Json event_to_json(const RecordedEvent& e) {
  Json j;
  j["kind"] = e.kind;
  j["phi_e"] = e.phi_e;
  j["branch"] = e.branch;
  Json values = Json::object();
  for (const auto& [name, v] : e.values) values[name] = std::isfinite(v) ? Json(v) : Json(nullptr);
  j["values"] = values;
  return j;
}

RecordedEvent event_from_json(const Json& j) {
  RecordedEvent e;
  e.kind = j.at("kind").get<std::string>();
  e.phi_e = j.at("phi_e").is_number() ? j.at("phi_e").get<double>() : std::nan("");
  e.branch = j.at("branch").get<std::string>();
  for (const auto& item : j.at("values").items())
    e.values.emplace_back(item.key(),
                          item.value().is_number() ? item.value().get<double>() : std::nan(""));
  return e;
}

/// A file name the record wrote itself (no directory part), so that removing it stays inside DIR.
bool plain_file_name(const std::string& name) {
  return !name.empty() && name.find('/') == std::string::npos && name != "." && name != "..";
}

void remove_temporaries(const std::string& directory) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) return;
  for (const auto& entry : fs::directory_iterator(directory))
    if (is_temporary_file_name(entry.path().filename().string())) fs::remove(entry.path());
}

}  // namespace

std::string special_point_event_fields(const SpecialPoint& sp) {
  std::ostringstream j;
  j << std::setprecision(10) << "\"kind\": \"" << to_string(sp.kind)
    << "\", \"phi_e\": " << sp.parameter << ", \"multiplicity\": " << sp.multiplicity
    << ", \"negative_before\": " << sp.negative_before
    << ", \"negative_after\": " << sp.negative_after << ", \"bracket\": " << sp.bracket_width;
  return j.str();
}

RecordedEvent special_point_summary(const SpecialPoint& sp, const std::string& branch) {
  return {to_string(sp.kind),
          sp.parameter,
          branch,
          {{"multiplicity", static_cast<double>(sp.multiplicity)},
           {"negative_before", static_cast<double>(sp.negative_before)},
           {"negative_after", static_cast<double>(sp.negative_after)}}};
}

std::optional<double> RecordedEvent::value(const std::string& name) const {
  for (const auto& [n, v] : values)
    if (n == name) return v;
  return std::nullopt;
}

bool BranchRecord::exists(const std::string& directory) {
  std::error_code ec;
  return fs::is_regular_file(fs::path(directory) / kRecordFile, ec);
}

std::string BranchRecord::committed_last_state(const std::string& directory) {
  const std::string path = directory + "/" + kRecordFile;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  try {
    const Json r = Json::parse(in);
    return r.at("last_state").is_string() ? r.at("last_state").get<std::string>() : "";
  } catch (const Json::exception& e) {
    throw std::runtime_error(path + " is not a branch record: " + e.what());
  }
}

BranchRecord::BranchRecord(std::string directory, std::vector<std::string> columns, Start start)
    : directory_(std::move(directory)), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::invalid_argument("BranchRecord: no columns");
  if (start == Start::Fresh || (!exists(directory_) && !fs::exists(path(kBranchFile))))
    start_fresh();
  else if (exists(directory_))
    continue_committed();
  else
    adopt_uncommitted();
}

void BranchRecord::start_fresh() {
  fs::create_directories(path("states"));
  // What an earlier record in the directory wrote, as its record.json lists it.
  if (exists(directory_)) {
    const Json old = Json::parse(std::ifstream(path(kRecordFile)), nullptr, false);
    if (old.is_object()) {
      std::vector<std::string> files;
      for (const Json& s : old.value("snapshots", Json::array()))
        files.push_back(s.value("file", ""));
      for (const Json& s : old.value("surfaces", Json::array()))
        files.push_back(s.get<std::string>());
      for (const std::string& f : files)
        if (plain_file_name(f)) fs::remove(path(f));
    }
  }
  for (const auto& entry : fs::directory_iterator(path("states"))) {
    const std::string name = entry.path().filename().string();
    if (saved_state_index(name) >= 0 || is_temporary_file_name(name)) fs::remove(entry.path());
  }
  remove_temporaries(directory_);
  fs::remove(path(kCollectionFile));
  write_file_atomically(path(kBranchFile), join(columns_, ",") + "\n");
  rewrite_events();
  commit();
}

void BranchRecord::continue_committed() {
  const std::string record_path = path(kRecordFile);
  Json r;
  try {
    r = Json::parse(std::ifstream(record_path));
    if (r.at("columns").get<std::vector<std::string>>() != columns_)
      throw std::runtime_error(record_path + " records the columns " +
                               join(r.at("columns").get<std::vector<std::string>>(), ",") +
                               ", not " + join(columns_, ","));
  } catch (const Json::exception& e) {
    throw std::runtime_error(record_path + " is not a branch record: " + e.what());
  }
  const std::size_t committed_rows = r.at("rows").get<std::size_t>();
  next_state_ = r.at("next_state").get<int>();
  last_state_ = r.at("last_state").is_string() ? r.at("last_state").get<std::string>() : "";
  for (const Json& e : r.at("events")) events_.push_back(event_from_json(e));
  for (const Json& s : r.at("snapshots"))
    snapshots_.push_back({s.at("phi_e").get<double>(), s.at("file").get<std::string>()});
  surfaces_ = r.at("surfaces").get<std::vector<std::string>>();

  // branch.csv: the header and the committed rows.
  const std::vector<std::string> lines = read_lines(path(kBranchFile));
  if (lines.empty() || lines[0] != join(columns_, ","))
    throw std::runtime_error(path(kBranchFile) + " does not start with the header " +
                             join(columns_, ","));
  if (lines.size() - 1 < committed_rows)
    throw std::runtime_error(path(kBranchFile) + " has " + std::to_string(lines.size() - 1) +
                             " rows, fewer than the " + std::to_string(committed_rows) +
                             " that record.json committed");
  std::string kept = lines[0] + "\n";
  for (std::size_t i = 1; i <= committed_rows; ++i) {
    rows_.push_back(
        parse_row(lines[i], columns_.size(), path(kBranchFile) + " row " + std::to_string(i)));
    kept += lines[i] + "\n";
  }
  if (lines.size() - 1 > committed_rows) write_file_atomically(path(kBranchFile), kept);

  // events.json: the committed events.
  event_lines_ = read_event_lines(path(kEventsFile));
  if (event_lines_.size() < events_.size())
    throw std::runtime_error(path(kEventsFile) + " has " + std::to_string(event_lines_.size()) +
                             " events, fewer than the " + std::to_string(events_.size()) +
                             " that record.json committed");
  if (event_lines_.size() > events_.size()) {
    event_lines_.resize(events_.size());
    rewrite_events();
  }

  // states/: none past the committed ones, and no temporaries.
  fs::create_directories(path("states"));
  for (const auto& entry : fs::directory_iterator(path("states"))) {
    const std::string name = entry.path().filename().string();
    if (saved_state_index(name) >= next_state_ || is_temporary_file_name(name))
      fs::remove(entry.path());
  }
  remove_temporaries(directory_);
  if (!last_state_.empty() && !fs::is_regular_file(path(last_state_)))
    throw std::runtime_error(record_path + " names the last state " + last_state_ +
                             ", which is missing");
  if (snapshots_.empty())
    fs::remove(path(kCollectionFile));
  else
    rewrite_collection();
}

void BranchRecord::adopt_uncommitted() {
  const std::vector<std::string> lines = read_lines(path(kBranchFile));
  if (lines.empty() || lines[0] != join(columns_, ","))
    throw std::runtime_error(path(kBranchFile) + " does not start with the header " +
                             join(columns_, ","));
  for (std::size_t i = 1; i < lines.size(); ++i)
    if (!lines[i].empty())
      rows_.push_back(
          parse_row(lines[i], columns_.size(), path(kBranchFile) + " row " + std::to_string(i)));
  if (fs::exists(path(kEventsFile))) {
    event_lines_ = read_event_lines(path(kEventsFile));
    for (const std::string& line : event_lines_) events_.push_back(summary_of_line(line));
  }
  fs::create_directories(path("states"));
  // The saved states in either format (an earlier version wrote .txt): the next index is
  // one past the last one there.
  const std::vector<fs::path> saved = saved_state_files(directory_);
  if (!saved.empty()) {
    next_state_ = saved_state_index(saved.back().filename().string()) + 1;
    last_state_ = "states/" + saved.back().filename().string();
  }
  remove_temporaries(directory_);
  remove_temporaries(path("states"));
  rewrite_events();
  commit();
}

void BranchRecord::append_row(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw std::invalid_argument("BranchRecord::append_row: " + std::to_string(values.size()) +
                                " values for " + std::to_string(columns_.size()) + " columns");
  std::ostringstream line;
  line << std::setprecision(12);
  for (std::size_t i = 0; i < values.size(); ++i) line << (i ? "," : "") << values[i];
  const std::string text = line.str();
  append_to_file(path(kBranchFile), text + "\n");
  rows_.push_back(parse_row(text, columns_.size(), path(kBranchFile) + " new row"));
}

double BranchRecord::value(std::size_t row, const std::string& column) const {
  if (row >= rows_.size())
    throw std::out_of_range(path(kBranchFile) + " has no row " + std::to_string(row));
  for (std::size_t c = 0; c < columns_.size(); ++c)
    if (columns_[c] == column) return rows_[row][c];
  throw std::out_of_range(path(kBranchFile) + " has no column '" + column + "'");
}

std::string BranchRecord::save_state(const BranchSample& sample, std::uint64_t model_fingerprint) {
  const std::string name = "states/" + saved_state_name(next_state_);
  save_branch_state(path(name), sample, model_fingerprint);
  ++next_state_;
  last_state_ = name;
  return name;
}

void BranchRecord::add_event(const std::string& json_object, RecordedEvent summary) {
  event_lines_.push_back(json_object);
  events_.push_back(std::move(summary));
  rewrite_events();
}

void BranchRecord::add_snapshot(double phi_e, const std::string& file_name,
                                const SurfaceSnapshot& surface) {
  write_atomically_with(path(file_name), [&](const std::string& t) { write_vtu(t, surface); });
  snapshots_.push_back({phi_e, file_name});
  rewrite_collection();
}

void BranchRecord::write_surface(const std::string& file_name, const SurfaceSnapshot& surface) {
  write_atomically_with(path(file_name), [&](const std::string& t) { write_vtu(t, surface); });
  surfaces_.push_back(file_name);
}

void BranchRecord::rewrite_events() const {
  std::string text = "[\n";
  for (std::size_t i = 0; i < event_lines_.size(); ++i)
    text += "  " + event_lines_[i] + (i + 1 < event_lines_.size() ? ",\n" : "\n");
  text += "]\n";
  write_file_atomically(path(kEventsFile), text);
}

void BranchRecord::rewrite_collection() const {
  write_atomically_with(path(kCollectionFile),
                        [&](const std::string& t) { write_pvd(t, snapshots_); });
}

void BranchRecord::commit() {
  Json r;
  r["record"] = "growshell branch record";
  r["columns"] = columns_;
  r["rows"] = rows_.size();
  r["next_state"] = next_state_;
  r["last_state"] = last_state_.empty() ? Json(nullptr) : Json(last_state_);
  Json events = Json::array();
  for (const RecordedEvent& e : events_) events.push_back(event_to_json(e));
  r["events"] = events;
  Json snapshots = Json::array();
  for (const CollectionEntry& s : snapshots_)
    snapshots.push_back({{"phi_e", s.time}, {"file", s.file}});
  r["snapshots"] = snapshots;
  r["surfaces"] = surfaces_;
  write_file_atomically(path(kRecordFile), r.dump(1) + "\n");
}

}  // namespace growshell
