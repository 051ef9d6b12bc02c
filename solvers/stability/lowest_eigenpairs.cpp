#include "solvers/stability/lowest_eigenpairs.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include <Eigen/Dense>

#include "solvers/newton/fixed_dof_elimination.hpp"
#include "solvers/stability/symmetric_indefinite_factorization.hpp"

namespace growshell {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// H with the fixed dofs eliminated, restricted to the free dofs for the iteration, and the
// factorisations of H - sigma I. In every shifted matrix the fixed diagonal keeps the positive
// pivot of FixedDofElimination (it is not shifted), so the fixed block is positive definite and
// the inertia counts only eigenvalues of the free block.
class ShiftedOperator {
 public:
  ShiftedOperator(const SpMat& upper, const std::vector<Eigen::Index>& fixed_dofs) {
    const Eigen::Index n = upper.rows();
    if (n == 0 || upper.cols() != n)
      throw std::invalid_argument("eigenpairs: matrix is " + std::to_string(upper.rows()) +
                                  " x " + std::to_string(upper.cols()) +
                                  ", expected square and non-empty");
    // Union with the diagonal pattern, so that every free dof has a diagonal entry to shift.
    SpMat zero_diagonal(n, n);
    zero_diagonal.setIdentity();
    zero_diagonal *= 0.0;
    matrix_ = upper + zero_diagonal;
    matrix_.makeCompressed();
    for (Eigen::Index k = 0; k < matrix_.nonZeros(); ++k)
      if (!std::isfinite(matrix_.valuePtr()[k]))
        throw std::invalid_argument("eigenpairs: the matrix has a non-finite entry");
    const FixedDofElimination elimination(matrix_, fixed_dofs);  // validates the pattern
    elimination.apply(matrix_);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (elimination.is_fixed(i)) continue;
      free_.push_back(i);
      free_diagonal_.push_back(elimination.diagonal_position(i));
    }
    // Gershgorin bounds of the free block (fixed rows and columns are zero off the diagonal).
    Eigen::VectorXd off_sum = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
    for (Eigen::Index col = 0; col < n; ++col) {
      for (SpMat::InnerIterator it(matrix_, col); it; ++it) {
        if (it.row() == col) {
          diagonal[col] = it.value();
        } else {
          off_sum[it.row()] += std::abs(it.value());
          off_sum[col] += std::abs(it.value());
        }
      }
    }
    lower_bound_ = std::numeric_limits<double>::infinity();
    upper_bound_ = -std::numeric_limits<double>::infinity();
    norm_inf_ = 0.0;
    for (const Eigen::Index i : free_) {
      lower_bound_ = std::min(lower_bound_, diagonal[i] - off_sum[i]);
      upper_bound_ = std::max(upper_bound_, diagonal[i] + off_sum[i]);
      norm_inf_ = std::max(norm_inf_, std::abs(diagonal[i]) + off_sum[i]);
    }
    shifted_ = matrix_;
  }

  Eigen::Index size() const { return matrix_.rows(); }
  Eigen::Index free_count() const { return static_cast<Eigen::Index>(free_.size()); }
  // ||H_free||_inf, or 1 for a zero matrix so that relative measures stay defined.
  double scale() const { return norm_inf_ > 0.0 ? norm_inf_ : 1.0; }
  double norm_inf() const { return norm_inf_; }
  // All eigenvalues of the free block lie in [gershgorin_lower(), gershgorin_upper()].
  double gershgorin_lower() const { return lower_bound_; }
  double gershgorin_upper() const { return upper_bound_; }
  int factorizations() const { return factorizations_; }

  // Factorises H - sigma I and returns the number of free eigenvalues below sigma. A shift
  // that is an eigenvalue to working precision (null pivots) is moved down by growing steps,
  // and `sigma` returns the shift actually used.
  int factorize_at(double& sigma) {
    double step = 1e-10 * scale();
    for (int attempt = 0; attempt < 8; ++attempt) {
      std::copy(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), shifted_.valuePtr());
      for (const int k : free_diagonal_) shifted_.valuePtr()[k] -= sigma;
      if (!analyzed_) {
        factorization_.analyze(shifted_);
        analyzed_ = true;
      }
      factorization_.factorize(shifted_);
      ++factorizations_;
      if (factorization_.zero_pivots() == 0) return factorization_.negative_eigenvalues();
      sigma -= step;
      step *= 10.0;
    }
    std::ostringstream message;
    message << "eigenpairs: H - sigma I stays singular down to sigma = " << sigma;
    throw std::runtime_error(message.str());
  }

  // (H - sigma I)^{-1} V for the last factorisation; V and the result on the free dofs.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& v) const {
    Eigen::MatrixXd out(v.rows(), v.cols());
    Eigen::VectorXd full = Eigen::VectorXd::Zero(size());
    for (Eigen::Index j = 0; j < v.cols(); ++j) {
      for (Eigen::Index k = 0; k < free_count(); ++k) full[free_[k]] = v(k, j);
      const Eigen::VectorXd x = factorization_.solve(full);
      for (Eigen::Index k = 0; k < free_count(); ++k) out(k, j) = x[free_[k]];
    }
    return out;
  }

  // H V on the free dofs.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& v) const {
    const Eigen::MatrixXd full = expand(v);
    const Eigen::MatrixXd product = matrix_.selfadjointView<Eigen::Upper>() * full;
    Eigen::MatrixXd out(v.rows(), v.cols());
    for (Eigen::Index k = 0; k < free_count(); ++k) out.row(k) = product.row(free_[k]);
    return out;
  }

  // Free-dof vectors to full vectors, zero at the fixed dofs.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& v) const {
    Eigen::MatrixXd full = Eigen::MatrixXd::Zero(size(), v.cols());
    for (Eigen::Index k = 0; k < free_count(); ++k) full.row(free_[k]) = v.row(k);
    return full;
  }

 private:
  SpMat matrix_;   // H, fixed rows and columns zeroed, positive pivot on their diagonal
  SpMat shifted_;  // work copy for H - sigma I
  std::vector<Eigen::Index> free_;
  std::vector<int> free_diagonal_;
  double lower_bound_ = 0.0;
  double upper_bound_ = 0.0;
  double norm_inf_ = 0.0;
  SymmetricIndefiniteFactorization factorization_;
  bool analyzed_ = false;
  int factorizations_ = 0;
};

Eigen::MatrixXd orthonormal_basis(const Eigen::MatrixXd& w) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(w);
  return qr.householderQ() * Eigen::MatrixXd::Identity(w.rows(), w.cols());
}

// A shift just below the lowest eigenvalue, from inertia counts only. Invariant: no
// eigenvalue below `lo`, at least one below `hi`. The bisection runs in log |sigma| on
// either side of zero, since the eigenvalues of interest (near-critical modes) are often many
// orders of magnitude smaller than ||H||.
double shift_below_spectrum(ShiftedOperator& op) {
  const double scale = op.scale();
  double lo = op.gershgorin_lower() - 0.01 * scale;
  double hi = op.gershgorin_upper() + 0.01 * scale;
  const double floor = 1e-10 * scale;
  auto probe = [&](double sigma) {
    const int below = op.factorize_at(sigma);
    if (below == 0)
      lo = std::max(lo, sigma);
    else
      hi = std::min(hi, sigma);
  };
  if (lo < 0.0 && hi > 0.0) probe(0.0);
  for (int step = 0; step < 200; ++step) {
    const double width = hi - lo;
    if (width <= 0.01 * std::max(std::abs(lo), std::abs(hi)) || width <= floor) break;
    double mid = 0.5 * (lo + hi);
    if (lo >= 0.0)
      mid = std::sqrt(std::max(lo, floor) * hi);
    else if (hi <= 0.0)
      mid = -std::sqrt(std::max(-hi, floor) * -lo);
    if (!(mid > lo && mid < hi)) mid = 0.5 * (lo + hi);
    probe(mid);
  }
  return lo;
}

void check_options(const EigenpairOptions& options, Eigen::Index free_count) {
  if (options.count < 1 || options.count > free_count)
    throw std::invalid_argument("EigenpairOptions::count = " + std::to_string(options.count) +
                                " is outside [1, " + std::to_string(free_count) +
                                "] (the number of free dofs)");
  if (options.block_size != 0 && options.block_size < options.count)
    throw std::invalid_argument("EigenpairOptions::block_size = " +
                                std::to_string(options.block_size) + " must be 0 or >= count = " +
                                std::to_string(options.count));
  if (options.max_iterations < 1)
    throw std::invalid_argument("EigenpairOptions::max_iterations = " +
                                std::to_string(options.max_iterations) + " must be >= 1");
  if (!(std::isfinite(options.tolerance) && options.tolerance > 0.0))
    throw std::invalid_argument("EigenpairOptions::tolerance must be finite and > 0");
  if (std::isinf(options.shift))
    throw std::invalid_argument("EigenpairOptions::shift must be finite, or NaN for the lowest");
}

}  // namespace

Eigenpairs lowest_eigenpairs_of_matrix(const SpMat& upper,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const EigenpairOptions& options) {
  ShiftedOperator op(upper, fixed_dofs);
  const Eigen::Index free_count = op.free_count();
  check_options(options, free_count);
  const bool lowest = std::isnan(options.shift);
  const Eigen::Index count = options.count;
  const Eigen::Index block = std::min<Eigen::Index>(
      free_count, options.block_size > 0 ? options.block_size
                                         : options.count + std::max(4, options.count / 2));
  const double scale = op.scale();

  Eigenpairs result;
  double sigma = lowest ? shift_below_spectrum(op) : options.shift;
  op.factorize_at(sigma);
  result.shift = sigma;

  // Fixed seed: the result must not depend on anything but the input.
  std::mt19937 rng(20240611u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd v(free_count, block);
  for (Eigen::Index j = 0; j < block; ++j)
    for (Eigen::Index i = 0; i < free_count; ++i) v(i, j) = uniform(rng);
  v = orthonormal_basis(v);

  Eigen::VectorXd ritz_values(block);
  Eigen::VectorXd residuals(block);
  bool converged = false;
  int iteration = 0;
  while (iteration < options.max_iterations && !converged) {
    ++iteration;
    const Eigen::MatrixXd q = orthonormal_basis(op.solve(v));
    const Eigen::MatrixXd hq = op.apply(q);
    Eigen::MatrixXd projected = q.transpose() * hq;
    projected = 0.5 * (projected + projected.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> small(projected);
    const Eigen::VectorXd& theta = small.eigenvalues();
    // Nearest to the shift first; ties (a degenerate pair) in ascending order.
    std::vector<Eigen::Index> order(static_cast<std::size_t>(block));
    std::iota(order.begin(), order.end(), Eigen::Index{0});
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
      return std::abs(theta[a] - sigma) < std::abs(theta[b] - sigma);
    });
    Eigen::MatrixXd s(block, block);
    for (Eigen::Index j = 0; j < block; ++j) {
      s.col(j) = small.eigenvectors().col(order[static_cast<std::size_t>(j)]);
      ritz_values[j] = theta[order[static_cast<std::size_t>(j)]];
    }
    v = q * s;
    const Eigen::MatrixXd residual = hq * s - v * ritz_values.asDiagonal();
    for (Eigen::Index j = 0; j < block; ++j) residuals[j] = residual.col(j).norm() / scale;
    converged = residuals.head(count).maxCoeff() <= options.tolerance;
  }
  result.iterations = iteration;

  // Report the wanted pairs in ascending order.
  std::vector<Eigen::Index> wanted(static_cast<std::size_t>(count));
  std::iota(wanted.begin(), wanted.end(), Eigen::Index{0});
  std::stable_sort(wanted.begin(), wanted.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return ritz_values[a] < ritz_values[b]; });
  Eigen::MatrixXd chosen(free_count, count);
  result.values.resize(count);
  result.residuals.resize(count);
  for (Eigen::Index j = 0; j < count; ++j) {
    const Eigen::Index k = wanted[static_cast<std::size_t>(j)];
    chosen.col(j) = v.col(k);
    result.values[j] = ritz_values[k];
    result.residuals[j] = residuals[k];
  }
  result.vectors = op.expand(chosen);

  // Inertia check (Sylvester): the eigenvalues in [a, b] around the reported ones must all be
  // Ritz values of the block; otherwise the iteration missed one (a start block deficient in
  // its direction) and the result is not the set asked for.
  const double margin = std::max(10.0 * options.tolerance, 1e-9) * scale;
  const double top = result.values[count - 1];
  const double bottom = result.values[0];
  double b = top + margin;
  double a = -std::numeric_limits<double>::infinity();
  if (!lowest) {
    const double radius = std::max(std::abs(top - sigma), std::abs(bottom - sigma));
    b = sigma + radius + margin;
    a = sigma - radius - margin;
  }
  const int below_b = op.factorize_at(b);
  const int below_a = std::isfinite(a) ? op.factorize_at(a) : 0;
  int ritz_in_interval = 0;
  int ritz_below_reported = 0;
  for (Eigen::Index j = 0; j < block; ++j) {
    if (ritz_values[j] >= a && ritz_values[j] <= b) ++ritz_in_interval;
    if (ritz_values[j] >= a && ritz_values[j] < bottom - margin) ++ritz_below_reported;
  }
  const int missed = (below_b - below_a) - ritz_in_interval;
  result.eigenvalues_below = below_a + ritz_below_reported;
  result.factorizations = op.factorizations();

  std::ostringstream message;
  if (!converged) {
    message << "not converged after " << iteration << " iterations: largest relative residual "
            << residuals.head(count).maxCoeff() << " > tolerance " << options.tolerance;
  } else if (missed > 0) {
    message << "converged in " << iteration << " iterations, but the inertia shows " << missed
            << " eigenvalue(s) in [" << a << ", " << b << "] that the block did not find";
  } else {
    message << "converged in " << iteration << " iterations at shift " << sigma << " ("
            << result.factorizations << " factorisations); inertia: " << below_b
            << " eigenvalue(s) below " << b;
  }
  result.converged = converged && missed <= 0;
  result.message = message.str();
  return result;
}

Eigenpairs lowest_eigenpairs(SparseObjective& objective, const Eigen::Ref<const Eigen::VectorXd>& x,
                             const std::vector<Eigen::Index>& fixed_dofs,
                             const EigenpairOptions& options) {
  if (x.size() != objective.dimension())
    throw std::invalid_argument("lowest_eigenpairs: x has " + std::to_string(x.size()) +
                                " entries, the objective " +
                                std::to_string(objective.dimension()));
  SpMat hessian = objective.hessian_pattern();
  objective.evaluate(x, nullptr, &hessian);
  return lowest_eigenpairs_of_matrix(hessian, fixed_dofs, options);
}

}  // namespace growshell
