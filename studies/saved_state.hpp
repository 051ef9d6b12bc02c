#pragma once
/// \file
/// One converged branch point on disk (a study's DIR/states/point_NNNNN.txt): phi_e,
/// dphi_e/ds, the number of unknowns, then x and dx/ds, one number per line at full precision
/// (17 significant digits), so that a trace can be resumed from it and post-processed exactly.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// "point_NNNNN.txt" (five digits, zero-padded) for the index-th saved state of a trace.
std::string saved_state_name(int index);

/// The index of a name saved_state_name made ("point_00012.txt" -> 12), or -1 for any other
/// name.
int saved_state_index(const std::string& file_name);

/// Writes the sample's parameter, tangent and state to `path` atomically (write_file_atomically).
/// Throws std::runtime_error naming the path if it cannot be written.
void save_branch_state(const std::string& path, const BranchSample& sample);

/// Reads a saved state of a model with n unknowns (parameter, tangent, x; arclength, counts
/// and iterations stay 0). Throws std::runtime_error naming the file if it is missing, of
/// another size or truncated.
BranchSample load_branch_state(const std::string& path, Eigen::Index n);

/// The saved states of a run directory (RUN_DIR/states/point_NNNNN.txt), sorted by name, i.e.
/// in trace order; other files there (e.g. a temporary left by a killed run) are skipped.
/// Throws std::filesystem::filesystem_error if RUN_DIR/states cannot be read.
std::vector<std::filesystem::path> saved_state_files(const std::string& run_dir);

}  // namespace growshell
