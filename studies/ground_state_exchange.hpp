#pragma once
/// \file
/// phi_e^crit by energy: the smallest excess angle from which a stable state of a second branch
/// (the skewed cone) has a lower energy than the first branch (the symmetric cone) at the same
/// phi_e. That happens in one of two ways:
///  - "energy_crossing": a stable part of the second branch crosses the first branch's energy;
///  - "stabilised_below": the second branch, already below the first one, turns stable (at a
///    branch point or a fold of its own): a lower state exists before, but it is a saddle;
///  - "lowest_sample": the second branch is stable and below the first at its lowest sample
///    compared (an upper bound only: trace it further down).
/// The energy crossing alone is not the exchange: a skewed saddle can lie below the symmetric
/// minimum without being a state the sheet can take.

#include <optional>
#include <string>
#include <vector>

namespace growshell {

/// One sample of a branch: its excess angle, its energy (J) and its negative count.
struct BranchStateSample {
  double phi_e = 0.0;
  double energy = 0.0;
  int negative = 0;
};

/// The energy of `branch` (sorted by increasing phi_e) at `phi`, linear between the samples
/// that bracket it; none outside its range.
std::optional<double> branch_energy_at(const std::vector<BranchStateSample>& branch, double phi);

/// Where the second branch takes over.
struct GroundStateExchange {
  double phi_e = 0.0;
  std::string criterion;  ///< "energy_crossing", "stabilised_below" or "lowest_sample"
};

/// The exchange between `first` (any order of phi_e; its energy interpolated linearly between
/// the samples bracketing a phi_e) and `second` (any order; sorted by phi_e here). `crossings`
/// are the accurate crossing parameters of the two branches (e.g. energy_crossings'): the one
/// nearest the linear estimate, within one sample interval of the interval where the sign
/// changes, replaces it. `second_special` are the phi_e of the second branch's special points;
/// one in the interval where the second branch turns stable gives where it does. Samples of
/// `second` outside the range of `first` are not compared. None if no stable sample of `second`
/// lies below `first`.
std::optional<GroundStateExchange> ground_state_exchange(std::vector<BranchStateSample> first,
                                                         std::vector<BranchStateSample> second,
                                                         const std::vector<double>& crossings,
                                                         const std::vector<double>& second_special);

}  // namespace growshell
