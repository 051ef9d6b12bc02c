#include "solvers/stability/symmetry_class_stability_index.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "solvers/newton/fixed_dof_elimination.hpp"
#include "solvers/stability/hessian_negative_count.hpp"
#include "solvers/stability/subspace_hessian_projection.hpp"
#include "solvers/stability/subspace_rigid_motions.hpp"
#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {

namespace {

std::string class_name(const std::vector<int>& character) {
  std::string name = "(";
  for (std::size_t k = 0; k < character.size(); ++k)
    name += std::string(k ? ", " : "") + (character[k] > 0 ? "+" : "-");
  return name + ")";
}

}  // namespace

/// One class: its basis, the projection of the full Hessian onto it, and the factorisation of
/// the block with the class's rigid motions pinned.
struct SymmetryClassStabilityIndex::ClassBlock {
  ClassBlock(const Eigen::SparseMatrix<double>& full_pattern, Eigen::SparseMatrix<double> q)
      : basis(std::move(q)), projection(full_pattern, basis), hessian(projection.pattern()) {
    if (basis.cols() > 0) factorization.analyze(hessian);
  }

  Eigen::SparseMatrix<double> basis;
  SubspaceHessianProjection projection;
  Eigen::SparseMatrix<double> hessian;  ///< the block of the last at(), pins eliminated
  SubspaceRigidMotions rigid;           ///< at the state of the last at()
  std::unique_ptr<FixedDofElimination> fixed;  ///< for rigid.pins
  std::vector<Eigen::Index> fixed_pins;
  SymmetricIndefiniteFactorization factorization;
};

SymmetryClassStabilityIndex::SymmetryClassStabilityIndex(const ParametrizedObjective& family,
                                                         const VertexSymmetryGroup& group)
    : family_(family), hessian_(family.hessian_pattern()) {
  if (family.dimension() != 3 * group.vertex_count())
    throw std::invalid_argument("SymmetryClassStabilityIndex: the family has " +
                                std::to_string(family.dimension()) + " unknowns, the group acts on " +
                                std::to_string(3 * group.vertex_count()));
  characters_ = group.splitting_characters();
  for (const std::vector<int>& character : characters_)
    blocks_.push_back(std::make_unique<ClassBlock>(hessian_, group.class_basis(character)));
  symmetric_basis_ = blocks_.front()->basis;
}

SymmetryClassStabilityIndex::~SymmetryClassStabilityIndex() = default;

std::vector<Eigen::Index> SymmetryClassStabilityIndex::class_dimensions() const {
  std::vector<Eigen::Index> out;
  for (const auto& block : blocks_) out.push_back(block->basis.cols());
  return out;
}

int SymmetryClassStabilityIndex::at(const Eigen::Ref<const Eigen::VectorXd>& x, double lambda) {
  if (x.size() != family_.dimension())
    throw std::invalid_argument("SymmetryClassStabilityIndex::at: the state has " +
                                std::to_string(x.size()) + " entries, expected " +
                                std::to_string(family_.dimension()));
  const Eigen::VectorXd symmetric_part =
      symmetric_basis_ * Eigen::VectorXd(symmetric_basis_.transpose() * x);
  const double off = (x - symmetric_part).lpNorm<Eigen::Infinity>();
  const double extent = std::max(1.0, x.lpNorm<Eigen::Infinity>());
  if (!(off <= 1e-9 * extent))
    throw std::invalid_argument("SymmetryClassStabilityIndex::at: the state is " +
                                std::to_string(off) +
                                " off the group's symmetric subspace: its Hessian is not "
                                "block-diagonal over the classes");
  class_negatives_.clear();
  family_.evaluate(x, lambda, nullptr, &hessian_);
  int total = 0;
  for (std::size_t c = 0; c < blocks_.size(); ++c) {
    ClassBlock& block = *blocks_[c];
    if (block.basis.cols() == 0) {
      class_negatives_.push_back(0);
      continue;
    }
    block.projection.project(hessian_, block.hessian);
    block.rigid = subspace_rigid_motions(block.basis, x);
    if (!block.fixed || block.fixed_pins != block.rigid.pins) {
      block.fixed = std::make_unique<FixedDofElimination>(block.hessian, block.rigid.pins);
      block.fixed_pins = block.rigid.pins;
    }
    block.fixed->apply(block.hessian);
    const Eigen::Map<const Eigen::VectorXd> values(block.hessian.valuePtr(),
                                                   block.hessian.nonZeros());
    const std::string name = class_name(characters_[c]);
    if (!values.allFinite())
      throw std::runtime_error("SymmetryClassStabilityIndex: the Hessian's block of class " +
                               name + " has non-finite entries");
    block.factorization.factorize(block.hessian);
    if (block.factorization.zero_pivots() > 0)
      throw std::runtime_error("SymmetryClassStabilityIndex: the Hessian's block of class " +
                               name + " is singular (zero pivot)");
    class_negatives_.push_back(block.factorization.negative_eigenvalues());
    total += class_negatives_.back();
  }
  return total;
}

int SymmetryClassStabilityIndex::negative_orthogonal_to(
    const Eigen::Ref<const Eigen::VectorXd>& direction) const {
  if (class_negatives_.empty())
    throw std::logic_error(
        "SymmetryClassStabilityIndex::negative_orthogonal_to: call at(x, lambda) first");
  if (direction.size() != family_.dimension())
    throw std::invalid_argument("SymmetryClassStabilityIndex::negative_orthogonal_to: the "
                                "direction has " + std::to_string(direction.size()) +
                                " entries, expected " + std::to_string(family_.dimension()));
  if (!direction.allFinite())
    throw std::invalid_argument(
        "SymmetryClassStabilityIndex::negative_orthogonal_to: the direction is not finite");
  // The class that holds the direction, and the size of its parts in the others.
  std::size_t holder = 0;
  std::vector<Eigen::VectorXd> parts;
  for (std::size_t c = 0; c < blocks_.size(); ++c) {
    parts.push_back(blocks_[c]->basis.transpose() * direction);
    if (parts[c].norm() > parts[holder].norm()) holder = c;
  }
  for (std::size_t c = 0; c < blocks_.size(); ++c)
    if (c != holder && parts[c].norm() > 1e-6 * parts[holder].norm())
      throw std::invalid_argument(
          "SymmetryClassStabilityIndex::negative_orthogonal_to: the direction has parts in "
          "classes " + class_name(characters_[holder]) + " and " + class_name(characters_[c]) +
          ": the count orthogonal to it is not one class's");
  const ClassBlock& block = *blocks_[holder];
  Eigen::VectorXd d = parts[holder];
  // Move d by the class's rigid motions (null directions of the block at an equilibrium) so
  // that it vanishes at the pins, then drop the pinned entries.
  const Eigen::Index k = static_cast<Eigen::Index>(block.rigid.pins.size());
  if (k > 0) {
    Eigen::MatrixXd at_pins(k, k);
    Eigen::VectorXd d_at_pins(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      at_pins.row(i) = block.rigid.motions.row(block.rigid.pins[static_cast<std::size_t>(i)]);
      d_at_pins(i) = d(block.rigid.pins[static_cast<std::size_t>(i)]);
    }
    d -= block.rigid.motions * at_pins.partialPivLu().solve(d_at_pins);
  }
  const double schur = inverse_quadratic_form(
      *block.fixed, block.factorization, d, "SymmetryClassStabilityIndex::negative_orthogonal_to");
  int total = 0;
  for (const int n : class_negatives_) total += n;
  return schur < 0.0 ? total - 1 : total;
}

}  // namespace growshell
