#include "studies/cone_mirror_subspace.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell {

ConeSubspaceChoice cone_mirror_subspace(const ShellModel& model, double radius, int folds) {
  try {
    const std::vector<int> axes = folds % 2 == 0 ? std::vector<int>{0, 1} : std::vector<int>{1};
    return {std::make_shared<const SymmetricSubspace>(mirror_subspace(model, axes, 1e-9 * radius)),
            ""};
  } catch (const std::invalid_argument& e) {
    return {nullptr, std::string("the symmetric branch is traced in the full space: ") + e.what()};
  }
}

ConeSubspaceChoice cone_half_turn_subspace(const ShellModel& model, double radius,
                                           const std::string& branch) {
  try {
    return {std::make_shared<const SymmetricSubspace>(half_turn_subspace(model, 1e-9 * radius)),
            ""};
  } catch (const std::invalid_argument& e) {
    return {nullptr, branch + " is traced in the full space: " + e.what()};
  }
}

ConeSubspaceChoice subspace_for_start(std::shared_ptr<const SymmetricSubspace> subspace,
                                      const Eigen::Ref<const Eigen::VectorXd>& x,
                                      double max_asymmetry, const std::string& branch) {
  if (!subspace) return {nullptr, ""};
  std::string note = subspace_start_mismatch(*subspace, x, max_asymmetry, branch);
  if (note.empty()) return {std::move(subspace), ""};
  return {nullptr, note + "; e.g. a fold pattern turned against the mesh"};
}

}  // namespace growshell
