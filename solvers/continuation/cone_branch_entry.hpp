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
  Eigen::VectorXd start;  ///< branch_point.x stepped off along the mode: hand to trace_branch_along
                          ///< with `mode` as direction
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
ConeBranchEntry enter_cone_branch(ParametrizedObjective& family, const ShellModel& model,
                                  const ConeEntryOptions& entry,
                                  const std::vector<Eigen::Index>& fixed_dofs,
                                  const ArclengthOptions& cone_options,
                                  const std::function<void(const SpecialPoint&)>& on_special = {});

}  // namespace growshell
