#include "libshell/mesh/hexagon_disc_map.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace growshell {
namespace {

using Complex = std::complex<double>;

/// C = 1 / int_0^1 (1 - t^6)^(-1/3) dt = 6 Gamma(5/6) / (Gamma(1/6) Gamma(2/3)), so f(1) = 1.
double scale_constant() {
  return 6.0 * std::tgamma(5.0 / 6.0) / (std::tgamma(1.0 / 6.0) * std::tgamma(2.0 / 3.0));
}

/// f'(w) / C = (1 - w^6)^(-1/3), principal branch (Re(1 - w^6) > 0 inside the disc).
Complex integrand(Complex w) { return std::pow(1.0 - std::pow(w, 6), -1.0 / 3.0); }

/// Series sum_k c_k w^(6k+1) / (6k+1) with c_k the coefficients of (1 - x)^(-1/3); used for
/// |w| <= kSeriesRadius, where 60 terms reach 1e-17.
constexpr double kSeriesRadius = 0.8;

Complex series(Complex w) {
  const Complex w6 = std::pow(w, 6);
  Complex power = w, sum = 0.0;
  double c = 1.0;
  for (int k = 0; k < 200; ++k) {
    const Complex term = c * power / (6.0 * k + 1.0);
    sum += term;
    if (std::abs(term) < 1e-18) break;
    c *= (k + 1.0 / 3.0) / (k + 1.0);
    power *= w6;
  }
  return sum;
}

/// 32-point Gauss-Legendre nodes and weights on [0, 1], computed once by Newton's method on
/// the Legendre polynomial.
struct GaussLegendre {
  std::array<double, 32> x, w;
  GaussLegendre() {
    const int n = 32;
    for (int i = 0; i < n; ++i) {
      double t = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
      double dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = t;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (t * p1 - p0) / (t * t - 1.0);
        const double dt = p1 / dp;
        t -= dt;
        if (std::abs(dt) < 1e-16) break;
      }
      x[i] = 0.5 * (1.0 - t);
      w[i] = 1.0 / ((1.0 - t * t) * dp * dp);  // = 2 / ((1-t^2) P'^2) / 2
    }
  }
};

}  // namespace

Complex disc_to_hexagon(Complex w) {
  static const double C = scale_constant();
  if (std::abs(w) <= kSeriesRadius) return C * series(w);
  // Integrate radially from the series' radius: f(w) = f(w0) + C int_w0^w (1 - t^6)^(-1/3).
  static const GaussLegendre gauss;
  const Complex w0 = w * (kSeriesRadius / std::abs(w));
  // t = w0 + (w - w0) (1 - (1 - s)^3) clusters the nodes at w, which cancels the
  // (corner - t)^(-1/3) singularity when w approaches a corner's pre-image.
  Complex sum = 0.0;
  for (std::size_t i = 0; i < gauss.x.size(); ++i) {
    const double r = 1.0 - gauss.x[i];
    sum += gauss.w[i] * 3.0 * r * r * integrand(w0 + (1.0 - r * r * r) * (w - w0));
  }
  return C * (series(w0) + sum * (w - w0));
}

Complex hexagon_to_disc(Complex z) {
  static const double C = scale_constant();
  // Schwarz reflection for points beyond a side: the side with outward normal at angle
  // (2s + 1) pi / 6 lies at distance cos(pi/6) from the centre.
  const double apothem = std::cos(std::numbers::pi / 6.0);
  const double angle = std::arg(z);
  const int side = static_cast<int>(std::floor(angle / (std::numbers::pi / 3.0)));
  const Complex normal = std::polar(1.0, (2.0 * side + 1.0) * std::numbers::pi / 6.0);
  const double beyond = (z * std::conj(normal)).real() - apothem;
  if (beyond > 1e-14) {
    const Complex mirrored = z - 2.0 * beyond * normal;
    const Complex w = hexagon_to_disc(mirrored);
    return w / std::norm(w);  // reflection in the unit circle: 1 / conj(w)
  }
  // Corners map to themselves exactly (the map is singular there).
  for (int k = 0; k < 6; ++k) {
    const Complex corner = std::polar(1.0, k * std::numbers::pi / 3.0);
    if (std::abs(z - corner) < 1e-14) return corner;
  }
  // Start strictly inside the disc: the derivative is infinite on the corners' pre-images.
  Complex w = z / C;
  if (std::abs(w) > 0.99) w *= 0.99 / std::abs(w);
  for (int it = 0; it < 100; ++it) {
    const Complex step = (disc_to_hexagon(w) - z) / (C * integrand(w));
    Complex next = w - step;
    // Stay in the closed disc; a step that leaves it is shortened.
    if (std::abs(next) > 1.0) next = 0.5 * (w + next / std::abs(next));
    const bool done = std::abs(next - w) < 1e-15;
    w = next;
    if (done) break;
  }
  return w;
}

}  // namespace growshell
