#pragma once
/// \file
/// One equilibrium of a growing shell with self-contact: min E(x) subject to gap >= contact
/// distance for every pair of non-neighbouring parts of the sheet, solved with Ipopt on the
/// pairs that are near, with the pair set rebuilt and the solve repeated until no other pair
/// comes closer than allowed. A state far from touching pays only the broad phase.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "solvers/contact/constrained_minimizer.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// Settings of solve_contact_equilibrium. Lengths in metres.
struct ContactSolveOptions {
  /// Mid-surface distance at which two parts touch (> 0), e.g. the thickness h.
  double contact_distance = 0.0;
  /// Pairs closer than this in the reference are neighbours, never contact (> 0; the scene
  /// default is 8 h, docs/contact.md).
  double exclusion_radius = 0.0;
  /// Pairs closer than contact_distance + candidate_margin at the start of a solve become
  /// constraints (> 0). It bounds how far two parts may approach during one solve without
  /// being seen; a pair that still ends closer than allowed triggers another round.
  double candidate_margin = 0.0;
  /// Which pairs become constraints. The paper used point-triangle pairs only; with both
  /// sheets' vertices tested against the other's triangles that suffices for smooth sheets
  /// sliding on each other, while edge-edge pairs matter where edges cross at an angle. Each
  /// pair costs a dense block of about (4 x 7 x 3)^2 entries in the Lagrangian Hessian, so
  /// the defaults keep the set small: no edge-edge pairs, and per vertex only its nearest
  /// triangle.
  bool edge_edge_pairs = false;
  bool nearest_triangle_only = true;
  /// Largest number of solves with an enlarged pair set (>= 1).
  int max_rounds = 4;
  /// Accepted violation of the final gaps (m, >= 0): every pair ends at distance >=
  /// contact_distance - violation_tolerance.
  double violation_tolerance = 0.0;
  ContactGapOptions gap;
  ConstrainedMinimizerOptions minimizer;
  /// Used instead of Ipopt when no pair is near (the no-contact fast path).
  NewtonOptions newton;
};

/// Result of solve_contact_equilibrium. `x` is always a finite state: the solution if
/// converged, otherwise the last state of the last solve that produced one (or x0).
struct ContactSolveResult {
  bool converged = false;
  std::string message;
  Eigen::VectorXd x;
  /// The constrained pairs of the final solve (empty if no pair was near).
  ContactCandidates pairs;
  /// KKT multiplier of each pair's constraint (N, >= 0), in the order of
  /// ContactGapConstraints (vertex-triangle pairs, then edge-edge pairs). It is the pair's
  /// contact force, except for a mollified edge-edge pair, whose force is multiplier x
  /// mollifier (contact_zones accounts for that).
  Eigen::VectorXd forces;
  /// Smallest distance at x over the constrained pairs and every pair (edge-edge included)
  /// closer than contact_distance - violation_tolerance (m); +infinity if there is none.
  double min_distance = 0.0;
  int rounds = 0;           ///< solves done (Newton or Ipopt)
  int iterations = 0;       ///< Newton or Ipopt iterations, summed over the rounds
  bool used_contact = false;  ///< false if the no-contact fast path sufficed
};

/// Minimises the model's energy at the excess angle phi_e (radians) from x0 (which should satisfy the
/// gaps: Ipopt keeps the interior-point iterates feasible only from a feasible start) with
/// `fixed_dofs` held. `warm` (optional): a previous result whose forces seed the multipliers
/// of the pairs it shares with this solve. Throws std::invalid_argument for bad options.
ContactSolveResult solve_contact_equilibrium(const ShellModel& model, double excess_angle,
                                             const ContactProxy& proxy,
                                             const Eigen::Ref<const Eigen::VectorXd>& x0,
                                             const std::vector<Eigen::Index>& fixed_dofs,
                                             const ContactSolveOptions& options,
                                             const ContactSolveResult* warm = nullptr);

}  // namespace growshell
