#include "studies/saved_state.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "studies/atomic_file.hpp"

namespace growshell {

std::string saved_state_name(int index) {
  std::ostringstream name;
  name << "point_" << std::setw(5) << std::setfill('0') << index << ".txt";
  return name.str();
}

int saved_state_index(const std::string& file_name) {
  const std::string prefix = "point_", suffix = ".txt";
  if (file_name.size() < prefix.size() + 5 + suffix.size() ||
      file_name.compare(0, prefix.size(), prefix) != 0 ||
      file_name.compare(file_name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string digits =
      file_name.substr(prefix.size(), file_name.size() - prefix.size() - suffix.size());
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  if (digits.size() > 9) return -1;
  return std::stoi(digits);
}

void save_branch_state(const std::string& path, const BranchSample& s) {
  std::ostringstream out;
  out << std::setprecision(17) << s.parameter << '\n'
      << s.tangent_parameter << '\n'
      << s.x.size() << '\n';
  for (Eigen::Index i = 0; i < s.x.size(); ++i) out << s.x(i) << '\n';
  for (Eigen::Index i = 0; i < s.x.size(); ++i) out << s.tangent_state(i) << '\n';
  write_file_atomically(path, out.str());
}

BranchSample load_branch_state(const std::string& path, Eigen::Index n) {
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

std::vector<std::filesystem::path> saved_state_files(const std::string& run_dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(run_dir + "/states"))
    if (saved_state_index(entry.path().filename().string()) >= 0) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace growshell
