#include "solvers/stability/mode_symmetry_class.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace growshell {

bool ModeSymmetryClass::trivial() const { return odd_generator() < 0; }

int ModeSymmetryClass::odd_generator() const {
  for (std::size_t s = 0; s < generator_signs.size(); ++s)
    if (generator_signs[s] < 0) return static_cast<int>(s);
  return -1;
}

ModeSymmetryClass mode_symmetry_class(const VertexSymmetryGroup& group,
                                      const Eigen::Ref<const Eigen::VectorXd>& v) {
  if (!group.classes_split_space())
    throw std::invalid_argument(
        "mode_symmetry_class: the group's classes do not split the space (it is not a group of "
        "commuting involutions)");
  if (v.size() != 3 * group.vertex_count())
    throw std::invalid_argument("mode_symmetry_class: the vector has " + std::to_string(v.size()) +
                                " entries, the group acts on " +
                                std::to_string(3 * group.vertex_count()));
  const double norm2 = v.squaredNorm();
  if (!(norm2 > 0.0) || !std::isfinite(norm2))
    throw std::invalid_argument("mode_symmetry_class: the vector is zero or not finite");
  ModeSymmetryClass best;
  best.weight = -1.0;
  for (const std::vector<int>& character : group.splitting_characters()) {
    const Eigen::SparseMatrix<double> basis = group.class_basis(character);
    const double weight = (basis.transpose() * v).squaredNorm() / norm2;
    if (weight > best.weight) {
      best.generator_signs = character;
      best.weight = weight;
    }
  }
  return best;
}

}  // namespace growshell
