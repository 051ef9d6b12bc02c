#include "solvers/newton/cholmod_factorization.hpp"

#include "solvers/newton/upper_triangle_check.hpp"

#include <cholmod.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell {
namespace {

const char* cholmod_status_name(int status) {
  switch (status) {
    case CHOLMOD_OK:
      return "CHOLMOD_OK";
    case CHOLMOD_NOT_INSTALLED:
      return "CHOLMOD_NOT_INSTALLED (method not installed)";
    case CHOLMOD_OUT_OF_MEMORY:
      return "CHOLMOD_OUT_OF_MEMORY";
    case CHOLMOD_TOO_LARGE:
      return "CHOLMOD_TOO_LARGE (integer overflow)";
    case CHOLMOD_INVALID:
      return "CHOLMOD_INVALID (invalid input)";
    case CHOLMOD_GPU_PROBLEM:
      return "CHOLMOD_GPU_PROBLEM";
    case CHOLMOD_NOT_POSDEF:
      return "CHOLMOD_NOT_POSDEF (matrix not positive definite)";
    case CHOLMOD_DSMALL:
      return "CHOLMOD_DSMALL (tiny pivot)";
    default:
      return "unknown CHOLMOD status";
  }
}

// CHOLMOD reports every failure through Common->status as well; this handler exists only so
// that nothing is printed or aborted. It cannot carry state (plain function pointer).
void ignore_cholmod_error(int, const char*, int, const char*) {}

// Views an Eigen upper triangle as a CHOLMOD symmetric matrix without copying. CHOLMOD takes
// non-const pointers but does not write to an input matrix.
cholmod_sparse view_upper(const Eigen::SparseMatrix<double>& m) {
  cholmod_sparse a{};
  a.nrow = static_cast<size_t>(m.rows());
  a.ncol = static_cast<size_t>(m.cols());
  a.nzmax = static_cast<size_t>(m.nonZeros());
  a.p = const_cast<int*>(m.outerIndexPtr());
  a.i = const_cast<int*>(m.innerIndexPtr());
  a.nz = nullptr;
  a.x = const_cast<double*>(m.valuePtr());
  a.z = nullptr;
  a.stype = 1;  // upper triangle stored, lower implied
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;  // checked in analyze(); factorize() requires the identical pattern
  a.packed = 1;
  return a;
}

}  // namespace

struct CholmodFactorization::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* solution = nullptr;  // cholmod_solve2 workspace, reused across solves
  cholmod_dense* work_y = nullptr;
  cholmod_dense* work_e = nullptr;
  std::vector<int> outer;  // analysed pattern, to detect a changed pattern in factorize()
  std::vector<int> inner;
  Eigen::Index n = 0;
  bool factorized = false;
  double flops = 0.0;
  double lnz = 0.0;
  FillReducingOrdering ordering = FillReducingOrdering::Metis;

  explicit Impl(const CholmodOptions& options) : ordering(options.ordering) {
    if (!cholmod_start(&common)) {
      throw std::runtime_error("CholmodFactorization: cholmod_start failed");
    }
    common.print = 0;
    common.error_handler = &ignore_cholmod_error;
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_ll = 1;
    common.nmethods = 1;
    common.method[0].ordering =
        options.ordering == FillReducingOrdering::Metis ? CHOLMOD_METIS : CHOLMOD_AMD;
    common.postorder = 1;
  }
  ~Impl() {
    free_factor();
    cholmod_free_dense(&solution, &common);
    cholmod_free_dense(&work_y, &common);
    cholmod_free_dense(&work_e, &common);
    cholmod_finish(&common);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void free_factor() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    factorized = false;
  }

  void throw_on_error(const char* routine) const {
    if (common.status < 0) {
      throw std::runtime_error(std::string("CholmodFactorization: ") + routine + " failed with " +
                               cholmod_status_name(common.status));
    }
  }
};

CholmodFactorization::CholmodFactorization(CholmodOptions options)
    : impl_(std::make_unique<Impl>(options)) {}
CholmodFactorization::~CholmodFactorization() = default;
CholmodFactorization::CholmodFactorization(CholmodFactorization&&) noexcept = default;
CholmodFactorization& CholmodFactorization::operator=(CholmodFactorization&&) noexcept = default;

namespace {
void require_impl(const void* impl, const char* what) {
  if (impl == nullptr) {
    throw std::logic_error(std::string("CholmodFactorization::") + what +
                           ": object was moved from");
  }
}
}  // namespace

void CholmodFactorization::analyze(const Eigen::SparseMatrix<double>& upper) {
  require_impl(impl_.get(), "analyze");
  check_upper_triangle(upper, "CholmodFactorization::analyze");
  const Eigen::Index n = upper.cols();
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();

  Impl& s = *impl_;
  s.free_factor();
  s.n = 0;
  s.outer.clear();
  s.inner.clear();
  cholmod_sparse a = view_upper(upper);
  s.factor = cholmod_analyze(&a, &s.common);
  if (s.factor == nullptr || s.common.status < 0) {
    s.free_factor();
    s.throw_on_error("cholmod_analyze");
    throw std::runtime_error("CholmodFactorization: cholmod_analyze returned no factor");
  }
  s.n = n;
  s.outer.assign(outer, outer + n + 1);
  s.inner.assign(inner, inner + upper.nonZeros());
  s.flops = s.common.fl;
  s.lnz = s.common.lnz;
}

FactorizationResult CholmodFactorization::factorize(const Eigen::SparseMatrix<double>& upper,
                                                    double shift) {
  require_impl(impl_.get(), "factorize");
  Impl& s = *impl_;
  if (s.factor == nullptr) {
    throw std::logic_error("CholmodFactorization::factorize: analyze() has not been called");
  }
  if (!std::isfinite(shift)) {
    throw std::invalid_argument("CholmodFactorization::factorize: shift is not finite");
  }
  // CHOLMOD trusts the caller's pattern; a different one would silently corrupt L.
  const bool same_pattern =
      upper.rows() == s.n && upper.cols() == s.n && upper.isCompressed() &&
      static_cast<size_t>(upper.nonZeros()) == s.inner.size() &&
      std::memcmp(upper.outerIndexPtr(), s.outer.data(), s.outer.size() * sizeof(int)) == 0 &&
      std::memcmp(upper.innerIndexPtr(), s.inner.data(), s.inner.size() * sizeof(int)) == 0;
  if (!same_pattern) {
    throw std::runtime_error(
        "CholmodFactorization::factorize: sparsity pattern differs from the one passed to "
        "analyze() (" +
        std::to_string(upper.rows()) + " x " + std::to_string(upper.cols()) + " with " +
        std::to_string(upper.nonZeros()) + " entries vs " + std::to_string(s.n) + " x " +
        std::to_string(s.n) + " with " + std::to_string(s.inner.size()) + ")");
  }
  const double* values = upper.valuePtr();
  for (Eigen::Index col = 0; col < s.n; ++col) {
    for (int k = s.outer[col]; k < s.outer[col + 1]; ++k) {
      if (!std::isfinite(values[k])) {
        throw std::invalid_argument("CholmodFactorization::factorize: entry (" +
                                    std::to_string(s.inner[k]) + ", " + std::to_string(col) +
                                    ") is not finite");
      }
    }
  }

  s.factorized = false;
  cholmod_sparse a = view_upper(upper);
  double beta[2] = {shift, 0.0};
  cholmod_factorize_p(&a, beta, nullptr, 0, s.factor, &s.common);
  s.throw_on_error("cholmod_factorize_p");
  FactorizationResult result;
  if (s.common.status == CHOLMOD_NOT_POSDEF) {
    const size_t minor = s.factor->minor;
    if (minor < static_cast<size_t>(s.n)) {
      // L->minor counts columns of the permuted matrix; report the caller's column.
      const int* perm = static_cast<const int*>(s.factor->Perm);
      result.failed_column = perm != nullptr ? perm[minor] : static_cast<int>(minor);
    }
    return result;
  }
  s.factorized = true;
  result.positive_definite = true;
  return result;
}

Eigen::VectorXd CholmodFactorization::solve(const Eigen::Ref<const Eigen::VectorXd>& b) const {
  require_impl(impl_.get(), "solve");
  Impl& s = *impl_;
  if (!s.factorized) {
    throw std::logic_error(
        "CholmodFactorization::solve: no successful factorisation (call factorize() and check "
        "positive_definite)");
  }
  if (b.size() != s.n) {
    throw std::invalid_argument("CholmodFactorization::solve: right-hand side has size " +
                                std::to_string(b.size()) + ", expected " + std::to_string(s.n));
  }
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(s.n);
  rhs.ncol = 1;
  rhs.nzmax = static_cast<size_t>(s.n);
  rhs.d = static_cast<size_t>(s.n);
  rhs.x = const_cast<double*>(b.data());  // read only by CHOLMOD
  rhs.z = nullptr;
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_solve2(CHOLMOD_A, s.factor, &rhs, nullptr, &s.solution, nullptr, &s.work_y,
                      &s.work_e, &s.common) ||
      s.common.status < 0) {
    s.throw_on_error("cholmod_solve2");
    throw std::runtime_error("CholmodFactorization: cholmod_solve2 failed");
  }
  return Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(s.solution->x), s.n);
}

Eigen::Index CholmodFactorization::rows() const { return impl_ ? impl_->n : 0; }
double CholmodFactorization::factorization_flops() const { return impl_ ? impl_->flops : 0.0; }
double CholmodFactorization::factor_nonzeros() const { return impl_ ? impl_->lnz : 0.0; }
FillReducingOrdering CholmodFactorization::ordering() const {
  require_impl(impl_.get(), "ordering");
  return impl_->ordering;
}

const char* to_string(FillReducingOrdering ordering) {
  switch (ordering) {
    case FillReducingOrdering::Metis:
      return "METIS";
    case FillReducingOrdering::Amd:
      return "AMD";
  }
  return "unknown";
}

}  // namespace growshell
