#include "solvers/continuation/branch_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace growshell {
namespace {

/// Value and lambda-derivative of the Hermite cubic of one interval.
struct HermiteValue {
  double value;
  double slope;
};

HermiteValue hermite(const BranchEnergySample& s0, const BranchEnergySample& s1, double lambda) {
  // Signed width: t runs from 0 at s0 to 1 at s1 whichever way lambda is ordered, and the
  // basis weights are exactly 0 or 1 at t = 0 and t = 1, so adjacent intervals agree exactly
  // at their shared sample (the deduplication relies on this).
  const double h = s1.parameter - s0.parameter;
  const double t = (lambda - s0.parameter) / h;
  const double t2 = t * t;
  const double t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1;
  const double h10 = t3 - 2 * t2 + t;
  const double h01 = -2 * t3 + 3 * t2;
  const double h11 = t3 - t2;
  const double d00 = 6 * t2 - 6 * t;
  const double d10 = 3 * t2 - 4 * t + 1;
  const double d11 = 3 * t2 - 2 * t;
  return {s0.energy * h00 + h * s0.energy_slope * h10 + s1.energy * h01 + h * s1.energy_slope * h11,
          (s0.energy - s1.energy) * d00 / h + s0.energy_slope * d10 + s1.energy_slope * d11};
}

/// A sample interval of nonzero width with what the error estimate needs.
struct Interval {
  std::size_t segment;  ///< i of [i, i+1] in the branch's samples
  std::size_t ordinal;  ///< position among the branch's nonzero-width intervals
  const BranchEnergySample* s0;
  const BranchEnergySample* s1;
  double lo, hi;
  bool has_quartic;  ///< a neighbour qualified, so `quartic` is set
  double quartic;    ///< c of the embedded quartic E^H + c (l - l_i)^2 (l - l_{i+1})^2

  HermiteValue at(double lambda) const { return hermite(*s0, *s1, lambda); }

  double bubble(double lambda) const {
    const double u = (lambda - s0->parameter) * (lambda - s1->parameter);
    return u * u;
  }

  /// Estimated |E - E^H| at lambda (see the header).
  double interpolation_error(double lambda) const {
    if (has_quartic) return std::abs(quartic) * bubble(lambda);
    const double t = (lambda - s0->parameter) / (s1->parameter - s0->parameter);
    const double chord = s0->energy + t * (s1->energy - s0->energy);
    return std::abs(at(lambda).value - chord);
  }
};

void validate(const std::vector<BranchEnergySample>& samples, const char* name) {
  if (samples.size() < 2) {
    throw std::invalid_argument(std::string("energy_crossings: branch ") + name + " has " +
                                std::to_string(samples.size()) +
                                " sample(s); at least 2 are needed");
  }
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const BranchEnergySample& s = samples[i];
    const char* field = !std::isfinite(s.parameter) ? "parameter"
                        : !std::isfinite(s.energy)  ? "energy"
                        : !std::isfinite(s.energy_slope) ? "energy_slope"
                                                         : nullptr;
    if (field != nullptr) {
      throw std::invalid_argument(std::string("energy_crossings: branch ") + name + " sample " +
                                  std::to_string(i) + " has a non-finite " + field);
    }
  }
}

std::vector<Interval> make_intervals(const std::vector<BranchEnergySample>& s) {
  std::vector<Interval> out;
  const std::size_t n = s.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double step = s[i + 1].parameter - s[i].parameter;
    if (step == 0.0) continue;
    Interval iv{i, out.size(), &s[i], &s[i + 1], std::min(s[i].parameter, s[i + 1].parameter),
                std::max(s[i].parameter, s[i + 1].parameter), false, 0.0};
    // A neighbour counts only if lambda keeps going the same way up to it: then it lies on the
    // same sheet of E(lambda) as the interval (no fold in between), strictly outside the
    // interval, so the bubble function is nonzero there.
    auto try_neighbour = [&](std::size_t neighbour, double neighbour_step) {
      if (neighbour_step == 0.0 || (neighbour_step > 0) != (step > 0)) return;
      const double lambda = s[neighbour].parameter;
      const double c = (s[neighbour].energy - iv.at(lambda).value) / iv.bubble(lambda);
      if (!iv.has_quartic || std::abs(c) > std::abs(iv.quartic)) iv.quartic = c;
      iv.has_quartic = true;
    };
    if (i >= 1) try_neighbour(i - 1, s[i].parameter - s[i - 1].parameter);
    if (i + 2 < n) try_neighbour(i + 2, s[i + 2].parameter - s[i + 1].parameter);
    out.push_back(iv);
  }
  return out;
}

/// Roots of the quadratic q0 + q1 u + q2 u^2 strictly inside (-r, r), ascending.
std::vector<double> quadratic_roots_inside(double q0, double q1, double q2, double r) {
  std::vector<double> roots;
  auto keep = [&](double u) {
    if (std::isfinite(u) && u > -r && u < r) roots.push_back(u);
  };
  if (q2 == 0.0) {
    if (q1 != 0.0) keep(-q0 / q1);
  } else {
    const double disc = q1 * q1 - 4 * q2 * q0;
    if (disc >= 0.0) {
      // Cancellation-free pair: q = -(q1 + sign(q1) sqrt(disc)) / 2, roots q/q2 and q0/q.
      const double q = -0.5 * (q1 + std::copysign(std::sqrt(disc), q1));
      keep(q / q2);
      if (q != 0.0) keep(q0 / q);
    }
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

struct Candidate {
  EnergyCrossing crossing;
  std::size_t ordinal_a, ordinal_b;
};

/// Appends the roots of E_a^H - E_b^H on the overlap of two intervals.
void pair_roots(const Interval& a, const Interval& b, double tolerance,
                std::vector<Candidate>& out) {
  const double lo = std::max(a.lo, b.lo);
  const double hi = std::min(a.hi, b.hi);
  // Ranges that merely touch (one branch ends where the other begins) carry no crossing; a
  // root at a shared sample inside both ranges is met by a pair of positive overlap anyway.
  if (!(hi > lo)) return;
  auto difference = [&](double lambda) { return a.at(lambda).value - b.at(lambda).value; };
  auto record = [&](double lambda, double bracket_half_width) {
    const HermiteValue ea = a.at(lambda);
    const HermiteValue eb = b.at(lambda);
    const double slope_difference = ea.slope - eb.slope;
    const double energy_error = a.interpolation_error(lambda) + b.interpolation_error(lambda);
    const double error = slope_difference == 0.0
                             ? std::numeric_limits<double>::infinity()
                             : energy_error / std::abs(slope_difference) + bracket_half_width;
    out.push_back({{lambda, 0.5 * (ea.value + eb.value), slope_difference, error, a.segment,
                    b.segment},
                   a.ordinal, b.ordinal});
  };
  // D is a cubic on the overlap; its derivative is a quadratic, recovered exactly (up to
  // rounding) from three values in the centred variable u = lambda - mid.
  const double mid = 0.5 * (lo + hi);
  const double r = 0.5 * (hi - lo);
  const double d_lo = a.at(lo).slope - b.at(lo).slope;
  const double d_mid = a.at(mid).slope - b.at(mid).slope;
  const double d_hi = a.at(hi).slope - b.at(hi).slope;
  const double D_lo = difference(lo);
  const double D_hi = difference(hi);
  if (D_lo == 0.0 && D_hi == 0.0 && d_lo == 0.0 && d_hi == 0.0 && difference(mid) == 0.0) {
    return;  // identical interpolants (a shared stretch of branch): no isolated crossing
  }
  std::vector<double> breaks{lo};
  for (double u : quadratic_roots_inside(d_mid, (d_hi - d_lo) / (2 * r),
                                         (d_hi - 2 * d_mid + d_lo) / (2 * r * r), r)) {
    breaks.push_back(mid + u);
  }
  breaks.push_back(hi);

  // Between consecutive breaks D is monotone, so a root there is bracketed by a sign change.
  double p = breaks[0];
  double Dp = D_lo;
  for (std::size_t k = 1; k < breaks.size(); ++k) {
    const double q = breaks[k];
    const double Dq = k + 1 == breaks.size() ? D_hi : difference(q);
    if (Dp == 0.0) record(p, 0.0);
    if (Dq == 0.0) {
      record(q, 0.0);
    } else if (Dp != 0.0 && (Dp > 0) != (Dq > 0)) {
      double left = p, right = q, f_left = Dp;
      while (right - left > tolerance) {
        const double m = 0.5 * (left + right);
        if (m <= left || m >= right) break;  // bracket at machine resolution
        const double fm = difference(m);
        if (fm == 0.0) {
          left = right = m;
          break;
        }
        if ((fm > 0) == (f_left > 0)) {
          left = m;
          f_left = fm;
        } else {
          right = m;
        }
      }
      record(0.5 * (left + right), 0.5 * (right - left));
    }
    p = q;
    Dp = Dq;
  }
}

}  // namespace

double hermite_energy(const BranchEnergySample& s0, const BranchEnergySample& s1, double lambda) {
  if (s0.parameter == s1.parameter) {
    throw std::invalid_argument("hermite_energy: the two samples have the same parameter " +
                                std::to_string(s0.parameter) + "; the interval has zero width");
  }
  return hermite(s0, s1, lambda).value;
}

std::vector<EnergyCrossing> energy_crossings(const std::vector<BranchEnergySample>& a,
                                             const std::vector<BranchEnergySample>& b,
                                             double tolerance) {
  validate(a, "a");
  validate(b, "b");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw std::invalid_argument("energy_crossings: tolerance " + std::to_string(tolerance) +
                                " must be positive and finite");
  }
  const std::vector<Interval> ia = make_intervals(a);
  const std::vector<Interval> ib = make_intervals(b);

  // Sweep over lower ends: when an interval opens, every still-open interval of the other
  // branch overlaps it, and each overlapping pair is met exactly once this way.
  struct Event {
    double lo;
    int branch;
    std::size_t index;
  };
  std::vector<Event> events;
  events.reserve(ia.size() + ib.size());
  for (std::size_t i = 0; i < ia.size(); ++i) events.push_back({ia[i].lo, 0, i});
  for (std::size_t i = 0; i < ib.size(); ++i) events.push_back({ib[i].lo, 1, i});
  std::sort(events.begin(), events.end(), [](const Event& x, const Event& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.branch != y.branch ? x.branch < y.branch : x.index < y.index;
  });
  const std::vector<Interval>* lists[2] = {&ia, &ib};
  std::vector<std::size_t> open[2];
  std::vector<Candidate> candidates;
  for (const Event& e : events) {
    const int other = 1 - e.branch;
    const std::vector<Interval>& other_list = *lists[other];
    std::erase_if(open[other], [&](std::size_t j) { return other_list[j].hi < e.lo; });
    const Interval& mine = (*lists[e.branch])[e.index];
    for (std::size_t j : open[other]) {
      if (e.branch == 0) {
        pair_roots(mine, other_list[j], tolerance, candidates);
      } else {
        pair_roots(other_list[j], mine, tolerance, candidates);
      }
    }
    open[e.branch].push_back(e.index);
  }

  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    if (x.crossing.parameter != y.crossing.parameter) return x.crossing.parameter < y.crossing.parameter;
    if (x.crossing.segment_a != y.crossing.segment_a) return x.crossing.segment_a < y.crossing.segment_a;
    return x.crossing.segment_b < y.crossing.segment_b;
  });
  // A root at a shared sample is found from both adjacent intervals (each to within the
  // bisection tolerance); two roots on non-adjacent intervals are distinct crossings even at
  // the same lambda (two sheets of a folded branch).
  const double same_root = 4 * tolerance;
  std::vector<Candidate> kept;
  for (const Candidate& c : candidates) {
    bool duplicate = false;
    for (auto it = kept.rbegin(); it != kept.rend(); ++it) {
      if (c.crossing.parameter - it->crossing.parameter > same_root) break;
      const auto near = [](std::size_t x, std::size_t y) { return (x > y ? x - y : y - x) <= 1; };
      if (near(c.ordinal_a, it->ordinal_a) && near(c.ordinal_b, it->ordinal_b)) {
        duplicate = true;
        break;
      }
    }
    if (!duplicate) kept.push_back(c);
  }
  std::vector<EnergyCrossing> result;
  result.reserve(kept.size());
  for (const Candidate& c : kept) result.push_back(c.crossing);
  return result;
}

std::vector<BranchEnergySample> join_branch_samples(const std::vector<BranchEnergySample>& earlier,
                                                    const std::vector<BranchEnergySample>& later) {
  for (std::size_t i = 0; i < earlier.size(); ++i) {
    if (!std::isfinite(earlier[i].parameter))
      throw std::invalid_argument("join_branch_samples: earlier sample " + std::to_string(i) +
                                  " has a non-finite parameter");
    if (i > 0 && !(earlier[i].parameter > earlier[i - 1].parameter))
      throw std::invalid_argument("join_branch_samples: earlier sample " + std::to_string(i) +
                                  " does not increase the parameter");
  }
  if (later.empty()) return earlier;
  std::vector<BranchEnergySample> joined;
  joined.reserve(earlier.size() + later.size());
  for (const BranchEnergySample& s : earlier)
    if (s.parameter < later.front().parameter) joined.push_back(s);
  joined.insert(joined.end(), later.begin(), later.end());
  return joined;
}

}  // namespace growshell
