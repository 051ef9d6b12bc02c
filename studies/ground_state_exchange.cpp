#include "studies/ground_state_exchange.hpp"

#include <algorithm>
#include <cmath>

namespace growshell {
namespace {

bool by_phi(const BranchStateSample& a, const BranchStateSample& b) { return a.phi_e < b.phi_e; }

/// The first value of `candidates` in [lo, hi], if any.
std::optional<double> first_in(const std::vector<double>& candidates, double lo, double hi) {
  std::optional<double> best;
  for (double c : candidates)
    if (c >= lo && c <= hi && (!best || c < *best)) best = c;
  return best;
}

/// The accurate crossing nearest the linear estimate `linear` of the sign change in [lo, hi],
/// if one lies within one interval width of that interval: the linear interpolation of the
/// first branch's energy can place the sign change an interval away from the true crossing.
std::optional<double> crossing_near(const std::vector<double>& crossings, double linear, double lo,
                                    double hi) {
  const double width = hi - lo;
  std::optional<double> best;
  for (double c : crossings)
    if (c >= lo - width && c <= hi + width &&
        (!best || std::abs(c - linear) < std::abs(*best - linear)))
      best = c;
  return best;
}

}  // namespace

std::optional<double> branch_energy_at(const std::vector<BranchStateSample>& branch, double phi) {
  for (std::size_t k = 0; k + 1 < branch.size(); ++k) {
    const BranchStateSample& a = branch[k];
    const BranchStateSample& b = branch[k + 1];
    if (a.phi_e <= phi && phi <= b.phi_e) {
      if (b.phi_e == a.phi_e) return a.energy;
      return a.energy + (phi - a.phi_e) / (b.phi_e - a.phi_e) * (b.energy - a.energy);
    }
  }
  return std::nullopt;
}

std::optional<GroundStateExchange> ground_state_exchange(
    std::vector<BranchStateSample> first, std::vector<BranchStateSample> second,
    const std::vector<double>& crossings, const std::vector<double>& second_special) {
  std::sort(first.begin(), first.end(), by_phi);
  std::sort(second.begin(), second.end(), by_phi);
  std::optional<double> previous_gap;  // second - first at the previous compared sample
  bool previous_stable = false;
  double previous_phi = 0.0;
  for (const BranchStateSample& s : second) {
    const std::optional<double> reference = branch_energy_at(first, s.phi_e);
    if (!reference) continue;
    const double gap = s.energy - *reference;
    const bool stable = s.negative == 0;
    if (stable && gap < 0.0) {
      if (!previous_gap) return GroundStateExchange{s.phi_e, "lowest_sample"};
      if (*previous_gap >= 0.0 && previous_stable) {
        // A crossing within the interval: the accurate one if given, else linear.
        const double linear =
            previous_phi + *previous_gap / (*previous_gap - gap) * (s.phi_e - previous_phi);
        return GroundStateExchange{
            crossing_near(crossings, linear, previous_phi, s.phi_e).value_or(linear),
            "energy_crossing"};
      }
      if (*previous_gap >= 0.0) {
        // Both happen within one interval: the later of the crossing and the stability change.
        const double linear =
            previous_phi + *previous_gap / (*previous_gap - gap) * (s.phi_e - previous_phi);
        const double crossing =
            crossing_near(crossings, linear, previous_phi, s.phi_e).value_or(linear);
        const double turn = first_in(second_special, previous_phi, s.phi_e).value_or(s.phi_e);
        return crossing >= turn ? GroundStateExchange{crossing, "energy_crossing"}
                                : GroundStateExchange{turn, "stabilised_below"};
      }
      // Below the first branch before and after: the second branch turned stable here.
      return GroundStateExchange{first_in(second_special, previous_phi, s.phi_e).value_or(s.phi_e),
                                 "stabilised_below"};
    }
    previous_gap = gap;
    previous_stable = stable;
    previous_phi = s.phi_e;
  }
  return std::nullopt;
}

}  // namespace growshell
