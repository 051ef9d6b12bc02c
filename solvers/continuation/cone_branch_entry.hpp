#pragma once
/// \file
/// Entering the n-fold e-cone branch from the flat disc: the flat branch is followed up to the
/// branch point whose critical mode has n folds around the axis, and the cone branch is entered
/// along that mode's mirror-symmetric member.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/parametrized_objective.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// Out-of-plane field r^n cos(n theta) about the origin of the reference plane: the member of
/// the degenerate n-fold pair that is mirror-symmetric about the x-axis.
Eigen::VectorXd fold_mode_hint(const ShellModel& model, int folds);

/// Dominant angular wavenumber k in [2, 8] of the out-of-plane part of `mode` on the outer rim
/// (k = 1 is the tilt that rigid-motion pins add to every mode).
int rim_angular_wavenumber(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& mode);

struct ConeEntryOptions {
  int folds = 2;  ///< n of the cone to enter (the n-th pair of modes goes unstable at the (n-1)-th
                  ///< branch point)
  double phi_start = 0.0;  ///< excess angle of the flat start
  double thickness =
      0.0;  ///< h (m): steps and location tolerances on the flat branch scale with (h/R)^2
  double radius = 0.0;  ///< R (m)
};

struct ConeBranchEntry {
  bool found = false;
  std::string message;        ///< why no entry was found
  SpecialPoint branch_point;  ///< on the flat branch
  Eigen::VectorXd mode;       ///< critical mode there (unit weighted norm, fixed dofs zero)
  double switch_step = 0.0;  ///< how far `start` is from the branch point along `mode`
  Eigen::VectorXd start;  ///< branch_point.x stepped off along the mode by switch_step: hand to
                          ///< leave_branch_point, or to trace_branch_along with `mode` as direction
  BranchTrace flat;       ///< the flat branch up to the branch point (its cost included)
};

/// Traces the flat branch of `family` (starting at the model's reference positions) through
/// its first folds - 1 branch points and picks the one whose critical mode has `folds` folds.
/// The flat disc buckles at phi_c = 10.6 (h/R)^2 (n = 2) and 21.1 (h/R)^2 (n = 3), so the flat
/// branch's steps and location tolerance are those of `cone_options` scaled down to (h/R)^2:
/// thin sheets (h = 0.001: phi_c = 1e-5) do not pass several branch points in one step. The
/// step off the branch is 0.005 (times h / 0.005 R for thinner sheets, whose cone amplitude
/// near threshold is smaller), so the corrector converges onto the cone. Special points of the
/// flat branch go to on_special. Throws std::invalid_argument for folds < 2 or h, R <= 0.
ConeBranchEntry enter_cone_branch(const ParametrizedObjective& family, const ShellModel& model,
                                  const ConeEntryOptions& entry,
                                  const std::vector<Eigen::Index>& fixed_dofs,
                                  const ArclengthOptions& cone_options,
                                  const std::function<void(const SpecialPoint&)>& on_special = {});

/// How the cone was entered by leave_branch_point.
struct BranchPointDeparture {
  BranchTrace trace;         ///< of the last attempt, with the cost of all attempts
  double switch_step = 0.0;  ///< the step off the branch point of the last attempt
  int attempts = 0;          ///< 1 if the first start converged
};

/// Traces the cone out of `entry`'s branch point: calls trace(start, mode) with the start
/// branch_point.x + s mode for s = entry.switch_step, and, while the corrector cannot converge
/// at that start (trace.start_converged false), again with half the previous s, at most
/// max_attempts times in all. The step off is a guess of the cone's amplitude: too large and
/// Newton on the bordered system leaves its basin (measured on the Gmsh disc at h = 0.005, where
/// the first step overshoots phi_e by 35 times the branch point's value and diverges), too
/// small and the pair's near-neutral partner slows it; halving keeps the first guess wherever
/// it works. `trace` is the caller's tracer (full space or a subspace), so its samples and
/// events go where the caller sends them; a failed attempt emits none. Throws
/// std::invalid_argument if entry.found is false or max_attempts < 1.
BranchPointDeparture leave_branch_point(
    const ConeBranchEntry& entry,
    const std::function<BranchTrace(const Eigen::VectorXd& start, const Eigen::VectorXd& mode)>&
        trace,
    int max_attempts = 4);

}  // namespace growshell
