#pragma once
// The message of the std::invalid_argument a callable throws, for tests that check what a
// refusal says.

#include <stdexcept>
#include <string>

namespace growshell::test_support {

/// The message of the exception of type E (std::invalid_argument unless given) that `f`
/// throws ("" if it throws nothing).
template <class E = std::invalid_argument, class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

}  // namespace growshell::test_support
