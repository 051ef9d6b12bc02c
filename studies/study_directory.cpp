#include "studies/study_directory.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include <nlohmann/json.hpp>

#include "studies/branch_record.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;

/// Keys a resumed study may change: where the trace ends and what it writes, not the states
/// already on its branch (phi_start is where a trace from flat begins, which a resumed study
/// never does; it may need to move into a new [phi_min, phi_max]).
constexpr std::array<std::string_view, 8> kResumableKeys = {
    "continuation.phi_start", "continuation.phi_min",  "continuation.phi_max",
    "output.directory",       "output.snapshot_every", "output.write_vtk",
    "study.through_contact",  "study.eigenmodes"};

/// The value of a dotted key in a scene_to_json document.
const nlohmann::json& at_key(const nlohmann::json& document, const std::string& key) {
  const std::size_t dot = key.find('.');
  return dot == std::string::npos ? document.at(key)
                                  : document.at(key.substr(0, dot)).at(key.substr(dot + 1));
}

}  // namespace

void check_output_directory(const std::string& directory, ExistingOutput existing,
                            const std::string& recorded, const std::string& record_file) {
  std::error_code ec;
  if (!fs::exists(directory, ec)) return;
  if (!fs::is_directory(directory, ec))
    throw std::invalid_argument("output directory '" + directory +
                                "' exists and is not a directory");
  if (fs::is_empty(directory, ec)) return;
  if (existing == ExistingOutput::Refuse)
    throw std::invalid_argument("output directory '" + directory +
                                "' is not empty; give --resume to continue the " + recorded +
                                " recorded there, or --overwrite to replace it");
  if (existing == ExistingOutput::Resume &&
      !fs::is_regular_file(fs::path(directory) / record_file, ec))
    throw std::invalid_argument("output directory '" + directory + "' holds no " + recorded +
                                " record (" + record_file + ") to resume; give --overwrite to " +
                                "replace what is there");
}

void check_study_directory(const std::string& directory, ExistingOutput existing) {
  check_output_directory(directory, existing, "study", BranchRecord::kRecordFileName);
}

void check_resumable_scene(const std::string& directory, const Scene& scene) {
  const std::string path = directory + "/scene.json";
  const nlohmann::json saved = nlohmann::json::parse(scene_to_json(read_scene(path)));
  const nlohmann::json wanted = nlohmann::json::parse(scene_to_json(scene));
  for (const std::string& key : scene_keys()) {
    if (std::find(kResumableKeys.begin(), kResumableKeys.end(), key) != kResumableKeys.end())
      continue;
    const nlohmann::json& a = at_key(saved, key);
    const nlohmann::json& b = at_key(wanted, key);
    if (a != b)
      throw std::invalid_argument("cannot resume the study in '" + directory + "': its scene has " +
                                  key + " = " + a.dump() + ", this scene " + b.dump() +
                                  " (a resumed study may change only continuation.phi_start, "
                                  "continuation.phi_min, continuation.phi_max, output.*, "
                                  "study.through_contact and study.eigenmodes)");
  }
}

}  // namespace growshell
