#pragma once
// The directories the programs read one traced branch from: a cone_branch study's (scene.json
// and states/ in it, e.g. an econe_contact study's DIR/cone or a sweep point) or one branch of
// an econe_contact study (DIR/symmetric, DIR/skewed, DIR/turned: states/ in it, the scene one
// folder up).

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "libshell/io/scene.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "studies/saved_state.hpp"

namespace growshell::examples {

/// The scene file of the branch directory `dir`: its own scene.json, else the one a folder up.
inline std::string branch_scene_file(const std::string& dir) {
  return std::filesystem::exists(dir + "/scene.json")
             ? dir + "/scene.json"
             : (std::filesystem::path(dir) / ".." / "scene.json").string();
}

/// The saved state of `dir` nearest phi_e, of the model of `scene` with n unknowns (its
/// fingerprint checked). Throws std::invalid_argument if dir/states holds none, and as
/// nearest_saved_state.
inline BranchSample nearest_branch_state(const std::string& dir, double phi_e, const Scene& scene,
                                         Eigen::Index n) {
  std::optional<BranchSample> nearest =
      nearest_saved_state(dir, phi_e, n, scene_model_fingerprint(scene));
  if (!nearest) throw std::invalid_argument(dir + "/states holds no saved state");
  return std::move(*nearest);
}

}  // namespace growshell::examples
