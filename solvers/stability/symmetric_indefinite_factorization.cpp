#include "solvers/stability/symmetric_indefinite_factorization.hpp"

#include "solvers/newton/upper_triangle_check.hpp"

#include <dmumps_c.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell {
namespace {

// MUMPS documents its controls and results 1-based (ICNTL(13)); the C arrays are 0-based.
constexpr int fortran_index(int i) { return i - 1; }

// The Fortran communicator value the sequential MUMPS (libmpiseq) expects.
constexpr MUMPS_INT kUseCommWorld = -987654;

enum MumpsJob : MUMPS_INT {
  kInit = -1,
  kEnd = -2,
  kAnalyze = 1,
  kFactorize = 2,
  kSolve = 3,
};

// How often factorize() retries with a larger workspace after INFOG(1) = -8 or -9: delayed
// pivots of an indefinite matrix can outgrow the estimate of the analysis, and each retry
// doubles the relaxation ICNTL(14).
constexpr int kMaxWorkspaceRetries = 4;

const char* mumps_error_name(int infog1) {
  switch (infog1) {
    case -1:
      return "error on another process";
    case -2:
      return "NNZ out of range";
    case -3:
      return "invalid JOB for the current state";
    case -4:
      return "error in the user permutation";
    case -5:
    case -7:
    case -13:
      return "memory allocation failed";
    case -6:
      return "matrix structurally singular";
    case -8:
      return "integer workspace too small for the factorisation";
    case -9:
      return "real workspace too small for the factorisation";
    case -10:
      return "matrix numerically singular";
    case -11:
      return "workspace too small for the solve";
    case -16:
      return "N out of range";
    case -17:
    case -20:
      return "internal communication buffer too small";
    default:
      return "see the error diagnostics of the MUMPS user guide";
  }
}

const char* ordering_name(int infog7) {
  switch (infog7) {
    case 0:
      return "AMD";
    case 1:
      return "user-given";
    case 2:
      return "AMF";
    case 3:
      return "SCOTCH";
    case 4:
      return "PORD";
    case 5:
      return "METIS";
    case 6:
      return "QAMD";
    default:
      return "unknown";
  }
}

MUMPS_INT mumps_ordering(IndefiniteOrdering ordering) {
  switch (ordering) {
    case IndefiniteOrdering::Automatic:
      return 7;
    case IndefiniteOrdering::Amd:
      return 0;
    case IndefiniteOrdering::Scotch:
      return 3;
    case IndefiniteOrdering::Metis:
      return 5;
  }
  return 7;
}

}  // namespace

struct SymmetricIndefiniteFactorization::Impl {
  DMUMPS_STRUC_C id{};
  // Coordinate input (1-based) of the analysed pattern, in the order of the Eigen storage so
  // that factorize() copies values without searching; MUMPS keeps pointers to these.
  std::vector<MUMPS_INT> irn;
  std::vector<MUMPS_INT> jcn;
  std::vector<double> a;
  std::vector<double> rhs;  // solve() workspace; MUMPS overwrites it with the solution
  Eigen::Index n = 0;
  bool analyzed = false;
  bool factorized = false;
  int negative = 0;
  int null_pivots = 0;

  explicit Impl(const SymmetricIndefiniteOptions& options) {
    id.job = kInit;
    id.par = 1;  // the (only) host process works too
    id.sym = 2;  // general symmetric: LDL^T with 1x1 and 2x2 pivots
    id.comm_fortran = kUseCommWorld;
    dmumps_c(&id);
    if (id.infog[fortran_index(1)] < 0) {
      const int code = id.infog[fortran_index(1)];
      throw std::runtime_error(
          "SymmetricIndefiniteFactorization: MUMPS initialisation failed with INFOG(1) = " +
          std::to_string(code) + " (" + mumps_error_name(code) + ")");
    }
    // Output streams for errors, diagnostics and global information off; print level 0.
    id.icntl[fortran_index(1)] = -1;
    id.icntl[fortran_index(2)] = -1;
    id.icntl[fortran_index(3)] = -1;
    id.icntl[fortran_index(4)] = 0;
    id.icntl[fortran_index(7)] = mumps_ordering(options.ordering);
    // Root node factorised by MUMPS itself rather than ScaLAPACK, which would leave its
    // negative pivots out of INFOG(12).
    id.icntl[fortran_index(13)] = 1;
    id.icntl[fortran_index(24)] = 1;  // null-pivot detection instead of failing with -10
    id.cntl[fortran_index(3)] = options.null_pivot_threshold;
    // No static pivoting: replacing tiny pivots by sqrt(eps)*||A|| would alter the inertia.
    // (MUMPS disables it anyway while null-pivot detection is on; explicit for the reader.)
    id.cntl[fortran_index(4)] = -1.0;
  }
  ~Impl() {
    id.job = kEnd;
    dmumps_c(&id);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  int infog(int i) const { return id.infog[fortran_index(i)]; }

  [[noreturn]] void throw_mumps_error(const char* phase) const {
    const int code = infog(1);
    throw std::runtime_error(std::string("SymmetricIndefiniteFactorization: MUMPS ") + phase +
                             " failed with INFOG(1) = " + std::to_string(code) + " (" +
                             mumps_error_name(code) + "), INFOG(2) = " + std::to_string(infog(2)));
  }
};

namespace {

void require_impl(const void* impl, const char* what) {
  if (impl == nullptr) {
    throw std::logic_error(std::string("SymmetricIndefiniteFactorization::") + what +
                           ": object was moved from");
  }
}

}  // namespace

SymmetricIndefiniteFactorization::SymmetricIndefiniteFactorization(
    SymmetricIndefiniteOptions options) {
  if (!std::isfinite(options.null_pivot_threshold) || options.null_pivot_threshold < 0.0) {
    throw std::invalid_argument("SymmetricIndefiniteFactorization: null_pivot_threshold is " +
                                std::to_string(options.null_pivot_threshold) +
                                ", must be finite and >= 0");
  }
  impl_ = std::make_unique<Impl>(options);
}
SymmetricIndefiniteFactorization::~SymmetricIndefiniteFactorization() = default;
SymmetricIndefiniteFactorization::SymmetricIndefiniteFactorization(
    SymmetricIndefiniteFactorization&&) noexcept = default;
SymmetricIndefiniteFactorization& SymmetricIndefiniteFactorization::operator=(
    SymmetricIndefiniteFactorization&&) noexcept = default;

void SymmetricIndefiniteFactorization::analyze(const Eigen::SparseMatrix<double>& upper) {
  require_impl(impl_.get(), "analyze");
  check_upper_triangle(upper, "SymmetricIndefiniteFactorization::analyze");
  if (upper.rows() == 0) {
    throw std::invalid_argument("SymmetricIndefiniteFactorization::analyze: matrix is empty");
  }
  if (upper.rows() > std::numeric_limits<MUMPS_INT>::max()) {
    throw std::invalid_argument("SymmetricIndefiniteFactorization::analyze: order " +
                                std::to_string(upper.rows()) +
                                " exceeds MUMPS's 32-bit index range");
  }
  const Eigen::Index n = upper.cols();
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  for (Eigen::Index col = 0; col < n; ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      if (!std::isfinite(upper.valuePtr()[k])) {
        throw std::invalid_argument("SymmetricIndefiniteFactorization::analyze: entry (" +
                                    std::to_string(inner[k]) + ", " + std::to_string(col) +
                                    ") is not finite");
      }
    }
  }

  Impl& s = *impl_;
  s.analyzed = false;
  s.factorized = false;
  s.n = 0;
  const auto nnz = static_cast<size_t>(upper.nonZeros());
  s.irn.resize(nnz);
  s.jcn.resize(nnz);
  // MUMPS's analysis of a symmetric indefinite matrix may use the values (weighted matching
  // for 2x2 pivot candidates, scaling), so it gets them.
  s.a.assign(upper.valuePtr(), upper.valuePtr() + nnz);
  for (Eigen::Index col = 0; col < n; ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      s.irn[static_cast<size_t>(k)] = inner[k] + 1;
      s.jcn[static_cast<size_t>(k)] = static_cast<MUMPS_INT>(col) + 1;
    }
  }
  s.id.n = static_cast<MUMPS_INT>(n);
  s.id.nnz = static_cast<MUMPS_INT8>(nnz);
  s.id.irn = s.irn.data();
  s.id.jcn = s.jcn.data();
  s.id.a = s.a.data();
  s.id.job = kAnalyze;
  dmumps_c(&s.id);
  if (s.infog(1) < 0) s.throw_mumps_error("analysis");
  s.n = n;
  s.analyzed = true;
}

void SymmetricIndefiniteFactorization::factorize(const Eigen::SparseMatrix<double>& upper) {
  require_impl(impl_.get(), "factorize");
  Impl& s = *impl_;
  if (!s.analyzed) {
    throw std::logic_error(
        "SymmetricIndefiniteFactorization::factorize: analyze() has not been called");
  }
  s.factorized = false;
  // The analysis holds for one pattern only. The stored coordinates are sorted by column, so
  // equal entry counts plus matching (row, column) of every entry mean an identical pattern.
  bool same_pattern = upper.rows() == s.n && upper.cols() == s.n && upper.isCompressed() &&
                      static_cast<size_t>(upper.nonZeros()) == s.irn.size();
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  for (Eigen::Index col = 0; same_pattern && col < s.n; ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      const auto kk = static_cast<size_t>(k);
      if (s.irn[kk] != inner[k] + 1 || s.jcn[kk] != col + 1) {
        same_pattern = false;
        break;
      }
    }
  }
  if (!same_pattern) {
    throw std::runtime_error(
        "SymmetricIndefiniteFactorization::factorize: sparsity pattern differs from the one "
        "passed to analyze() (" +
        std::to_string(upper.rows()) + " x " + std::to_string(upper.cols()) + " with " +
        std::to_string(upper.nonZeros()) + " entries vs " + std::to_string(s.n) + " x " +
        std::to_string(s.n) + " with " + std::to_string(s.irn.size()) + ")");
  }
  const double* values = upper.valuePtr();
  for (size_t k = 0; k < s.a.size(); ++k) {
    if (!std::isfinite(values[k])) {
      throw std::invalid_argument("SymmetricIndefiniteFactorization::factorize: entry (" +
                                  std::to_string(s.irn[k] - 1) + ", " +
                                  std::to_string(s.jcn[k] - 1) + ") is not finite");
    }
    s.a[k] = values[k];
  }

  s.id.job = kFactorize;
  for (int attempt = 0;; ++attempt) {
    dmumps_c(&s.id);
    const int code = s.infog(1);
    const bool workspace_too_small = code == -8 || code == -9;
    if (!workspace_too_small || attempt == kMaxWorkspaceRetries) break;
    s.id.icntl[fortran_index(14)] *= 2;
  }
  if (s.infog(1) < 0) s.throw_mumps_error("factorisation");
  s.negative = s.infog(12);
  s.null_pivots = s.infog(28);
  s.factorized = true;
}

Eigen::VectorXd SymmetricIndefiniteFactorization::solve(
    const Eigen::Ref<const Eigen::VectorXd>& b) const {
  require_impl(impl_.get(), "solve");
  Impl& s = *impl_;
  if (!s.factorized) {
    throw std::logic_error(
        "SymmetricIndefiniteFactorization::solve: no factorisation (call factorize())");
  }
  if (s.null_pivots > 0) {
    throw std::runtime_error("SymmetricIndefiniteFactorization::solve: matrix is singular (" +
                             std::to_string(s.null_pivots) + " null pivots)");
  }
  if (b.size() != s.n) {
    throw std::invalid_argument(
        "SymmetricIndefiniteFactorization::solve: right-hand side has size " +
        std::to_string(b.size()) + ", expected " + std::to_string(s.n));
  }
  s.rhs.assign(b.data(), b.data() + b.size());
  s.id.rhs = s.rhs.data();
  s.id.nrhs = 1;
  s.id.lrhs = static_cast<MUMPS_INT>(s.n);
  s.id.job = kSolve;
  dmumps_c(&s.id);
  s.id.rhs = nullptr;
  if (s.infog(1) < 0) s.throw_mumps_error("solve");
  return Eigen::Map<const Eigen::VectorXd>(s.rhs.data(), s.n);
}

int SymmetricIndefiniteFactorization::negative_eigenvalues() const {
  require_impl(impl_.get(), "negative_eigenvalues");
  if (!impl_->factorized) {
    throw std::logic_error(
        "SymmetricIndefiniteFactorization::negative_eigenvalues: no factorisation (call "
        "factorize())");
  }
  return impl_->negative;
}

int SymmetricIndefiniteFactorization::zero_pivots() const {
  require_impl(impl_.get(), "zero_pivots");
  if (!impl_->factorized) {
    throw std::logic_error(
        "SymmetricIndefiniteFactorization::zero_pivots: no factorisation (call factorize())");
  }
  return impl_->null_pivots;
}

Eigen::Index SymmetricIndefiniteFactorization::rows() const { return impl_ ? impl_->n : 0; }

std::string SymmetricIndefiniteFactorization::ordering_used() const {
  require_impl(impl_.get(), "ordering_used");
  if (!impl_->analyzed) {
    throw std::logic_error(
        "SymmetricIndefiniteFactorization::ordering_used: analyze() has not been called");
  }
  return ordering_name(impl_->infog(7));
}

}  // namespace growshell
