#pragma once
// One converged branch point on disk (trace_disc's states/point_NNNNN.state), for the programs
// that read a trace's states: the library's format (studies/saved_state.hpp: phi_e, dphi_e/ds,
// the number of unknowns, then x and dx/ds at full precision), under the names the programs
// use.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "solvers/continuation/pseudo_arclength.hpp"
#include "studies/saved_state.hpp"

namespace growshell::examples {

/// save_branch_state: written atomically.
inline void save_point(const std::string& path, const BranchSample& s) {
  save_branch_state(path, s);
}

/// Reads a saved point of a model with n unknowns; throws std::runtime_error naming the file
/// if it is missing, of another size or truncated.
inline BranchSample load_point(const std::string& path, Eigen::Index n) {
  return load_branch_state(path, n);
}

/// The saved points of a run directory (RUN_DIR/states/point_NNNNN.state, or .txt of an
/// earlier version), in trace order.
/// in trace order. Throws std::filesystem::filesystem_error if RUN_DIR/states cannot be read.
inline std::vector<std::filesystem::path> saved_point_files(const std::string& run_dir) {
  return saved_state_files(run_dir);
}

}  // namespace growshell::examples
