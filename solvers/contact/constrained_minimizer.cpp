#include "solvers/contact/constrained_minimizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "solvers/newton/upper_triangle_check.hpp"

namespace growshell {
namespace {

using Ipopt::Index;
using Ipopt::Number;
using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Ipopt treats bounds at or beyond these as absent; we set the options to the same values
// explicitly so that the bounds we pass and the options cannot drift apart.
constexpr double kLowerInf = -1e19;
constexpr double kUpperInf = 1e19;

std::string sci(double v) {
  std::ostringstream s;
  s.precision(3);
  s << std::scientific << v;
  return s.str();
}

[[noreturn]] void invalid(const std::string& what) {
  throw std::invalid_argument("minimize_with_constraints: " + what);
}

void check_options(const ConstrainedMinimizerOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      invalid(std::string("option ") + name + " = " + sci(v) + " must be finite and > 0");
    }
  };
  positive(o.length_scale, "length_scale");
  positive(o.force_scale, "force_scale");
  positive(o.tolerance, "tolerance");
  positive(o.constraint_violation_tolerance, "constraint_violation_tolerance");
  positive(o.complementarity_tolerance, "complementarity_tolerance");
  positive(o.dual_infeasibility_tolerance, "dual_infeasibility_tolerance");
  positive(o.acceptable_tolerance, "acceptable_tolerance");
  positive(o.warm_start_barrier, "warm_start_barrier");
  if (o.acceptable_tolerance < o.tolerance) {
    invalid("option acceptable_tolerance = " + sci(o.acceptable_tolerance) +
            " must be >= tolerance = " + sci(o.tolerance));
  }
  if (o.acceptable_iterations < 0) {
    invalid("option acceptable_iterations = " + std::to_string(o.acceptable_iterations) +
            " must be >= 0");
  }
  if (o.max_iterations < 0) {
    invalid("option max_iterations = " + std::to_string(o.max_iterations) + " must be >= 0");
  }
  if (!(o.bound_push > 0.0 && o.bound_push <= 0.5)) {
    invalid("option bound_push = " + sci(o.bound_push) + " must lie in (0, 0.5]");
  }
  if (!(o.warm_start_push > 0.0 && o.warm_start_push <= 0.5)) {
    invalid("option warm_start_push = " + sci(o.warm_start_push) + " must lie in (0, 0.5]");
  }
  if (o.print_level < 0 || o.print_level > 12) {
    invalid("option print_level = " + std::to_string(o.print_level) + " must lie in 0..12");
  }
}

// True iff the structure of `m` is still the one of `pattern` (same sizes, compressed, same
// column/row starts and inner indices), i.e. the value arrays correspond entry by entry.
template <class Matrix>
bool same_structure(const Matrix& m, const Matrix& pattern) {
  if (m.rows() != pattern.rows() || m.cols() != pattern.cols() || !m.isCompressed() ||
      m.nonZeros() != pattern.nonZeros()) {
    return false;
  }
  const auto outer = static_cast<std::size_t>(m.outerSize() + 1);
  const auto nnz = static_cast<std::size_t>(m.nonZeros());
  return std::equal(m.outerIndexPtr(), m.outerIndexPtr() + outer, pattern.outerIndexPtr()) &&
         std::equal(m.innerIndexPtr(), m.innerIndexPtr() + nnz, pattern.innerIndexPtr());
}

// Position of every entry of the upper pattern `part` in the value array of `whole`, whose
// structure contains it (both compressed with sorted row indices per column).
std::vector<Index> positions_in(const Eigen::SparseMatrix<double>& part,
                                const Eigen::SparseMatrix<double>& whole) {
  std::vector<Index> where;
  where.reserve(static_cast<std::size_t>(part.nonZeros()));
  for (Eigen::Index j = 0; j < part.outerSize(); ++j) {
    const int* begin = whole.innerIndexPtr() + whole.outerIndexPtr()[j];
    const int* end = whole.innerIndexPtr() + whole.outerIndexPtr()[j + 1];
    for (Eigen::SparseMatrix<double>::InnerIterator it(part, j); it; ++it) {
      const int* at = std::lower_bound(begin, end, static_cast<int>(it.row()));
      where.push_back(static_cast<Index>(at - whole.innerIndexPtr()));
    }
  }
  return where;
}

bool same_point(const Eigen::VectorXd& cached, const Number* x) {
  return cached.size() > 0 &&
         std::memcmp(cached.data(), x, sizeof(double) * static_cast<std::size_t>(cached.size())) ==
             0;
}

// The problem as Ipopt sees it. Ipopt's Lagrangian is sigma E + sum lambda_k c_k with
// lambda_k <= 0 at an active lower bound c_k >= 0; our multipliers are mu = -lambda.
class ContactNlp final : public Ipopt::TNLP {
 public:
  ContactNlp(SparseObjective& energy, InequalityConstraints& constraints,
             const Eigen::Ref<const Eigen::VectorXd>& x0, const std::vector<char>& is_fixed,
             const ConstrainedMinimizerOptions& options, const Eigen::VectorXd* multipliers)
      : energy_(energy),
        constraints_(constraints),
        x0_(x0),
        is_fixed_(is_fixed),
        options_(options),
        initial_multipliers_(multipliers),
        n_(x0.size()),
        m_(constraints.count()) {
    energy_hessian_ = energy.hessian_pattern();
    if (energy_hessian_.rows() != n_ || energy_hessian_.cols() != n_) {
      invalid("energy.hessian_pattern() is " + std::to_string(energy_hessian_.rows()) + " x " +
              std::to_string(energy_hessian_.cols()) + ", expected " + std::to_string(n_) + " x " +
              std::to_string(n_));
    }
    check_upper_triangle(energy_hessian_, "minimize_with_constraints: energy.hessian_pattern()");
    constraint_hessian_ = constraints.hessian_pattern();
    if (constraint_hessian_.rows() != n_ || constraint_hessian_.cols() != n_) {
      invalid("constraints.hessian_pattern() is " + std::to_string(constraint_hessian_.rows()) +
              " x " + std::to_string(constraint_hessian_.cols()) + ", expected " +
              std::to_string(n_) + " x " + std::to_string(n_));
    }
    check_upper_triangle(constraint_hessian_,
                         "minimize_with_constraints: constraints.hessian_pattern()");
    jacobian_ = constraints.jacobian_pattern();
    if (jacobian_.rows() != m_ || jacobian_.cols() != n_ || !jacobian_.isCompressed()) {
      invalid("constraints.jacobian_pattern() is " + std::to_string(jacobian_.rows()) + " x " +
              std::to_string(jacobian_.cols()) +
              (jacobian_.isCompressed() ? "" : " (not compressed)") + ", expected compressed " +
              std::to_string(m_) + " x " + std::to_string(n_));
    }
    energy_pattern_ = energy_hessian_;
    constraint_pattern_ = constraint_hessian_;
    jacobian_pattern_ = jacobian_;

    // Union of the two upper patterns: the structure of the Lagrangian's Hessian.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(energy_hessian_.nonZeros() +
                                             constraint_hessian_.nonZeros()));
    for (const Eigen::SparseMatrix<double>* p : {&energy_hessian_, &constraint_hessian_}) {
      for (Eigen::Index j = 0; j < p->outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(*p, j); it; ++it) {
          entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(j), 1.0);
        }
      }
    }
    lagrangian_hessian_.resize(n_, n_);
    lagrangian_hessian_.setFromTriplets(entries.begin(), entries.end());
    lagrangian_hessian_.makeCompressed();
    energy_positions_ = positions_in(energy_hessian_, lagrangian_hessian_);
    constraint_positions_ = positions_in(constraint_hessian_, lagrangian_hessian_);
    const double max_index = static_cast<double>(std::numeric_limits<Index>::max());
    if (static_cast<double>(lagrangian_hessian_.nonZeros()) > max_index ||
        static_cast<double>(jacobian_.nonZeros()) > max_index) {
      invalid("the Hessian or Jacobian has more entries than Ipopt's int index can address");
    }
    constraint_values_.resize(m_);
  }

  // Outcome, filled by finalize_solution() and the callbacks.
  bool finalized = false;
  Eigen::VectorXd final_x;
  Eigen::VectorXd final_multipliers;
  int last_iteration = 0;
  int non_finite_energy_evaluations = 0;
  std::exception_ptr error;

  // E at x (value only; reuses the cache when x was the last point evaluated).
  double energy_at(const Eigen::VectorXd& x) {
    if (!ensure_energy(x.data(), false)) return std::numeric_limits<double>::quiet_NaN();
    return energy_value_;
  }
  // max(0, max_k -c_k(x)).
  double violation_at(const Eigen::VectorXd& x) {
    if (m_ == 0) return 0.0;
    ensure_constraints(x.data());
    return std::max(0.0, -constraint_values_.minCoeff());
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = static_cast<Index>(n_);
    m = static_cast<Index>(m_);
    nnz_jac_g = static_cast<Index>(jacobian_.nonZeros());
    nnz_h_lag = static_cast<Index>(lagrangian_hessian_.nonZeros());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      if (is_fixed_[static_cast<std::size_t>(i)] != 0) {
        x_l[i] = x_u[i] = x0_[i];  // fixed_variable_treatment make_parameter removes them
      } else {
        x_l[i] = kLowerInf;
        x_u[i] = kUpperInf;
      }
    }
    for (Index k = 0; k < m; ++k) {
      g_l[k] = 0.0;
      g_u[k] = kUpperInf;
    }
    return true;
  }

  bool get_scaling_parameters(Number& obj_scaling, bool& use_x_scaling, Index n,
                              Number* x_scaling, bool& use_g_scaling, Index m,
                              Number* g_scaling) override {
    // See ConstrainedMinimizerOptions: x~ = x / L, E~ = E / (F L), c~ = c / L.
    const double length = options_.length_scale;
    obj_scaling = 1.0 / (options_.force_scale * length);
    use_x_scaling = true;
    std::fill(x_scaling, x_scaling + n, 1.0 / length);
    use_g_scaling = true;
    std::fill(g_scaling, g_scaling + m, 1.0 / length);
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_L,
                          Number* z_U, Index m, bool init_lambda, Number* lambda) override {
    if (init_x) std::copy(x0_.data(), x0_.data() + n, x);
    // No free variable has a bound (fixed ones are removed), so the bound duals are unused.
    if (init_z) {
      std::fill(z_L, z_L + n, 0.0);
      std::fill(z_U, z_U + n, 0.0);
    }
    if (init_lambda) {
      for (Index k = 0; k < m; ++k) {
        lambda[k] = initial_multipliers_ != nullptr ? -(*initial_multipliers_)[k] : 0.0;
      }
    }
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj_value) override {
    if (error) return false;
    if (!guarded([&] { return ensure_energy(x, false); })) return false;
    obj_value = energy_value_;
    return true;
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    if (error) return false;
    if (!guarded([&] { return ensure_energy(x, false); })) return false;
    if (!energy_gradient_.allFinite()) return false;
    std::copy(energy_gradient_.data(), energy_gradient_.data() + n, grad_f);
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    if (error) return false;
    if (!guarded([&] {
          ensure_constraints(x);
          return constraint_values_.allFinite();
        })) {
      return false;
    }
    std::copy(constraint_values_.data(), constraint_values_.data() + m, g);
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* iRow, Index* jCol,
                  Number* values) override {
    if (error) return false;
    if (values == nullptr) {
      Index e = 0;
      for (Eigen::Index k = 0; k < jacobian_.outerSize(); ++k) {
        for (RowMajorMatrix::InnerIterator it(jacobian_, k); it; ++it, ++e) {
          iRow[e] = static_cast<Index>(k);
          jCol[e] = static_cast<Index>(it.col());
        }
      }
      return true;
    }
    if (!guarded([&] {
          ensure_constraints(x);
          return Eigen::Map<const Eigen::VectorXd>(jacobian_.valuePtr(), jacobian_.nonZeros())
              .allFinite();
        })) {
      return false;
    }
    std::copy(jacobian_.valuePtr(), jacobian_.valuePtr() + jacobian_.nonZeros(), values);
    return true;
  }

  bool eval_h(Index, const Number* x, bool, Number obj_factor, Index m, const Number* lambda,
              bool, Index nele_hess, Index* iRow, Index* jCol, Number* values) override {
    if (error) return false;
    if (values == nullptr) {
      // Ipopt wants the lower triangle (row >= column); our patterns are upper, so transpose.
      Index e = 0;
      for (Eigen::Index j = 0; j < lagrangian_hessian_.outerSize(); ++j) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(lagrangian_hessian_, j); it; ++it, ++e) {
          iRow[e] = static_cast<Index>(j);
          jCol[e] = static_cast<Index>(it.row());
        }
      }
      return true;
    }
    return guarded([&] {
      std::fill(values, values + nele_hess, 0.0);
      if (obj_factor != 0.0) {
        if (!ensure_energy(x, true)) return false;
        const double* h = energy_hessian_.valuePtr();
        for (std::size_t e = 0; e < energy_positions_.size(); ++e) {
          values[energy_positions_[e]] += obj_factor * h[e];
        }
      }
      if (m > 0 && !constraint_positions_.empty()) {
        // Ipopt's lambda (= -mu) are exactly the weights of its Lagrangian.
        const Eigen::Map<const Eigen::VectorXd> weights(lambda, m);
        constraints_.weighted_hessian(Eigen::Map<const Eigen::VectorXd>(x, n_), weights,
                                      constraint_hessian_);
        if (!same_structure(constraint_hessian_, constraint_pattern_)) {
          throw std::runtime_error(
              "minimize_with_constraints: constraints.weighted_hessian() changed the structure "
              "of hessian_pattern()");
        }
        const double* h = constraint_hessian_.valuePtr();
        for (std::size_t e = 0; e < constraint_positions_.size(); ++e) {
          values[constraint_positions_[e]] += h[e];
        }
      }
      return Eigen::Map<const Eigen::VectorXd>(values, nele_hess).allFinite();
    });
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*,
                         const Number*, Index m, const Number*, const Number* lambda, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    finalized = true;
    final_x = Eigen::Map<const Eigen::VectorXd>(x, n);
    // 0 - lambda rather than -lambda: an inactive constraint reads +0, not -0.
    final_multipliers = Eigen::VectorXd::Zero(m) - Eigen::Map<const Eigen::VectorXd>(lambda, m);
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index iter, Number, Number, Number, Number,
                             Number, Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    last_iteration = static_cast<int>(iter);
    return !error;  // stop as soon as a callback has thrown
  }

 private:
  // Runs f, turning an exception into a stored error (rethrown once Ipopt has returned, since
  // exceptions must not cross Ipopt's frames) and a failed evaluation.
  template <class F>
  bool guarded(F&& f) {
    try {
      return f();
    } catch (...) {
      error = std::current_exception();
      return false;
    }
  }

  // Energy value and gradient (and Hessian if `hessian`) at x, from the cache when x is the
  // point of the last evaluation. Returns false if the energy or gradient is not finite.
  bool ensure_energy(const Number* x, bool hessian) {
    const bool same = same_point(energy_x_, x);
    if (!same || (hessian && !energy_has_hessian_)) {
      const Eigen::Map<const Eigen::VectorXd> xv(x, n_);
      energy_x_.resize(0);  // invalid until evaluate() has returned
      energy_has_hessian_ = false;
      energy_value_ = energy_.evaluate(xv, &energy_gradient_, hessian ? &energy_hessian_ : nullptr);
      energy_finite_ = std::isfinite(energy_value_) && energy_gradient_.size() == n_ &&
                       energy_gradient_.allFinite();
      if (!energy_finite_) ++non_finite_energy_evaluations;
      if (hessian) {
        if (!same_structure(energy_hessian_, energy_pattern_)) {
          throw std::runtime_error(
              "minimize_with_constraints: energy.evaluate() changed the structure of "
              "hessian_pattern()");
        }
        energy_has_hessian_ = true;
      }
      energy_x_ = xv;
    }
    return energy_finite_;
  }

  void ensure_constraints(const Number* x) {
    if (same_point(constraints_x_, x)) return;
    const Eigen::Map<const Eigen::VectorXd> xv(x, n_);
    constraints_x_.resize(0);  // invalid until evaluate() has returned
    constraints_.evaluate(xv, constraint_values_, &jacobian_);
    if (constraint_values_.size() != m_) {
      throw std::runtime_error("minimize_with_constraints: constraints.evaluate() returned " +
                               std::to_string(constraint_values_.size()) + " values, count() is " +
                               std::to_string(m_));
    }
    if (!same_structure(jacobian_, jacobian_pattern_)) {
      throw std::runtime_error(
          "minimize_with_constraints: constraints.evaluate() changed the structure of "
          "jacobian_pattern()");
    }
    constraints_x_ = xv;
  }

  SparseObjective& energy_;
  InequalityConstraints& constraints_;
  Eigen::VectorXd x0_;
  const std::vector<char>& is_fixed_;
  const ConstrainedMinimizerOptions& options_;
  const Eigen::VectorXd* initial_multipliers_;
  Eigen::Index n_;
  Eigen::Index m_;

  Eigen::SparseMatrix<double> energy_pattern_, energy_hessian_;
  Eigen::SparseMatrix<double> constraint_pattern_, constraint_hessian_;
  Eigen::SparseMatrix<double> lagrangian_hessian_;
  std::vector<Index> energy_positions_, constraint_positions_;
  RowMajorMatrix jacobian_pattern_, jacobian_;

  // Evaluation caches: Ipopt asks for f, grad f and the Hessian at the same x in separate
  // calls, and one energy evaluation serves all of them.
  Eigen::VectorXd energy_x_;
  double energy_value_ = 0.0;
  bool energy_finite_ = false;
  bool energy_has_hessian_ = false;
  Eigen::VectorXd energy_gradient_;
  Eigen::VectorXd constraints_x_;
  Eigen::VectorXd constraint_values_;
};

void set_option(Ipopt::OptionsList& list, const std::string& name, const std::string& value) {
  if (!list.SetStringValue(name, value)) {
    invalid("Ipopt rejected option " + name + " = \"" + value + "\"");
  }
}
void set_option(Ipopt::OptionsList& list, const std::string& name, double value) {
  if (!list.SetNumericValue(name, value)) {
    invalid("Ipopt rejected option " + name + " = " + sci(value));
  }
}
void set_option(Ipopt::OptionsList& list, const std::string& name, int value) {
  if (!list.SetIntegerValue(name, value)) {
    invalid("Ipopt rejected option " + name + " = " + std::to_string(value));
  }
}

}  // namespace

std::string ipopt_status_message(int status) {
  switch (status) {
    case Ipopt::Solve_Succeeded: return "Ipopt: converged";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Ipopt: converged to the acceptable level (absolute tolerances met, relative "
             "tolerance not)";
    case Ipopt::Infeasible_Problem_Detected:
      return "Ipopt: local infeasibility (no point near the iterates satisfies the constraints)";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Ipopt: search direction became too small (stalled)";
    case Ipopt::Diverging_Iterates:
      return "Ipopt: diverging iterates (energy unbounded below?)";
    case Ipopt::User_Requested_Stop: return "Ipopt: stopped by the caller";
    case Ipopt::Feasible_Point_Found: return "Ipopt: feasible point found";
    case Ipopt::Maximum_Iterations_Exceeded: return "Ipopt: maximum iterations exceeded";
    case Ipopt::Restoration_Failed:
      return "Ipopt: restoration failed (could not regain feasibility or progress)";
    case Ipopt::Error_In_Step_Computation:
      return "Ipopt: error in step computation (singular or indefinite KKT system)";
    case Ipopt::Maximum_CpuTime_Exceeded: return "Ipopt: maximum CPU time exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom: return "Ipopt: not enough degrees of freedom";
    case Ipopt::Invalid_Problem_Definition: return "Ipopt: invalid problem definition";
    case Ipopt::Invalid_Option: return "Ipopt: invalid option";
    case Ipopt::Invalid_Number_Detected:
      return "Ipopt: error in evaluating the energy or constraints (NaN or Inf)";
    case Ipopt::Unrecoverable_Exception: return "Ipopt: unrecoverable exception";
    case Ipopt::NonIpopt_Exception_Thrown: return "Ipopt: exception thrown by the problem";
    case Ipopt::Insufficient_Memory: return "Ipopt: insufficient memory";
    case Ipopt::Internal_Error: return "Ipopt: internal error";
    default: return "Ipopt: unknown return status " + std::to_string(status);
  }
}

ConstrainedResult minimize_with_constraints(SparseObjective& energy,
                                            InequalityConstraints& constraints,
                                            const Eigen::Ref<const Eigen::VectorXd>& x0,
                                            const std::vector<Eigen::Index>& fixed_dofs,
                                            const ConstrainedMinimizerOptions& options,
                                            const Eigen::VectorXd* initial_multipliers) {
  check_options(options);
  const Eigen::Index n = energy.dimension();
  const Eigen::Index m = constraints.count();
  if (x0.size() != n) {
    invalid("x0 has size " + std::to_string(x0.size()) + ", energy dimension is " +
            std::to_string(n));
  }
  if (constraints.dimension() != n) {
    invalid("constraints.dimension() = " + std::to_string(constraints.dimension()) +
            " differs from energy.dimension() = " + std::to_string(n));
  }
  if (m < 0) invalid("constraints.count() = " + std::to_string(m) + " is negative");
  if (!x0.allFinite()) invalid("x0 is not finite");
  std::vector<char> is_fixed(static_cast<std::size_t>(n), 0);
  for (const Eigen::Index dof : fixed_dofs) {
    if (dof < 0 || dof >= n) {
      invalid("fixed dof " + std::to_string(dof) + " is outside 0.." + std::to_string(n - 1));
    }
    if (is_fixed[static_cast<std::size_t>(dof)] != 0) {
      invalid("fixed dof " + std::to_string(dof) + " is listed twice");
    }
    is_fixed[static_cast<std::size_t>(dof)] = 1;
  }
  const bool warm = options.warm_start && initial_multipliers != nullptr;
  if (initial_multipliers != nullptr) {
    if (initial_multipliers->size() != m) {
      invalid("initial_multipliers has size " + std::to_string(initial_multipliers->size()) +
              ", constraints.count() is " + std::to_string(m));
    }
    for (Eigen::Index k = 0; k < m; ++k) {
      const double mu = (*initial_multipliers)[k];
      if (!(mu >= 0.0) || !std::isfinite(mu)) {
        invalid("initial multiplier " + std::to_string(k) + " = " + sci(mu) +
                " must be finite and >= 0");
      }
    }
  }

  Ipopt::SmartPtr<ContactNlp> nlp =
      new ContactNlp(energy, constraints, x0, is_fixed, options, initial_multipliers);

  // No console journal unless asked for: the library never prints.
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app =
      new Ipopt::IpoptApplication(options.print_level > 0, false);
  Ipopt::OptionsList& o = *app->Options();
  set_option(o, "print_level", options.print_level);
  set_option(o, "sb", std::string("yes"));
  set_option(o, "hessian_approximation", std::string("exact"));
  set_option(o, "fixed_variable_treatment", std::string("make_parameter"));
  set_option(o, "nlp_scaling_method", std::string("user-scaling"));
  set_option(o, "nlp_lower_bound_inf", kLowerInf);
  set_option(o, "nlp_upper_bound_inf", kUpperInf);
  set_option(o, "linear_solver", options.linear_solver);
  // MUMPS' automatic ordering can pick threaded SCOTCH, which was seen to hang in its thread
  // launch (Debian's scotch 7, a 5.7k-unknown skewed cone); METIS, as CHOLMOD uses, does not.
  if (options.linear_solver == "mumps") set_option(o, "mumps_pivot_order", 5);
  set_option(o, "max_iter", options.max_iterations);
  set_option(o, "tol", options.tolerance);
  set_option(o, "constr_viol_tol", options.constraint_violation_tolerance);
  set_option(o, "compl_inf_tol", options.complementarity_tolerance);
  set_option(o, "dual_inf_tol", options.dual_infeasibility_tolerance);
  set_option(o, "acceptable_tol", options.acceptable_tolerance);
  set_option(o, "acceptable_iter", options.acceptable_iterations);
  set_option(o, "acceptable_constr_viol_tol", options.constraint_violation_tolerance);
  set_option(o, "acceptable_compl_inf_tol", options.complementarity_tolerance);
  set_option(o, "acceptable_dual_inf_tol", options.dual_infeasibility_tolerance);
  // Ipopt relaxes the bound c >= 0 to c >= -bound_relax_factor (unscaled units, since the
  // bound is 0) and measures its violation against the relaxed bound, so the relaxation adds
  // to the true violation: keep it at a tenth of the tolerance.
  set_option(o, "bound_relax_factor", std::min(1e-8, 0.1 * options.constraint_violation_tolerance));
  set_option(o, "bound_push", options.bound_push);
  set_option(o, "bound_frac", options.bound_push);
  if (warm) {
    set_option(o, "warm_start_init_point", std::string("yes"));
    set_option(o, "warm_start_bound_push", options.warm_start_push);
    set_option(o, "warm_start_bound_frac", options.warm_start_push);
    set_option(o, "warm_start_slack_bound_push", options.warm_start_push);
    set_option(o, "warm_start_slack_bound_frac", options.warm_start_push);
    set_option(o, "warm_start_mult_bound_push", options.warm_start_push);
    set_option(o, "mu_init", options.warm_start_barrier);
  }
  // "" skips the options file: a stray ./ipopt.opt must not change the library's behaviour.
  const Ipopt::ApplicationReturnStatus init = app->Initialize(std::string());
  if (init != Ipopt::Solve_Succeeded) {
    invalid("Ipopt initialisation failed: " + ipopt_status_message(static_cast<int>(init)));
  }

  const Ipopt::ApplicationReturnStatus status =
      app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(Ipopt::GetRawPtr(nlp)));
  if (nlp->error) std::rethrow_exception(nlp->error);
  if (status == Ipopt::Invalid_Option) {
    invalid("Ipopt rejected the options (e.g. linear_solver = \"" + options.linear_solver +
            "\" is not available in this build)");
  }

  ConstrainedResult result;
  result.status = static_cast<int>(status);
  result.iterations = nlp->last_iteration;
  result.x = x0;
  result.multipliers = Eigen::VectorXd::Zero(m);
  const int non_finite = nlp->non_finite_energy_evaluations;
  bool have_final = false;
  double e = std::numeric_limits<double>::quiet_NaN();
  if (nlp->finalized && nlp->final_x.allFinite()) {
    e = nlp->energy_at(nlp->final_x);
    if (std::isfinite(e)) {
      have_final = true;
      result.x = nlp->final_x;
      if (nlp->final_multipliers.allFinite()) result.multipliers = nlp->final_multipliers;
    }
  }
  if (!have_final) e = nlp->energy_at(result.x);
  result.energy = e;
  result.max_violation = nlp->violation_at(result.x);

  std::string detail = std::to_string(result.iterations) + " iterations, max violation " +
                       sci(result.max_violation);
  if (non_finite > 0) {
    detail += ", " + std::to_string(non_finite) +
              " evaluations with a non-finite energy or gradient";
  }
  if (!have_final) detail += ", x is x0";
  result.message = ipopt_status_message(result.status) + " (" + detail + ")";
  return result;
}

}  // namespace growshell
