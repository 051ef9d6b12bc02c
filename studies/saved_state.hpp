#pragma once
/// \file
/// One converged branch point on disk (a study's DIR/states/point_NNNNN.state): phi_e,
/// dphi_e/ds, the next arclength step, x and dx/ds, bit for bit, and, for a sample of a trace
/// in a symmetric subspace, its reduced state and frame (BranchSample::reduced_x,
/// reduced_frame), so that a trace can be resumed from it exactly (the same steps as the trace
/// that wrote it, to the last bit) and post-processed exactly.
///
/// Format (`.state`): the line "growshell-state 3\n", then little-endian binary: int64 n (the
/// number of unknowns), uint64 the model fingerprint (scene_model_fingerprint, 0 = none),
/// float64 phi_e, float64 dphi_e/ds, float64 the next step (BranchSample::next_step),
/// float64 x[n], float64 dx/ds[n], int64 m (the reduced state's size, 0 = none, at most n),
/// if m > 0 float64 R[9] (row by row) and float64 t[3] of the reduced frame and float64 y[m],
/// and uint64 the FNV-1a hash of every byte before it, so a truncated or damaged file is named
/// as such. 16 n + 74 bytes without a reduced state, 16 n + 8 m + 170 with one. Versions 2
/// (without m and what follows it), 1 (without the next step either) and the text format of
/// earlier versions (`.txt`: one number per line, 17 significant digits, no fingerprint) are
/// still read, with what they lack empty or 0.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// "point_NNNNN.state" (five digits, zero-padded) for the index-th saved state of a trace.
std::string saved_state_name(int index);

/// The index of a saved state's file name ("point_00012.state" or, from an earlier version,
/// "point_00012.txt" -> 12), or -1 for any other name.
int saved_state_index(const std::string& file_name);

/// Writes the sample's parameter, tangent, state and reduced state to `path` atomically (write_file_atomically)
/// in the binary format, with the fingerprint of the model it belongs to (0 = none). Throws
/// std::runtime_error naming the path if it cannot be written.
void save_branch_state(const std::string& path, const BranchSample& sample,
                       std::uint64_t model_fingerprint = 0);

/// Reads a saved state of a model with n unknowns (parameter, tangent, next step, x, reduced
/// state and frame; arclength, counts and iterations stay 0), in any of the formats (told by its first line,
/// not its name). Throws std::runtime_error naming the file if it is missing, of another size,
/// truncated, damaged (hash mismatch), or saved for another model: when both the file's
/// fingerprint and `expected_fingerprint` are non-zero and differ (a text state has none).
BranchSample load_branch_state(const std::string& path, Eigen::Index n,
                               std::uint64_t expected_fingerprint = 0);

/// The saved states of a run directory (RUN_DIR/states/point_NNNNN.state or .txt), in trace
/// order (by index); other files there (e.g. a temporary left by a killed run) are skipped.
/// Throws std::filesystem::filesystem_error if RUN_DIR/states cannot be read.
std::vector<std::filesystem::path> saved_state_files(const std::string& run_dir);

/// The saved state of RUN_DIR whose phi_e lies nearest `phi_e` (the first in trace order on a
/// tie), read as load_branch_state reads it; nothing if RUN_DIR/states holds none. Throws as
/// saved_state_files and load_branch_state.
std::optional<BranchSample> nearest_saved_state(const std::string& run_dir, double phi_e,
                                                Eigen::Index n,
                                                std::uint64_t expected_fingerprint = 0);

/// The saved states of RUN_DIR nearest each of `phis_e` (each chosen as nearest_saved_state
/// chooses it), each state once, in trace order; empty if RUN_DIR/states holds none. Every
/// state is read once, and at most one per excess angle is held at a time. Throws as
/// nearest_saved_state.
std::vector<BranchSample> nearest_saved_states(const std::string& run_dir,
                                               const std::vector<double>& phis_e, Eigen::Index n,
                                               std::uint64_t expected_fingerprint = 0);

}  // namespace growshell
