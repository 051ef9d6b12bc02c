#include "solvers/stability/reduced_hessian_inertia.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "solvers/newton/upper_triangle_check.hpp"

namespace growshell {
namespace {

constexpr const char* kWho = "reduced_hessian_inertia";

// Null-pivot threshold (relative, MUMPS CNTL(3)) of the Gram matrix of the normalised rows.
// Its pivots are squared sines of the angle between a row and the span of the rows eliminated
// before it: exactly dependent rows leave round-off (~1e-16), and 1e-12 flags rows within a
// sine of about 1e-6 of dependence, where the multipliers would be ill-determined anyway.
constexpr double kDependentRowThreshold = 1e-12;

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

std::string entry_name(Eigen::Index row, Eigen::Index col) {
  return "(" + std::to_string(row) + ", " + std::to_string(col) + ")";
}

[[noreturn]] void throw_rank_deficient(const std::string& why) {
  throw std::runtime_error(std::string(kWho) + ": the constraint Jacobian is rank deficient on "
                           "the free dofs (" + why + "); the bordered-matrix inertia then "
                           "cannot separate the reduced Hessian's zero eigenvalues from "
                           "dependent constraints. Drop the dependent constraints (e.g. "
                           "duplicated or coinciding contact pairs, constraints on fixed dofs "
                           "only) and call again");
}

}  // namespace

ReducedInertia reduced_hessian_inertia(const Eigen::SparseMatrix<double>& hessian_upper,
                                       const Eigen::SparseMatrix<double>& constraint_jacobian,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const SymmetricIndefiniteOptions& options) {
  const Eigen::SparseMatrix<double>& h = hessian_upper;
  check_upper_triangle(h, std::string(kWho) + ": hessian_upper");
  const Eigen::Index n = h.rows();
  const Eigen::Index m = constraint_jacobian.rows();
  if (constraint_jacobian.cols() != n) {
    throw std::invalid_argument(std::string(kWho) + ": constraint_jacobian is " +
                                std::to_string(m) + " x " +
                                std::to_string(constraint_jacobian.cols()) + ", expected " +
                                std::to_string(n) + " columns (the order of hessian_upper)");
  }
  for (Eigen::Index col = 0; col < n; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(h, col); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw std::invalid_argument(std::string(kWho) + ": hessian_upper entry " +
                                    entry_name(it.row(), col) + " is not finite");
      }
    }
  }
  for (Eigen::Index col = 0; col < constraint_jacobian.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(constraint_jacobian, col); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw std::invalid_argument(std::string(kWho) + ": constraint_jacobian entry " +
                                    entry_name(it.row(), it.col()) + " is not finite");
      }
    }
  }

  // free_index[i]: position of dof i among the free dofs, -1 if fixed. Increasing in i, so
  // the upper triangle of H maps onto the upper triangle of H_f.
  std::vector<int> free_index(static_cast<size_t>(n), 0);
  for (size_t k = 0; k < fixed_dofs.size(); ++k) {
    const Eigen::Index d = fixed_dofs[k];
    if (d < 0 || d >= n) {
      throw std::invalid_argument(std::string(kWho) + ": fixed dof " + std::to_string(d) +
                                  " (fixed_dofs[" + std::to_string(k) + "]) is outside [0, " +
                                  std::to_string(n) + ")");
    }
    free_index[static_cast<size_t>(d)] = -1;
  }
  int nf = 0;
  for (int& f : free_index) f = f < 0 ? -1 : nf++;

  ReducedInertia result;
  result.constraints = static_cast<int>(m);
  result.free_dofs = nf;
  if (m > nf) {
    throw_rank_deficient(std::to_string(m) + " constraints on " + std::to_string(nf) +
                         " free dofs");
  }
  if (nf == 0) return result;  // nothing free and (from above) no constraints

  // Rows of J restricted to the free dofs, normalised: J_hat (m x nf, row-major).
  const RowMajorMatrix j_rows = constraint_jacobian;
  RowMajorMatrix j_hat(m, nf);
  {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<size_t>(j_rows.nonZeros()));
    for (Eigen::Index k = 0; k < m; ++k) {
      double norm2 = 0.0;
      for (RowMajorMatrix::InnerIterator it(j_rows, k); it; ++it) {
        if (free_index[static_cast<size_t>(it.col())] >= 0) norm2 += it.value() * it.value();
      }
      if (!(norm2 > 0.0)) {
        throw_rank_deficient("row " + std::to_string(k) +
                             " has no nonzero entry on a free dof");
      }
      const double scale = 1.0 / std::sqrt(norm2);
      for (RowMajorMatrix::InnerIterator it(j_rows, k); it; ++it) {
        const int f = free_index[static_cast<size_t>(it.col())];
        if (f >= 0 && it.value() != 0.0) entries.emplace_back(k, f, scale * it.value());
      }
    }
    j_hat.setFromTriplets(entries.begin(), entries.end());
  }

  if (m > 0) {
    const Eigen::SparseMatrix<double> gram = j_hat * j_hat.transpose();
    Eigen::SparseMatrix<double> gram_upper = gram.triangularView<Eigen::Upper>();
    gram_upper.makeCompressed();
    SymmetricIndefiniteOptions gram_options;
    gram_options.ordering = options.ordering;
    gram_options.null_pivot_threshold = kDependentRowThreshold;
    SymmetricIndefiniteFactorization gram_ldlt(gram_options);
    gram_ldlt.analyze(gram_upper);
    gram_ldlt.factorize(gram_upper);
    // A Gram matrix is positive semidefinite: a negative pivot is a null one spoilt by
    // round-off.
    const int dependent = gram_ldlt.zero_pivots() + gram_ldlt.negative_eigenvalues();
    if (dependent > 0) {
      throw_rank_deficient("about " + std::to_string(dependent) + " of its " +
                           std::to_string(m) + " rows depend on the others");
    }
  }

  // Scale of H_f: the bordering block gets entries of this size (a congruence of K).
  double h_scale = 0.0;
  for (Eigen::Index col = 0; col < n; ++col) {
    if (free_index[static_cast<size_t>(col)] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(h, col); it; ++it) {
      if (free_index[static_cast<size_t>(it.row())] >= 0) {
        h_scale = std::max(h_scale, std::abs(it.value()));
      }
    }
  }
  if (h_scale == 0.0) h_scale = 1.0;

  // K's upper triangle, column by column in compressed storage: first the free columns of H
  // (free rows only, with an explicit zero diagonal where H has none), then column nf + k
  // holding row k of h_scale * J_hat above an explicit zero diagonal. Explicit diagonals
  // keep every row structurally present for MUMPS.
  const Eigen::Index order = nf + m;
  std::vector<Eigen::Index> column_start(static_cast<size_t>(order) + 1, 0);
  for (Eigen::Index col = 0; col < n; ++col) {
    const int fc = free_index[static_cast<size_t>(col)];
    if (fc < 0) continue;
    Eigen::Index count = 1;  // the diagonal, stored or added
    for (Eigen::SparseMatrix<double>::InnerIterator it(h, col); it; ++it) {
      if (it.row() != col && free_index[static_cast<size_t>(it.row())] >= 0) ++count;
    }
    column_start[static_cast<size_t>(fc) + 1] = count;
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    column_start[static_cast<size_t>(nf + k) + 1] = j_hat.outerIndexPtr()[k + 1] -
                                                     j_hat.outerIndexPtr()[k] + 1;
  }
  for (size_t c = 0; c < static_cast<size_t>(order); ++c) column_start[c + 1] += column_start[c];
  const Eigen::Index nnz = column_start.back();
  if (nnz > std::numeric_limits<int>::max()) {
    throw std::runtime_error(std::string(kWho) + ": the bordered matrix has " +
                             std::to_string(nnz) + " entries, beyond 32-bit indices");
  }

  Eigen::SparseMatrix<double> k_upper(order, order);
  k_upper.resizeNonZeros(nnz);
  int* outer = k_upper.outerIndexPtr();
  int* inner = k_upper.innerIndexPtr();
  double* values = k_upper.valuePtr();
  for (size_t c = 0; c <= static_cast<size_t>(order); ++c) {
    outer[c] = static_cast<int>(column_start[c]);
  }
  for (Eigen::Index col = 0; col < n; ++col) {
    const int fc = free_index[static_cast<size_t>(col)];
    if (fc < 0) continue;
    int pos = outer[fc];
    double diagonal = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(h, col); it; ++it) {
      if (it.row() == col) {
        diagonal = it.value();
        continue;
      }
      const int fr = free_index[static_cast<size_t>(it.row())];
      if (fr < 0) continue;
      inner[pos] = fr;
      values[pos] = it.value();
      ++pos;
    }
    inner[pos] = fc;  // rows are sorted and below col, so the diagonal comes last
    values[pos] = diagonal;
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    int pos = outer[nf + k];
    for (RowMajorMatrix::InnerIterator it(j_hat, k); it; ++it) {
      inner[pos] = static_cast<int>(it.col());
      values[pos] = h_scale * it.value();
      ++pos;
    }
    inner[pos] = static_cast<int>(nf + k);
    values[pos] = 0.0;
  }

  SymmetricIndefiniteFactorization ldlt(options);
  ldlt.analyze(k_upper);
  ldlt.factorize(k_upper);
  const int negative = ldlt.negative_eigenvalues();
  // With J_f of full rank K has at least m negative eigenvalues; fewer means the rank test
  // above missed a dependence that round-off hid from it.
  if (negative < m) {
    throw_rank_deficient("the bordered matrix has only " + std::to_string(negative) +
                         " negative eigenvalues for " + std::to_string(m) + " constraints");
  }
  result.negative = negative - static_cast<int>(m);
  result.zero = ldlt.zero_pivots();
  return result;
}

}  // namespace growshell
