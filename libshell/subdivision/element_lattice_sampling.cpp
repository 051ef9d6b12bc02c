#include "libshell/subdivision/element_lattice_sampling.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "libshell/subdivision/loop_patch.hpp"

namespace growshell {

ElementLatticeSampling::ElementLatticeSampling(
    const ElementPatches& patches, const Eigen::Ref<const Eigen::MatrixX3d>& reference_control, int n)
    : n_(n),
      num_elements_(static_cast<Eigen::Index>(patches.patch.size())),
      num_vertices_(reference_control.rows()) {
  const Eigen::Index num_vertices = num_vertices_;
  if (n < 1)
    throw std::invalid_argument("ElementLatticeSampling: n = " + std::to_string(n) +
                                " subdivisions per edge must be >= 1");
  std::vector<Eigen::Triplet<double>> entries;
  std::size_t nodes = 0;
  for (const LoopPatch& patch : patches.patch) nodes += patch.control.size();
  entries.reserve(nodes * static_cast<std::size_t>(points_per_element()));
  for (Eigen::Index e = 0; e < num_elements_; ++e) {
    const LoopPatch& patch = patches.patch[static_cast<std::size_t>(e)];
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n - i; ++j) {
        const Eigen::VectorXd value =
            evaluate_patch_basis(patch, static_cast<double>(i) / n, static_cast<double>(j) / n).value;
        for (int k = 0; k < patch.size(); ++k) {
          const int vertex = patch.control[static_cast<std::size_t>(k)];
          if (vertex < 0 || vertex >= num_vertices)
            throw std::invalid_argument("ElementLatticeSampling: element " + std::to_string(e) +
                                        " refers to vertex " + std::to_string(vertex) + " of " +
                                        std::to_string(num_vertices));
          if (value(k) != 0.0) entries.emplace_back(row(e, i, j), vertex, value(k));
        }
      }
    }
  }
  basis_.resize(num_elements_ * points_per_element(), num_vertices);
  basis_.setFromTriplets(entries.begin(), entries.end());
  reference_ = basis_ * reference_control;
}

Eigen::MatrixX3d ElementLatticeSampling::positions(const Eigen::Ref<const Eigen::MatrixX3d>& control) const {
  if (control.rows() != num_vertices_)
    throw std::invalid_argument("ElementLatticeSampling::positions: " + std::to_string(control.rows()) +
                                " control points for a mesh of " + std::to_string(num_vertices_));
  return basis_ * control;
}

Eigen::MatrixX3d ElementLatticeSampling::state_positions(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  if (x.size() != 3 * num_vertices_)
    throw std::invalid_argument("ElementLatticeSampling::state_positions: a state of " +
                                std::to_string(x.size()) + " entries for a mesh of " +
                                std::to_string(num_vertices_) + " control points");
  return basis_ * Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
                      x.data(), num_vertices_, 3);
}

}  // namespace growshell
