#include "libshell/subdivision/loop_basis.hpp"

#include <array>
#include <initializer_list>

namespace growshell {
namespace {

/// One monomial coef * u^a v^b w^c of a basis function (before the common factor 1/12).
struct Monomial {
  double coef;
  int a, b, c;
};

using Basis = std::initializer_list<Monomial>;

// Stam (1998) / Cirak et al. (2000), Eq. (17), in our 0-based numbering.
const std::array<Basis, 12>& basis_monomials() {
  static const std::array<Basis, 12> kBasis = {
      Basis{{1, 4, 0, 0}, {2, 3, 1, 0}},
      Basis{{1, 4, 0, 0}, {2, 3, 0, 1}},
      Basis{{1, 4, 0, 0}, {2, 3, 0, 1}, {6, 3, 1, 0}, {6, 2, 1, 1}, {12, 2, 2, 0}, {6, 1, 2, 1},
            {6, 1, 3, 0}, {2, 0, 3, 1}, {1, 0, 4, 0}},
      Basis{{6, 4, 0, 0}, {24, 3, 0, 1}, {24, 2, 0, 2}, {8, 1, 0, 3}, {1, 0, 0, 4},
            {24, 3, 1, 0}, {60, 2, 1, 1}, {36, 1, 1, 2}, {6, 0, 1, 3}, {24, 2, 2, 0},
            {36, 1, 2, 1}, {12, 0, 2, 2}, {8, 1, 3, 0}, {6, 0, 3, 1}, {1, 0, 4, 0}},
      Basis{{1, 4, 0, 0}, {6, 3, 0, 1}, {12, 2, 0, 2}, {6, 1, 0, 3}, {1, 0, 0, 4}, {2, 3, 1, 0},
            {6, 2, 1, 1}, {6, 1, 1, 2}, {2, 0, 1, 3}},
      Basis{{2, 1, 3, 0}, {1, 0, 4, 0}},
      Basis{{1, 4, 0, 0}, {6, 3, 0, 1}, {12, 2, 0, 2}, {6, 1, 0, 3}, {1, 0, 0, 4}, {8, 3, 1, 0},
            {36, 2, 1, 1}, {36, 1, 1, 2}, {8, 0, 1, 3}, {24, 2, 2, 0}, {60, 1, 2, 1},
            {24, 0, 2, 2}, {24, 1, 3, 0}, {24, 0, 3, 1}, {6, 0, 4, 0}},
      Basis{{1, 4, 0, 0}, {8, 3, 0, 1}, {24, 2, 0, 2}, {24, 1, 0, 3}, {6, 0, 0, 4}, {6, 3, 1, 0},
            {36, 2, 1, 1}, {60, 1, 1, 2}, {24, 0, 1, 3}, {12, 2, 2, 0}, {36, 1, 2, 1},
            {24, 0, 2, 2}, {6, 1, 3, 0}, {8, 0, 3, 1}, {1, 0, 4, 0}},
      Basis{{2, 1, 0, 3}, {1, 0, 0, 4}},
      Basis{{2, 0, 3, 1}, {1, 0, 4, 0}},
      Basis{{2, 1, 0, 3}, {1, 0, 0, 4}, {6, 1, 1, 2}, {6, 0, 1, 3}, {6, 1, 2, 1}, {12, 0, 2, 2},
            {2, 1, 3, 0}, {6, 0, 3, 1}, {1, 0, 4, 0}},
      Basis{{1, 0, 0, 4}, {2, 0, 1, 3}},
  };
  return kBasis;
}

/// x^n and its first two derivatives (n x^(n-1), n(n-1) x^(n-2)), safe for n < 2.
struct PowerJet {
  double p, d1, d2;
};

PowerJet power_jet(double x, int n) {
  auto pw = [x](int k) {
    double r = 1.0;
    for (int i = 0; i < k; ++i) r *= x;
    return r;
  };
  return {pw(n), n >= 1 ? n * pw(n - 1) : 0.0, n >= 2 ? n * (n - 1) * pw(n - 2) : 0.0};
}

}  // namespace

LoopBasisValues evaluate_regular_loop_basis(double v, double w) {
  const double u = 1.0 - v - w;
  LoopBasisValues out;
  out.value.setZero();
  out.first.setZero();
  out.second.setZero();
  const auto& basis = basis_monomials();
  for (int i = 0; i < 12; ++i) {
    for (const Monomial& m : basis[i]) {
      // f = U(u) V(v) W(w) with u = 1 - v - w, so d/dv = -U' V W + U V' W, etc.
      const PowerJet U = power_jet(u, m.a), V = power_jet(v, m.b), W = power_jet(w, m.c);
      const double c = m.coef / 12.0;
      out.value(i) += c * U.p * V.p * W.p;
      out.first(i, 0) += c * (-U.d1 * V.p + U.p * V.d1) * W.p;
      out.first(i, 1) += c * (-U.d1 * W.p + U.p * W.d1) * V.p;
      out.second(i, 0) += c * (U.d2 * V.p - 2.0 * U.d1 * V.d1 + U.p * V.d2) * W.p;
      out.second(i, 1) += c * (U.d2 * W.p - 2.0 * U.d1 * W.d1 + U.p * W.d2) * V.p;
      out.second(i, 2) +=
          c * (U.d2 * V.p * W.p - U.d1 * V.d1 * W.p - U.d1 * V.p * W.d1 + U.p * V.d1 * W.d1);
    }
  }
  return out;
}

}  // namespace growshell
