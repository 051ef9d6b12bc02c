#include "studies/saved_state.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/content_hash.hpp"
#include "studies/atomic_file.hpp"

namespace growshell {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the binary state format is little-endian; a big-endian build needs byte swaps");

/// Version 3 adds the reduced state after dx/ds, version 2 the next step after dphi_e/ds;
/// versions 1 and 2 are still read (no reduced state; version 1: next step 0).
constexpr std::string_view kMagic = "growshell-state 3\n";
constexpr std::string_view kMagicVersion2 = "growshell-state 2\n";
constexpr std::string_view kMagicVersion1 = "growshell-state 1\n";
constexpr std::string_view kSuffixes[] = {".state", ".txt"};

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void put_vector(std::string& out, const Eigen::VectorXd& v) {
  out.append(reinterpret_cast<const char*>(v.data()),
             static_cast<std::size_t>(v.size()) * sizeof(double));
}

[[noreturn]] void does_not_fit(const std::string& path, long long size, Eigen::Index n) {
  throw std::runtime_error("saved point " + path + " does not fit this scene (" +
                           std::to_string(size) + " unknowns, expected " + std::to_string(n) +
                           ")");
}

BranchSample parse_binary(const std::string& path, std::string_view bytes, Eigen::Index n,
                          std::uint64_t expected_fingerprint, int version) {
  std::size_t at = kMagic.size();
  static_assert(kMagic.size() == kMagicVersion1.size() && kMagic.size() == kMagicVersion2.size());
  auto take = [&](void* to, std::size_t size) {
    if (bytes.size() < at + size) throw std::runtime_error("saved point " + path + " is truncated");
    std::memcpy(to, bytes.data() + at, size);
    at += size;
  };
  std::int64_t size = 0;
  take(&size, sizeof size);
  if (size != n) does_not_fit(path, size, n);
  std::uint64_t fingerprint = 0;
  take(&fingerprint, sizeof fingerprint);
  BranchSample s;
  take(&s.parameter, sizeof(double));
  take(&s.tangent_parameter, sizeof(double));
  if (version >= 2) take(&s.next_step, sizeof(double));
  s.x.resize(n);
  s.tangent_state.resize(n);
  take(s.x.data(), static_cast<std::size_t>(n) * sizeof(double));
  take(s.tangent_state.data(), static_cast<std::size_t>(n) * sizeof(double));
  if (version >= 3) {
    std::int64_t m = 0;
    take(&m, sizeof m);
    if (m < 0 || m > n)
      throw std::runtime_error("saved point " + path + " is damaged (a reduced state of " +
                               std::to_string(m) + " entries for " + std::to_string(n) +
                               " unknowns)");
    if (m > 0) {
      double frame[12];
      take(frame, sizeof frame);
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) s.reduced_frame.rotation(r, c) = frame[3 * r + c];
        s.reduced_frame.translation(r) = frame[9 + r];
      }
      s.reduced_x.resize(m);
      take(s.reduced_x.data(), static_cast<std::size_t>(m) * sizeof(double));
    }
  }
  const std::uint64_t expected = fnv1a_64(bytes.substr(0, at));
  std::uint64_t stored = 0;
  take(&stored, sizeof stored);
  if (at != bytes.size())
    throw std::runtime_error("saved point " + path + " has " +
                             std::to_string(bytes.size() - at) + " bytes after its end");
  if (stored != expected)
    throw std::runtime_error("saved point " + path + " is damaged (its hash does not match)");
  if (fingerprint != 0 && expected_fingerprint != 0 && fingerprint != expected_fingerprint)
    throw std::runtime_error("saved point " + path +
                             " belongs to another model: its scene differs from this one in "
                             "geometry, thickness, material, growth or mesh");
  return s;
}

BranchSample parse_text(const std::string& path, const std::string& text, Eigen::Index n) {
  std::istringstream in(text);
  BranchSample s;
  Eigen::Index size = 0;
  in >> s.parameter >> s.tangent_parameter >> size;
  if (!in || size != n) does_not_fit(path, static_cast<long long>(size), n);
  s.x.resize(n);
  s.tangent_state.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) in >> s.x(i);
  for (Eigen::Index i = 0; i < n; ++i) in >> s.tangent_state(i);
  if (!in) throw std::runtime_error("saved point " + path + " is truncated");
  return s;
}

}  // namespace

std::string saved_state_name(int index) {
  std::ostringstream name;
  name << "point_" << std::setw(5) << std::setfill('0') << index << kSuffixes[0];
  return name.str();
}

int saved_state_index(const std::string& file_name) {
  const std::string_view prefix = "point_";
  if (file_name.compare(0, prefix.size(), prefix) != 0) return -1;
  for (std::string_view suffix : kSuffixes) {
    if (file_name.size() < prefix.size() + 5 + suffix.size() ||
        file_name.compare(file_name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits =
        file_name.substr(prefix.size(), file_name.size() - prefix.size() - suffix.size());
    if (digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return -1;
    return std::stoi(digits);
  }
  return -1;
}

void save_branch_state(const std::string& path, const BranchSample& s,
                       std::uint64_t model_fingerprint) {
  if (s.tangent_state.size() != s.x.size())
    throw std::invalid_argument("save_branch_state: the tangent has " +
                                std::to_string(s.tangent_state.size()) + " entries, the state " +
                                std::to_string(s.x.size()));
  std::string out(kMagic);
  out.reserve(kMagic.size() + 16 * static_cast<std::size_t>(s.x.size()) +
              8 * static_cast<std::size_t>(s.reduced_x.size()) + 160);
  put(out, static_cast<std::int64_t>(s.x.size()));
  put(out, model_fingerprint);
  put(out, s.parameter);
  put(out, s.tangent_parameter);
  put(out, s.next_step);
  put_vector(out, s.x);
  put_vector(out, s.tangent_state);
  if (s.reduced_x.size() > s.x.size())
    throw std::invalid_argument("save_branch_state: a reduced state of " +
                                std::to_string(s.reduced_x.size()) + " entries for " +
                                std::to_string(s.x.size()) + " unknowns");
  put(out, static_cast<std::int64_t>(s.reduced_x.size()));
  if (s.reduced_x.size() > 0) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) put(out, s.reduced_frame.rotation(r, c));
    for (int r = 0; r < 3; ++r) put(out, s.reduced_frame.translation(r));
    put_vector(out, s.reduced_x);
  }
  put(out, fnv1a_64(out));
  write_file_atomically(path, out);
}

BranchSample load_branch_state(const std::string& path, Eigen::Index n,
                               std::uint64_t expected_fingerprint) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read saved point " + path);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string_view head = std::string_view(bytes).substr(0, kMagic.size());
  if (head == kMagic) return parse_binary(path, bytes, n, expected_fingerprint, 3);
  if (head == kMagicVersion2) return parse_binary(path, bytes, n, expected_fingerprint, 2);
  if (head == kMagicVersion1) return parse_binary(path, bytes, n, expected_fingerprint, 1);
  return parse_text(path, bytes, n);
}

std::vector<std::filesystem::path> saved_state_files(const std::string& run_dir) {
  std::vector<std::pair<int, std::filesystem::path>> indexed;
  for (const auto& entry : std::filesystem::directory_iterator(run_dir + "/states")) {
    const int index = saved_state_index(entry.path().filename().string());
    if (index >= 0) indexed.emplace_back(index, entry.path());
  }
  std::sort(indexed.begin(), indexed.end());
  std::vector<std::filesystem::path> files;
  for (auto& [index, path] : indexed) files.push_back(std::move(path));
  return files;
}

std::optional<BranchSample> nearest_saved_state(const std::string& run_dir, double phi_e,
                                                Eigen::Index n,
                                                std::uint64_t expected_fingerprint) {
  std::vector<BranchSample> nearest = nearest_saved_states(run_dir, {phi_e}, n, expected_fingerprint);
  if (nearest.empty()) return std::nullopt;
  return std::move(nearest.front());
}

std::vector<BranchSample> nearest_saved_states(const std::string& run_dir,
                                               const std::vector<double>& phis_e, Eigen::Index n,
                                               std::uint64_t expected_fingerprint) {
  // For each excess angle asked for, the trace index of the nearest state so far and that state.
  std::vector<std::optional<std::pair<std::size_t, BranchSample>>> nearest(phis_e.size());
  std::size_t index = 0;
  for (const std::filesystem::path& file : saved_state_files(run_dir)) {
    const BranchSample s = load_branch_state(file.string(), n, expected_fingerprint);
    for (std::size_t k = 0; k < phis_e.size(); ++k)
      if (!nearest[k] ||
          std::abs(s.parameter - phis_e[k]) < std::abs(nearest[k]->second.parameter - phis_e[k]))
        nearest[k] = std::make_pair(index, s);
    ++index;
  }
  std::vector<std::pair<std::size_t, BranchSample>> chosen;
  for (auto& n_k : nearest)
    if (n_k && std::none_of(chosen.begin(), chosen.end(),
                            [&](const auto& c) { return c.first == n_k->first; }))
      chosen.push_back(std::move(*n_k));
  std::sort(chosen.begin(), chosen.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<BranchSample> samples;
  for (auto& c : chosen) samples.push_back(std::move(c.second));
  return samples;
}

}  // namespace growshell
