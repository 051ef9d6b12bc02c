#pragma once
/// \file
/// The energy crossing of two branches (e.g. phi_e^crit of the symmetric and the skewed e-cone)
/// re-located under hard contact constraints. The branches are traced with the contact penalty
/// (contact_branch.hpp), which lets pairs sit slightly closer than the contact distance and
/// stores energy in the overlap. Here a few samples of each branch near the crossing are
/// re-solved with Ipopt (solve_contact_equilibrium: gap >= contact distance on the pairs it
/// selects) and the crossing of the re-solved elastic energies is located by energy_crossings.
///
/// Why a few samples suffice. The constraints do not depend on phi_e, so along a branch of
/// constrained minimisers x*(phi) the envelope theorem applied to the Lagrangian
/// L = E(x; phi) - lambda . g(x) gives dE(x*(phi); phi)/dphi = partial E / partial phi at fixed
/// x* (while the active set does not change). Each re-solved sample therefore carries its
/// energy and its exact slope, and the cubic Hermite interpolation of branch_crossing.hpp
/// applies, with its O(dphi^4) error: two samples per branch that bracket the crossing locate
/// it, and a third (a neighbour) gives the error estimate.
///
/// Each re-solve starts from the penalty state and is independent of the others.
///
/// Warm start. With penalty_stiffness set, each re-solve is warm started
/// (ConstrainedMinimizerOptions::warm_start): the multipliers are seeded with the penalty's
/// forces k (h - d)_+ on the vertex-triangle pairs within reach of the start (zero for those
/// not touching), so Ipopt begins with a small barrier parameter next to the penalty's
/// equilibrium instead of pushing every near pair's slack inside by bound_push. On the paper's
/// scene (h = 0.02, 24 rings) that made the re-solves of contact-free samples 15-40 times
/// faster and those in contact 1.3-2 times, and it found the same minimisers as cold starts
/// (energies equal to 1e-9 J).

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/continuation/branch_crossing.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// Settings of hard_contact_energy_crossing.
struct HardContactCrossingOptions {
  /// The Ipopt solve of each sample (contact distance, exclusion radius, pair selection,
  /// tolerances). Validated by solve_contact_equilibrium.
  ContactSolveOptions solve;
  /// Stiffness k of the penalty the samples were traced with (N/m, >= 0): their penalty
  /// forces seed Ipopt's multipliers (warm start, see the file comment); 0 = cold start.
  double penalty_stiffness = 0.0;
  /// Rigid-motion pins are re-chosen on each sample's state when the given ones hold the rigid
  /// motions with a condition above this (well_conditioned_pins; > 1).
  double max_pin_condition = 20.0;
  /// Contact zones of the re-solved states, for the angle gamma between their planes
  /// (contact_zones.hpp): link distance (m, > 0), the force fraction below which a pair is
  /// inactive (>= 0) and the largest normal angle within one zone (radians, in (0, pi/2]).
  double zone_link_distance = 0.1;
  double zone_active_fraction = 1e-3;
  double zone_max_normal_angle = 0.5235987755982988;  // pi / 6
  /// Half-width of the central difference for partial E / partial phi (radians, > 0;
  /// elastic_energy_slope).
  double slope_step = 1e-4;
  /// Consecutive converged re-solves of one branch whose branch_continuity_mismatch exceeds this
  /// (> 0) are reported in HardContactCrossing::message: one of them has probably relaxed onto
  /// another branch, and a crossing next to them is suspect.
  double max_branch_mismatch = 0.05;
  /// Root-finding tolerance of energy_crossings (parameter units, > 0).
  double crossing_tolerance = 1e-10;
};

/// One branch sample re-solved under hard constraints.
struct HardContactSample {
  double parameter = 0.0;     ///< phi_e (radians), the sample's
  bool converged = false;     ///< the Ipopt solve converged and its final gaps passed the check
  std::string message;        ///< solve_contact_equilibrium's message
  Eigen::VectorXd x;          ///< the re-solved state (the last iterate if not converged)
  double energy = 0.0;        ///< elastic (stretching + bending) energy at x (J)
  double energy_slope = 0.0;  ///< partial E / partial phi_e at fixed x (J per radian)
  /// Elastic energy of the given (penalty) state at the same phi_e (J).
  double start_energy = 0.0;
  double max_state_difference = 0.0;  ///< max |x - x_start| over the dofs (m)
  double min_distance = 0.0;          ///< smallest pair distance at x (m; +inf without pairs)
  /// Angle between the contact planes of the two largest zones (radians); NaN with fewer than
  /// two zones carrying force.
  double gamma = 0.0;
  int constrained_pairs = 0;  ///< pairs in the final solve's constraint set
  int active_pairs =
      0;  ///< of those, pairs whose force exceeds zone_active_fraction of the largest
  double total_force = 0.0;  ///< sum of the contact forces (N)
  int rounds = 0;            ///< solves of solve_contact_equilibrium
  int iterations = 0;        ///< Ipopt (or Newton) iterations over the rounds
  double seconds = 0.0;      ///< wall time of the re-solve (s)
};

/// Result of hard_contact_energy_crossing.
struct HardContactCrossing {
  std::vector<HardContactSample> a, b;  ///< the re-solved samples, in the order given
  /// Crossings of the Hermite-interpolated re-solved energies of a and b (energy_crossings on
  /// the converged samples, in order), sorted by parameter. Empty if a branch has fewer than
  /// two converged samples or the energies do not cross.
  std::vector<EnergyCrossing> crossings;
  /// Why there is no crossing, which samples failed, and which consecutive samples do not lie on
  /// one smooth branch (max_branch_mismatch); empty if none of these.
  std::string message;
};

/// Re-solves one branch sample (a state of `model` at sample.parameter, e.g. a penalty-traced
/// one) with Ipopt under the hard constraints, holding the six rigid-motion `pins` (re-chosen on
/// the state if their condition exceeds options.max_pin_condition), at sample.parameter. Throws std::invalid_argument for bad options or pins, or a state
/// that does not fit the model or is not finite.
HardContactSample resolve_with_hard_contact(const ShellModel& model, const ContactProxy& proxy,
                                            const BranchSample& sample,
                                            const std::vector<Eigen::Index>& pins,
                                            const HardContactCrossingOptions& options);

/// How far two re-solved samples of one branch are from lying on one smooth branch of
/// constrained minimisers: the mismatch of the trapezoidal rule,
///     |E_1 - E_0 - (s_0 + s_1) / 2 (phi_1 - phi_0)| / (max(|s_0|, |s_1|) |phi_1 - phi_0|),
/// with E the re-solved energies and s their slopes. Along one smooth branch the slopes are the
/// derivative of the energy (envelope theorem), so this is O(dphi^2) (the third derivative of E
/// times dphi^2 / 12, over the slope); a sample that relaxed onto another branch (e.g. a skewed
/// state that slid to the symmetric one where its constrained branch no longer exists) shows as
/// O(1). Throws std::invalid_argument if the two parameters are equal or a value is not finite.
double branch_continuity_mismatch(const HardContactSample& a, const HardContactSample& b);

/// The stretch of `samples` (converged re-solves following one branch in order, e.g. by
/// increasing phi_e) that lies on one smooth branch with samples[anchor]: the indices
/// [first, last] around anchor such that every consecutive pair inside has
/// branch_continuity_mismatch <= max_mismatch, extended outwards from anchor until the first
/// pair that does not. Samples beyond it have left the anchor's branch (or the branch ended
/// there). Throws std::invalid_argument if anchor is out of range or max_mismatch <= 0.
std::pair<std::size_t, std::size_t> continuous_stretch(
    const std::vector<HardContactSample>& samples, std::size_t anchor, double max_mismatch);

/// Progress callback: the branch ('a' or 'b'), the sample's index in its list and its result.
using HardContactSampleCallback =
    std::function<void(char branch, std::size_t index, const HardContactSample& sample)>;

/// Re-solves every sample of branches a and b (states of `model`, e.g. penalty-traced samples
/// on both sides of their crossing) with Ipopt at the sample's phi_e, holding the six
/// rigid-motion `pins` (re-chosen per state, see max_pin_condition), and locates the crossings
/// of the re-solved elastic energies. Samples within one list must follow their branch in
/// order (phi_e may not repeat). A failed solve is reported in its sample and left out of the
/// crossing. Throws std::invalid_argument for bad options, pins that are not six dofs, or a
/// sample whose state does not fit the model or is not finite, naming branch and index.
HardContactCrossing hard_contact_energy_crossing(const ShellModel& model, const ContactProxy& proxy,
                                                 const std::vector<BranchSample>& a,
                                                 const std::vector<BranchSample>& b,
                                                 const std::vector<Eigen::Index>& pins,
                                                 const HardContactCrossingOptions& options,
                                                 const HardContactSampleCallback& on_sample = {});

}  // namespace growshell
