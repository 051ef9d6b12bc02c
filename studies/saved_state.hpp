#pragma once
/// \file
/// One converged branch point on disk (a study's DIR/states/point_NNNNN.state): phi_e,
/// dphi_e/ds, x and dx/ds, bit for bit, so that a trace can be resumed from it and
/// post-processed exactly.
///
/// Format (`.state`): the line "growshell-state 1\n", then little-endian binary: int64 n (the
/// number of unknowns), float64 phi_e, float64 dphi_e/ds, float64 x[n], float64 dx/ds[n], and
/// uint64 the FNV-1a hash of every byte before it, so a truncated or damaged file is named as
/// such. 16 n + 50 bytes: 2.7 times smaller than the text format of earlier versions
/// (`.txt`: one number per line, 17 significant digits), which is still read.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// "point_NNNNN.state" (five digits, zero-padded) for the index-th saved state of a trace.
std::string saved_state_name(int index);

/// The index of a saved state's file name ("point_00012.state" or, from an earlier version,
/// "point_00012.txt" -> 12), or -1 for any other name.
int saved_state_index(const std::string& file_name);

/// Writes the sample's parameter, tangent and state to `path` atomically (write_file_atomically)
/// in the binary format. Throws std::runtime_error naming the path if it cannot be written.
void save_branch_state(const std::string& path, const BranchSample& sample);

/// Reads a saved state of a model with n unknowns (parameter, tangent, x; arclength, counts
/// and iterations stay 0), in either format (told by its first line, not its name). Throws
/// std::runtime_error naming the file if it is missing, of another size, truncated or, in the
/// binary format, damaged (hash mismatch).
BranchSample load_branch_state(const std::string& path, Eigen::Index n);

/// The saved states of a run directory (RUN_DIR/states/point_NNNNN.state or .txt), in trace
/// order (by index); other files there (e.g. a temporary left by a killed run) are skipped.
/// Throws std::filesystem::filesystem_error if RUN_DIR/states cannot be read.
std::vector<std::filesystem::path> saved_state_files(const std::string& run_dir);

}  // namespace growshell
