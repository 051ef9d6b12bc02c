#pragma once
/// \file
/// Sparse symmetric indefinite LDL^T factorisation through sequential MUMPS, with the inertia
/// of the matrix: the exact number of negative eigenvalues (and of null pivots). Continuation
/// along unstable equilibrium branches needs both solves with an indefinite Hessian, where
/// CHOLMOD's LL^T fails, and the count of unstable directions. Symmetric shells make double
/// eigenvalues generic, so the count must be exact; the sign of a determinant would miss a
/// pair of eigenvalues crossing zero together.

#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace growshell {

/// Fill-reducing ordering MUMPS applies in analyze() (its ICNTL(7)).
enum class IndefiniteOrdering {
  Automatic,  ///< MUMPS chooses from the orderings it was built with (ICNTL(7) = 7).
  Amd,        ///< Approximate minimum degree (ICNTL(7) = 0); always available.
  Scotch,     ///< SCOTCH nested dissection (ICNTL(7) = 3); built into Debian's MUMPS.
  /// METIS nested dissection (ICNTL(7) = 5). Debian's MUMPS is built without METIS, and MUMPS
  /// then silently falls back to its automatic choice; see ordering_used().
  Metis
};

/// Options of SymmetricIndefiniteFactorization.
struct SymmetricIndefiniteOptions {
  /// Ordering used by analyze().
  IndefiniteOrdering ordering = IndefiniteOrdering::Automatic;
  /// Null-pivot threshold (MUMPS CNTL(3)). A pivot counts as null (zero_pivots()) when it and
  /// the rest of its row in the frontal matrix are at most this value times
  /// ||A_s||_inf, where A_s is A after MUMPS's symmetric scaling. 0 selects MUMPS's default
  /// sqrt(p) * eps * ||A_s||_inf, with p the number of pivots on the critical path of the
  /// elimination tree and eps = 2.2e-16: only matrices singular up to round-off have null
  /// pivots. Must be finite and >= 0.
  double null_pivot_threshold = 0.0;
};

/// Symmetric indefinite LDL^T factorisation (MUMPS 5, sequential, SYM = 2: threshold partial
/// pivoting with 1x1 and 2x2 pivots) of a sparse symmetric matrix given by its upper triangle,
/// with the inertia.
///
/// The matrix passed to analyze() and factorize() must be a square, column-major, compressed
/// Eigen::SparseMatrix<double> (int indices) holding the upper triangle (row <= column).
/// analyze() fixes the sparsity pattern; factorize() may then be called any number of times
/// with new values on exactly that pattern, reusing the analysis.
///
/// Inertia: by Sylvester's law of inertia A = L D L^T has as many negative eigenvalues as D,
/// and MUMPS counts them (INFOG(12)) including those of 2x2 pivot blocks. The whole
/// factorisation runs sequentially without ScaLAPACK (ICNTL(13) = 1) and without static
/// pivoting (CNTL(4) < 0), the two MUMPS features that would make the count a lower bound or
/// perturb it. Null-pivot detection is always on (ICNTL(24) = 1): a null pivot is counted in
/// zero_pivots() and not in negative_eigenvalues(), whatever its sign.
///
/// Not thread-safe: every call, solve() included, uses the object's MUMPS instance. The
/// library never prints (MUMPS output is switched off); MUMPS failures become
/// std::runtime_error naming INFOG(1) and INFOG(2).
class SymmetricIndefiniteFactorization {
 public:
  /// Starts a MUMPS instance (sequential, symmetric indefinite) with the given options.
  /// Throws std::invalid_argument on a negative or non-finite null_pivot_threshold,
  /// std::runtime_error if MUMPS fails to initialise.
  explicit SymmetricIndefiniteFactorization(SymmetricIndefiniteOptions options = {});
  /// Releases the MUMPS instance.
  ~SymmetricIndefiniteFactorization();
  SymmetricIndefiniteFactorization(const SymmetricIndefiniteFactorization&) = delete;
  SymmetricIndefiniteFactorization& operator=(const SymmetricIndefiniteFactorization&) = delete;
  /// Moves the MUMPS instance and factor; the moved-from object may only be destroyed or
  /// assigned.
  SymmetricIndefiniteFactorization(SymmetricIndefiniteFactorization&&) noexcept;
  /// Moves the MUMPS instance and factor; the moved-from object may only be destroyed or
  /// assigned.
  SymmetricIndefiniteFactorization& operator=(SymmetricIndefiniteFactorization&&) noexcept;

  /// Symbolic analysis (ordering, elimination tree) of the pattern of `upper`. Call once per
  /// sparsity pattern; discards any previous factor. MUMPS may also use the values (weighted
  /// matching for 2x2 pivot candidates), so pass representative ones; factorize() accepts any
  /// values on the pattern.
  /// Throws std::invalid_argument if `upper` is empty, not square, not compressed, has
  /// entries below the diagonal or non-finite values, std::runtime_error if MUMPS fails.
  void analyze(const Eigen::SparseMatrix<double>& upper);

  /// Numeric LDL^T factorisation of A, given by its upper triangle with the pattern passed to
  /// analyze(). A singular matrix is a normal outcome: zero_pivots() > 0, and solve() throws.
  /// Throws std::logic_error if analyze() was not called, std::invalid_argument on a
  /// non-finite value, std::runtime_error if the pattern differs from the analysed one or
  /// MUMPS fails (the message names INFOG(1) and INFOG(2)). After a throw no factor is
  /// available.
  void factorize(const Eigen::SparseMatrix<double>& upper);

  /// Returns x solving A x = b for the last factorisation.
  /// Throws std::logic_error without a factorisation, std::runtime_error if that
  /// factorisation found null pivots (A singular: a solution exists only for some b, and
  /// MUMPS would return one of them without telling whether b was one of those),
  /// std::invalid_argument if b has the wrong size.
  Eigen::VectorXd solve(const Eigen::Ref<const Eigen::VectorXd>& b) const;

  /// Number of negative eigenvalues of A (= negative pivots of D, MUMPS INFOG(12)) from the
  /// last factorisation; null pivots are not included. Throws std::logic_error without one.
  int negative_eigenvalues() const;

  /// Number of null pivots of the last factorisation (MUMPS INFOG(28)); see
  /// SymmetricIndefiniteOptions::null_pivot_threshold. A positive count means A is singular to
  /// working precision and has at least that many (near-)zero eigenvalues. Throws
  /// std::logic_error without a factorisation.
  int zero_pivots() const;

  /// Order n of the analysed matrix (0 before analyze()).
  Eigen::Index rows() const;

  /// Name of the ordering MUMPS actually used in analyze() ("AMD", "AMF", "SCOTCH", "PORD",
  /// "METIS", "QAMD"; MUMPS INFOG(7)). Throws std::logic_error before analyze().
  std::string ordering_used() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace growshell
