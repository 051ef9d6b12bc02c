#pragma once
/// \file
/// Q^T H Q for a sparse symmetric H with a fixed pattern and a basis Q with at most one
/// nonzero in each row, as a symmetric subspace's orbit basis has (every dof lies in one orbit):
/// each stored entry of H then goes to one entry of the product with one factor, and the
/// projection is a single pass over H's values. A general sparse product Q^T H Q (a full
/// symmetric copy of H, two products, a scatter) took four times as long as the shell's whole
/// assembly at 7035 unknowns (docs/performance.md, "Assembly in the symmetric subspace").

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace growshell {

class SubspaceHessianProjection {
 public:
  /// `full_pattern`: the compressed upper triangle (row <= column) of H's structure, as
  /// ParametrizedObjective::hessian_pattern gives it; `basis`: Q, full_pattern.rows() x m.
  /// Throws std::invalid_argument if the pattern is not a compressed square upper triangle, if
  /// the sizes differ, or naming the first row of Q with more than one nonzero.
  SubspaceHessianProjection(const Eigen::SparseMatrix<double>& full_pattern,
                            const Eigen::SparseMatrix<double>& basis);

  /// Upper triangle of the structure of Q^T H Q: the entries (a, b) that some stored entry
  /// of H reaches (values: 1).
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }
  /// The full pattern given at construction: the structure project() takes.
  const Eigen::SparseMatrix<double>& full_pattern() const { return full_pattern_; }

  /// Writes the upper triangle of Q^T H Q into `projected` (given the structure of pattern()
  /// if it has another), from the upper triangle `full_upper` of H. Throws
  /// std::invalid_argument unless `full_upper` has exactly the structure of the full pattern
  /// given at construction.
  void project(const Eigen::SparseMatrix<double>& full_upper,
               Eigen::SparseMatrix<double>& projected) const;

 private:
  Eigen::SparseMatrix<double> full_pattern_;
  Eigen::SparseMatrix<double> pattern_;
  /// For each stored entry k of the full pattern: the position in pattern_'s values it adds
  /// to (-1: none, a row or column of H outside the subspace), and its factor q_i q_j (twice
  /// that for an off-diagonal entry of H that lands on the diagonal of the product, where the
  /// entry and its mirror image across the diagonal meet).
  std::vector<Eigen::Index> target_;
  std::vector<double> factor_;
};

}  // namespace growshell
