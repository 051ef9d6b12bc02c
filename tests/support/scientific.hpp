#pragma once
// A number in std::scientific notation, for test messages.

#include <sstream>
#include <string>

namespace growshell::test_support {

inline std::string scientific(double v) {
  std::ostringstream s;
  s << std::scientific << v;
  return s.str();
}

}  // namespace growshell::test_support
