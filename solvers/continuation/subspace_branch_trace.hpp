#pragma once
/// \file
/// Pseudo-arclength continuation restricted to a symmetric subspace, with full states in and
/// out: the branch through a symmetric equilibrium is followed among the symmetric states
/// only (SymmetricSubspaceFamily), so it passes the branch points where it loses stability to
/// symmetry-breaking modes however the steps fall, while its stability index stays the full
/// Hessian's. Background: docs/continuation.md, "Symmetric subspace".

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"

namespace growshell {

/// As trace_branch_along, for a start (x0, lambda0) that has the subspace's symmetry up to a
/// rigid motion. The start is turned into the subspace's frame (aligning_motion) and projected;
/// the trace runs on the restricted family with the subspace's rigid-motion pins and an
/// arclength weight rescaled so that a step measures the same change of the full state. Every
/// sample, special point and event (and the result's states) is handed back as a full state in
/// the caller's frame; event test functions see such samples too. The samples' negative count
/// is options.stability_index of the full sample (which also carries its reduced_x and
/// reduced_frame) if set, else the negative count of the full Hessian without its rigid
/// motions: class by class (SymmetryClassStabilityIndex, at the expanded state in the
/// subspace's frame) where the subspace's group splits the space, else with `fixed_dofs` held
/// (one more assembly and factorisation per corrected point either way; cost in
/// TraceCost::stability_*). Throws std::invalid_argument if the subspace is for another
/// dimension, and as trace_branch_along and SymmetricSubspace::aligning_motion.
BranchTrace trace_branch_in_subspace(
    const ParametrizedObjective& family, const SymmetricSubspace& subspace,
    const Eigen::Ref<const Eigen::VectorXd>& x0, double lambda0,
    const Eigen::Ref<const Eigen::VectorXd>& direction_state, double direction_parameter,
    const std::vector<Eigen::Index>& fixed_dofs, const ArclengthOptions& options,
    const std::function<void(const BranchSample&)>& on_sample = {},
    const std::function<void(const SpecialPoint&)>& on_special = {},
    const std::vector<BranchEvent>& events = {},
    const std::function<void(const LocatedEvent&)>& on_event = {});

/// As trace_branch_in_subspace from start.x, for a sample an earlier trace in the same
/// subspace handed back: where the sample keeps its reduced coordinates (reduced_x of the
/// subspace's dimension, with reduced_frame^-1(Q reduced_x) equal to start.x bit for bit) the
/// trace starts from them in that frame, so that with start.next_step as the initial step it
/// takes the same steps, to the last bit, as the trace that wrote the sample. Otherwise (a
/// full-space sample, another subspace, a state changed since) it projects start.x as
/// trace_branch_in_subspace does. `reduced_start_used`, if given, tells which.
BranchTrace resume_branch_in_subspace(
    const ParametrizedObjective& family, const SymmetricSubspace& subspace,
    const BranchSample& start, const Eigen::Ref<const Eigen::VectorXd>& direction_state,
    double direction_parameter, const std::vector<Eigen::Index>& fixed_dofs,
    const ArclengthOptions& options,
    const std::function<void(const BranchSample&)>& on_sample = {},
    const std::function<void(const SpecialPoint&)>& on_special = {},
    const std::vector<BranchEvent>& events = {},
    const std::function<void(const LocatedEvent&)>& on_event = {},
    bool* reduced_start_used = nullptr);

}  // namespace growshell
