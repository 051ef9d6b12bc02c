#pragma once
// One converged branch point on disk (trace_disc's states/point_NNNNN.txt): phi_e,
// dphi_e/ds, the number of unknowns, then x and dx/ds, one number per line at full precision,
// so a run can be resumed from it and post-processed exactly.

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell::examples {

inline void save_point(const std::string& path, const BranchSample& s) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << std::setprecision(17) << s.parameter << '\n' << s.tangent_parameter << '\n'
      << s.x.size() << '\n';
  for (Eigen::Index i = 0; i < s.x.size(); ++i) out << s.x(i) << '\n';
  for (Eigen::Index i = 0; i < s.x.size(); ++i) out << s.tangent_state(i) << '\n';
}

/// Reads a saved point of a model with n unknowns; throws std::runtime_error naming the file
/// if it is missing, of another size or truncated.
inline BranchSample load_point(const std::string& path, Eigen::Index n) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read saved point " + path);
  BranchSample s;
  Eigen::Index size = 0;
  in >> s.parameter >> s.tangent_parameter >> size;
  if (!in || size != n)
    throw std::runtime_error("saved point " + path + " does not fit this scene (" +
                             std::to_string(size) + " unknowns, expected " + std::to_string(n) +
                             ")");
  s.x.resize(n);
  s.tangent_state.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) in >> s.x(i);
  for (Eigen::Index i = 0; i < n; ++i) in >> s.tangent_state(i);
  if (!in) throw std::runtime_error("saved point " + path + " is truncated");
  return s;
}

/// The saved points of a run directory (RUN_DIR/states/*), sorted by name, i.e. in trace order.
/// Throws std::filesystem::filesystem_error if RUN_DIR/states cannot be read.
inline std::vector<std::filesystem::path> saved_point_files(const std::string& run_dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(run_dir + "/states"))
    files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace growshell::examples
