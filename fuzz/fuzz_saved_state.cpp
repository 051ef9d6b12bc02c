// libFuzzer target: the saved-state reader (load_branch_state), both formats. Any file must
// either be refused with std::runtime_error or read into a state that saves and reads back
// bit for bit.
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "studies/saved_state.hpp"

namespace {

/// A scratch file of this process (load_branch_state reads from a path).
std::string scratch(const std::string& name) {
  static const std::string prefix = "/tmp/growshell_fuzz_state_" + std::to_string(getpid()) + "_";
  return prefix + name;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input = scratch("input.state");
  std::ofstream(input, std::ios::binary).write(reinterpret_cast<const char*>(data),
                                                static_cast<std::streamsize>(size));
  // Models of a few sizes (the input's own size field decides which one it fits).
  for (Eigen::Index n : {Eigen::Index(1), Eigen::Index(3), Eigen::Index(6)}) {
    growshell::BranchSample s;
    try {
      s = growshell::load_branch_state(input, n, 7);
    } catch (const std::runtime_error&) {
      continue;
    }
    const std::string again = scratch("output.state");
    growshell::save_branch_state(again, s, 7);
    const growshell::BranchSample t = growshell::load_branch_state(again, n, 7);
    // Bit for bit (NaN included): compare the bytes.
    auto same = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return a.size() == b.size() &&
             std::equal(reinterpret_cast<const char*>(a.data()),
                        reinterpret_cast<const char*>(a.data() + a.size()),
                        reinterpret_cast<const char*>(b.data()));
    };
    auto same_number = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    if (!same(s.x, t.x) || !same(s.tangent_state, t.tangent_state) ||
        !same_number(s.parameter, t.parameter) ||
        !same_number(s.tangent_parameter, t.tangent_parameter) ||
        !same_number(s.next_step, t.next_step) || !same(s.reduced_x, t.reduced_x) ||
        !std::equal(s.reduced_frame.rotation.data(), s.reduced_frame.rotation.data() + 9,
                    t.reduced_frame.rotation.data(), same_number) ||
        !std::equal(s.reduced_frame.translation.data(), s.reduced_frame.translation.data() + 3,
                    t.reduced_frame.translation.data(), same_number))
      std::abort();
  }
  return 0;
}
