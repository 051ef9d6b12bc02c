#pragma once
/// \file
/// A penalty equilibrium as the warm start of a hard-contact solve. The penalty
/// (k / 2) sum_k (offset - d_k)_+^2 (libshell/contact/contact_penalty.hpp) balances the shell's
/// forces with the pair forces k (offset - d_k)_+; as k grows its equilibria tend to those of
/// the hard constraints d_k >= offset, and those pair forces to the constraints' KKT
/// multipliers. So a state traced with the penalty, re-solved under the hard constraints,
/// starts from its own contact forces rather than from Ipopt's generic multiplier estimate,
/// which on a folded cone is far from them: the Lagrangian Hessian of that estimate is strongly
/// indefinite, and the solve then crawls under inertia correction.

#include <Eigen/Core>

#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "solvers/contact/contact_equilibrium.hpp"

namespace growshell {

/// What solve_contact_equilibrium takes as `warm` from a penalty equilibrium x: `pairs` as
/// given (the penalty's pairs at x) and, per pair in ContactGapConstraints' order, the force
/// stiffness * max(0, offset - d_k(x)) (N); every other field is left at its default (the
/// warm start reads only pairs and forces). `offset` (m) and `stiffness` (N/m) are the
/// penalty's. Throws std::invalid_argument unless offset > 0 and stiffness >= 0 are finite,
/// and as ContactGapConstraints for bad pairs or x.
ContactSolveResult penalty_warm_start(const ContactProxy& proxy, const ContactCandidates& pairs,
                                      const Eigen::Ref<const Eigen::VectorXd>& x, double offset,
                                      double stiffness);

}  // namespace growshell
