#pragma once
/// \file
/// Pseudo-arclength continuation with one linear phase condition c . x = c . x0, with full
/// states in and out: the branch through (x0, lambda0) is followed on the hyperplane, the
/// force along c taken up by a Lagrange multiplier (PhaseConditionedFamily). Used where a
/// nearly neutral direction that the discretisation alone makes stiff or soft (the turn of a
/// fold pattern over a mesh without the pattern's rotational symmetry) must not steer the
/// branch. Background: docs/continuation.md, "Phase condition".

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// As trace_branch_along on `family`, with the state held on c . x = c . x0 (`functional` c,
/// one entry per unknown, not all zero). Internally the unknowns are (x, mu), mu the
/// multiplier of the unit functional c/|c|; every sample, special point and event (and the
/// result's states and tangents) is handed back as the state x alone, and event test
/// functions see such samples too. The multiplier of a sample can be recovered from the
/// gradient of `family` there (phase_multiplier). The samples' negative count is
/// options.stability_index of the state if set, else the negative count of the Hessian with
/// `fixed_dofs` held, restricted to the hyperplane c . dx = 0, from the inertia of the bordered
/// Hessian (one more LDL^T per corrected point; defined also where the Hessian is singular
/// along an exact symmetry orbit). Throws std::invalid_argument for a functional of the wrong
/// size, not finite or vanishing, or a direction of the wrong size, and as trace_branch_along.
BranchTrace trace_branch_with_phase_condition(
    const ParametrizedObjective& family, const Eigen::Ref<const Eigen::VectorXd>& functional,
    const Eigen::Ref<const Eigen::VectorXd>& x0, double lambda0,
    const Eigen::Ref<const Eigen::VectorXd>& direction_state, double direction_parameter,
    const std::vector<Eigen::Index>& fixed_dofs, const ArclengthOptions& options,
    const std::function<void(const BranchSample&)>& on_sample = {},
    const std::function<void(const SpecialPoint&)>& on_special = {},
    const std::vector<BranchEvent>& events = {},
    const std::function<void(const LocatedEvent&)>& on_event = {});

}  // namespace growshell
