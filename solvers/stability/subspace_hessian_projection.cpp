#include "solvers/stability/subspace_hessian_projection.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace growshell {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

bool same_structure(const Sparse& a, const Sparse& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros() ||
      !a.isCompressed() || !b.isCompressed())
    return false;
  const auto outer_bytes = static_cast<std::size_t>(a.outerSize() + 1) * sizeof(int);
  const auto inner_bytes = static_cast<std::size_t>(a.nonZeros()) * sizeof(int);
  return std::memcmp(a.outerIndexPtr(), b.outerIndexPtr(), outer_bytes) == 0 &&
         std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), inner_bytes) == 0;
}

/// Position of (row, column) among the stored entries of the compressed `m`.
Eigen::Index position_of(const Sparse& m, Eigen::Index row, Eigen::Index column) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[column];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[column + 1];
  const int* hit = std::lower_bound(begin, end, static_cast<int>(row));
  return hit - m.innerIndexPtr();
}

}  // namespace

SubspaceHessianProjection::SubspaceHessianProjection(const Sparse& full_pattern,
                                                     const Sparse& basis) {
  const Eigen::Index n = full_pattern.rows();
  if (full_pattern.cols() != n || !full_pattern.isCompressed())
    throw std::invalid_argument(
        "SubspaceHessianProjection: the Hessian pattern must be square and compressed");
  if (basis.rows() != n)
    throw std::invalid_argument("SubspaceHessianProjection: the basis has " +
                                std::to_string(basis.rows()) + " rows, the Hessian " +
                                std::to_string(n));
  std::vector<Eigen::Index> column_of(static_cast<std::size_t>(n), -1);
  std::vector<double> coefficient_of(static_cast<std::size_t>(n), 0.0);
  for (Eigen::Index j = 0; j < basis.outerSize(); ++j)
    for (Sparse::InnerIterator it(basis, j); it; ++it) {
      if (it.value() == 0.0) continue;
      const auto i = static_cast<std::size_t>(it.row());
      if (column_of[i] >= 0)
        throw std::invalid_argument("SubspaceHessianProjection: row " + std::to_string(it.row()) +
                                    " of the basis has more than one nonzero");
      column_of[i] = j;
      coefficient_of[i] = it.value();
    }

  // Where each stored entry of H goes, then the product's structure from those targets.
  const auto stored = static_cast<std::size_t>(full_pattern.nonZeros());
  std::vector<Eigen::Index> row_to(stored, -1), column_to(stored, -1);
  factor_.assign(stored, 0.0);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(stored);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index k = full_pattern.outerIndexPtr()[j];
         k < full_pattern.outerIndexPtr()[j + 1]; ++k) {
      const Eigen::Index i = full_pattern.innerIndexPtr()[k];
      if (i > j)
        throw std::invalid_argument(
            "SubspaceHessianProjection: the Hessian pattern has an entry below the diagonal");
      const Eigen::Index a = column_of[static_cast<std::size_t>(i)];
      const Eigen::Index b = column_of[static_cast<std::size_t>(j)];
      if (a < 0 || b < 0) continue;
      const auto s = static_cast<std::size_t>(k);
      row_to[s] = std::min(a, b);
      column_to[s] = std::max(a, b);
      factor_[s] = coefficient_of[static_cast<std::size_t>(i)] *
                   coefficient_of[static_cast<std::size_t>(j)] * (i != j && a == b ? 2.0 : 1.0);
      entries.emplace_back(row_to[s], column_to[s], 1.0);
    }
  pattern_.resize(basis.cols(), basis.cols());
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + pattern_.nonZeros(), 1.0);

  target_.assign(stored, -1);
  for (std::size_t s = 0; s < stored; ++s)
    if (row_to[s] >= 0) target_[s] = position_of(pattern_, row_to[s], column_to[s]);
  full_pattern_ = full_pattern;
}

void SubspaceHessianProjection::project(const Sparse& full_upper, Sparse& projected) const {
  if (!same_structure(full_upper, full_pattern_))
    throw std::invalid_argument(
        "SubspaceHessianProjection::project: the Hessian does not carry the pattern the "
        "projection was built for");
  if (!same_structure(projected, pattern_)) projected = pattern_;
  double* out = projected.valuePtr();
  std::fill(out, out + projected.nonZeros(), 0.0);
  const double* values = full_upper.valuePtr();
  const std::size_t stored = target_.size();
  for (std::size_t s = 0; s < stored; ++s)
    if (target_[s] >= 0) out[target_[s]] += factor_[s] * values[s];
}

}  // namespace growshell
