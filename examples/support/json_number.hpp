#pragma once
// A number for the programs' JSON output: 12 significant digits, and null for NaN or infinity
// (JSON has no such numbers).

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace growshell::examples {

inline std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o << std::setprecision(12) << v;
  return o.str();
}

}  // namespace growshell::examples
