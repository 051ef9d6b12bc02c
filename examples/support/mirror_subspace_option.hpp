#pragma once
// The --symmetric-subspace option of trace_contact and crit_vs_h: the subspace of the mirrors
// an n-fold cone with a fold on the x-axis keeps (y -> -y, and x -> -x for even n), or none,
// with a note on stdout saying why, where the mesh lacks them (the annulus grid, a disc
// centred off the origin). The choice is the library's (studies/cone_mirror_subspace.hpp).

#include <Eigen/Core>
#include <cstdio>
#include <memory>
#include <utility>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "studies/cone_mirror_subspace.hpp"

namespace growshell::examples {

inline std::shared_ptr<const SymmetricSubspace> mirror_subspace_option(const ShellModel& model,
                                                                       double radius, bool wanted,
                                                                       int folds = 2) {
  if (!wanted) return nullptr;
  ConeSubspaceChoice choice = cone_mirror_subspace(model, radius, folds);
  if (!choice.note.empty()) std::printf("# %s\n", choice.note.c_str());
  return choice.subspace;
}

/// `subspace` if the start state x has its symmetry up to `max_asymmetry` (m) in some frame,
/// else none, with a note: e.g. a cone grown in natural steps, whose fold pattern has crept
/// round against the mesh.
inline std::shared_ptr<const SymmetricSubspace> subspace_for_start(
    std::shared_ptr<const SymmetricSubspace> subspace, const Eigen::VectorXd& x,
    double max_asymmetry) {
  ConeSubspaceChoice choice = growshell::subspace_for_start(std::move(subspace), x, max_asymmetry);
  if (!choice.note.empty()) std::printf("# %s\n", choice.note.c_str());
  return choice.subspace;
}

}  // namespace growshell::examples
