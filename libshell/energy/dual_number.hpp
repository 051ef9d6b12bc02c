#pragma once
/// \file
/// Forward-mode dual number a + b eps (eps^2 = 0) for exact first derivatives with respect to
/// one parameter, e.g. the excess angle in d(gradient)/d(phi_e).

#include <cmath>

namespace growshell {

/// value + derivative * eps. Arithmetic propagates the derivative exactly.
struct Dual {
  double value = 0.0;
  double derivative = 0.0;
  constexpr Dual() = default;
  constexpr Dual(double v) : value(v) {}  // NOLINT(google-explicit-constructor): constants
  constexpr Dual(double v, double d) : value(v), derivative(d) {}
};

inline Dual operator+(Dual a, Dual b) { return {a.value + b.value, a.derivative + b.derivative}; }
inline Dual operator-(Dual a, Dual b) { return {a.value - b.value, a.derivative - b.derivative}; }
inline Dual operator-(Dual a) { return {-a.value, -a.derivative}; }
inline Dual operator*(Dual a, Dual b) {
  return {a.value * b.value, a.derivative * b.value + a.value * b.derivative};
}
inline Dual operator/(Dual a, Dual b) {
  return {a.value / b.value,
          (a.derivative * b.value - a.value * b.derivative) / (b.value * b.value)};
}
inline Dual sqrt(Dual a) {
  const double s = std::sqrt(a.value);
  return {s, a.derivative / (2.0 * s)};
}

inline Dual log(Dual a) { return {std::log(a.value), a.derivative / a.value}; }

/// Value part of a double or a Dual.
inline double value_of(double x) { return x; }
inline double value_of(Dual x) { return x.value; }

}  // namespace growshell
