#pragma once
/// \file
/// Sparse Cholesky factorisation of a symmetric positive-definite matrix through CHOLMOD
/// (supernodal LL^T), with the symbolic analysis separated from the numeric factorisation so
/// that a Newton solver analyses its Hessian pattern once and refactorises every iteration.

#include <memory>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace growshell {

/// Fill-reducing ordering CHOLMOD applies before factorising.
enum class FillReducingOrdering {
  Metis,  ///< METIS nested dissection: least fill on 2-D meshes such as shells.
  Amd     ///< Approximate minimum degree: cheaper to compute, usually more fill.
};

/// Options of CholmodFactorization.
struct CholmodOptions {
  /// Ordering used by analyze().
  FillReducingOrdering ordering = FillReducingOrdering::Metis;
};

/// Outcome of one numeric factorisation.
struct FactorizationResult {
  /// True if A + shift*I was numerically positive definite and L is usable for solve().
  bool positive_definite = false;
  /// When not positive definite: the column (caller's numbering, 0-based) at which the
  /// Cholesky pivot became non-positive; -1 otherwise.
  int failed_column = -1;
};

/// CHOLMOD supernodal LL^T factorisation of a symmetric matrix given by its upper triangle.
///
/// The matrix passed to analyze() and factorize() is read in place (no copy): it must be a
/// square, column-major, compressed Eigen::SparseMatrix<double> (int indices) holding the
/// upper triangle (row <= column). analyze() fixes the sparsity pattern; factorize() may then
/// be called any number of times with new values on exactly that pattern.
///
/// Not thread-safe: every call, solve() included, uses the object's CHOLMOD workspace.
/// The library never prints; CHOLMOD failures other than "not positive definite" become
/// std::runtime_error naming CHOLMOD's status.
class CholmodFactorization {
 public:
  /// Starts a CHOLMOD workspace configured for supernodal LL^T with the given ordering.
  explicit CholmodFactorization(CholmodOptions options = {});
  ~CholmodFactorization();
  CholmodFactorization(const CholmodFactorization&) = delete;
  CholmodFactorization& operator=(const CholmodFactorization&) = delete;
  /// Moves the workspace and factor; the moved-from object may only be destroyed or assigned.
  CholmodFactorization(CholmodFactorization&&) noexcept;
  /// Moves the workspace and factor; the moved-from object may only be destroyed or assigned.
  CholmodFactorization& operator=(CholmodFactorization&&) noexcept;

  /// Symbolic analysis (ordering, elimination tree, supernodes) of the pattern of `upper`.
  /// Call once per sparsity pattern; discards any previous factor.
  /// Throws std::invalid_argument if `upper` is not square/compressed or has entries below
  /// the diagonal, std::runtime_error if CHOLMOD fails.
  void analyze(const Eigen::SparseMatrix<double>& upper);

  /// Numeric factorisation of A + shift*I, A given by its upper triangle with the pattern
  /// passed to analyze(). A non-positive-definite matrix is a normal outcome reported in the
  /// result (solve() is then unavailable until a successful factorisation).
  /// Throws std::logic_error if analyze() was not called, std::invalid_argument on a
  /// non-finite value or shift, std::runtime_error if the pattern differs from the analysed
  /// one or CHOLMOD fails (e.g. out of memory).
  FactorizationResult factorize(const Eigen::SparseMatrix<double>& upper, double shift = 0.0);

  /// Returns x solving (A + shift*I) x = b for the last successful factorisation.
  /// Throws std::logic_error without one, std::invalid_argument if b has the wrong size.
  Eigen::VectorXd solve(const Eigen::Ref<const Eigen::VectorXd>& b) const;

  /// Order n of the analysed matrix (0 before analyze()).
  Eigen::Index rows() const;

  /// Floating-point operation count of one numeric factorisation with the analysed
  /// ordering (CHOLMOD's Common->fl); 0 before analyze().
  double factorization_flops() const;

  /// Number of nonzeros in the factor L with the analysed ordering (CHOLMOD's Common->lnz);
  /// 0 before analyze().
  double factor_nonzeros() const;

  /// Ordering this object was configured with.
  FillReducingOrdering ordering() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Name of an ordering ("METIS" or "AMD").
const char* to_string(FillReducingOrdering ordering);

}  // namespace growshell
