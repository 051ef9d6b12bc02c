#pragma once
// The --symmetric-subspace option of trace_contact and crit_vs_h: the subspace of the disc's
// two mirrors for the symmetric branch, or none (with a note saying why) where the mesh lacks
// them (the annulus grid, a disc centred off the origin).

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "libshell/assembly/shell_model.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"

namespace growshell::examples {

inline std::shared_ptr<const SymmetricSubspace> mirror_subspace_option(const ShellModel& model,
                                                                       double radius, bool wanted) {
  if (!wanted) return nullptr;
  try {
    return std::make_shared<const SymmetricSubspace>(two_mirror_subspace(model, 1e-9 * radius));
  } catch (const std::invalid_argument& e) {
    std::printf("# the symmetric branch is traced in the full space: %s\n", e.what());
    return nullptr;
  }
}

}  // namespace growshell::examples
