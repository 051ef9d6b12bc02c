#pragma once
// The observed order of convergence between two errors at mesh sizes h and h / 2.

#include <cmath>

namespace growshell::test_support {

inline double convergence_rate(double coarse, double fine) { return std::log2(coarse / fine); }

}  // namespace growshell::test_support
