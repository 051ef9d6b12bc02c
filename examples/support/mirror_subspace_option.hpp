#pragma once
// The --symmetric-subspace option of trace_contact, crit_vs_h and trace_disc: the subspace of
// the mirrors an n-fold cone with a fold on the x-axis keeps (y -> -y, and x -> -x for even
// n), or none, with a note saying why, where the mesh lacks them (the annulus grid, a disc
// centred off the origin).

#include <Eigen/Core>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"

namespace growshell::examples {

inline std::shared_ptr<const SymmetricSubspace> mirror_subspace_option(const ShellModel& model,
                                                                       double radius, bool wanted,
                                                                       int folds = 2) {
  if (!wanted) return nullptr;
  try {
    const std::vector<int> axes = folds % 2 == 0 ? std::vector<int>{0, 1} : std::vector<int>{1};
    return std::make_shared<const SymmetricSubspace>(mirror_subspace(model, axes, 1e-9 * radius));
  } catch (const std::invalid_argument& e) {
    std::printf("# the symmetric branch is traced in the full space: %s\n", e.what());
    return nullptr;
  }
}

/// `subspace` if the start state x has its symmetry up to `max_asymmetry` (m) in some frame,
/// else none, with a note: e.g. a cone grown in natural steps, whose fold pattern has crept
/// round against the mesh.
inline std::shared_ptr<const SymmetricSubspace> subspace_for_start(
    std::shared_ptr<const SymmetricSubspace> subspace, const Eigen::VectorXd& x,
    double max_asymmetry) {
  if (!subspace) return nullptr;
  const double asymmetry = subspace->aligned_asymmetry(x);
  if (asymmetry <= max_asymmetry) return subspace;
  std::printf(
      "# the symmetric branch is traced in the full space: its start is %.3g m off its mirror "
      "image in every frame (more than %.3g m; e.g. a fold pattern turned against the mesh)\n",
      asymmetry, max_asymmetry);
  return nullptr;
}

}  // namespace growshell::examples
