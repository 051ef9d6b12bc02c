#include "solvers/contact/contact_stability.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

namespace growshell {
namespace {

constexpr const char* kWho = "contact_constrained_inertia";

using RowMajorJacobian = Eigen::SparseMatrix<double, Eigen::RowMajor>;

void require_finite(const Eigen::SparseMatrix<double>& upper, const char* what) {
  for (Eigen::Index col = 0; col < upper.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, col); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw std::invalid_argument(std::string(kWho) + ": the " + what + " Hessian entry (" +
                                    std::to_string(it.row()) + ", " + std::to_string(col) +
                                    ") is not finite at x");
      }
    }
  }
}

void require_size(Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                  Eigen::Index want_cols, const char* what) {
  if (rows != want_rows || cols != want_cols) {
    throw std::invalid_argument(std::string(kWho) + ": the " + what + " is " +
                                std::to_string(rows) + " x " + std::to_string(cols) +
                                ", expected " + std::to_string(want_rows) + " x " +
                                std::to_string(want_cols));
  }
}

}  // namespace

ReducedInertia contact_constrained_inertia(SparseObjective& energy,
                                           InequalityConstraints& constraints,
                                           const Eigen::Ref<const Eigen::VectorXd>& x,
                                           const Eigen::Ref<const Eigen::VectorXd>& multipliers,
                                           double active_force_threshold,
                                           const std::vector<Eigen::Index>& fixed_dofs,
                                           const SymmetricIndefiniteOptions& options) {
  const Eigen::Index n = energy.dimension();
  const Eigen::Index m = constraints.count();
  if (constraints.dimension() != n) {
    throw std::invalid_argument(std::string(kWho) + ": the energy has " + std::to_string(n) +
                                " unknowns but the constraints have " +
                                std::to_string(constraints.dimension()));
  }
  if (x.size() != n) {
    throw std::invalid_argument(std::string(kWho) + ": x has size " + std::to_string(x.size()) +
                                ", expected " + std::to_string(n));
  }
  if (multipliers.size() != m) {
    throw std::invalid_argument(std::string(kWho) + ": multipliers has size " +
                                std::to_string(multipliers.size()) + ", expected " +
                                std::to_string(m) + " (one per constraint)");
  }
  for (Eigen::Index k = 0; k < m; ++k) {
    if (!std::isfinite(multipliers(k)) || multipliers(k) < 0.0) {
      throw std::invalid_argument(std::string(kWho) + ": multiplier " + std::to_string(k) +
                                  " is " + std::to_string(multipliers(k)) +
                                  ", must be finite and >= 0 (a contact force)");
    }
  }
  if (!std::isfinite(active_force_threshold) || active_force_threshold < 0.0) {
    throw std::invalid_argument(std::string(kWho) + ": active_force_threshold is " +
                                std::to_string(active_force_threshold) +
                                ", must be finite and >= 0");
  }

  Eigen::SparseMatrix<double> energy_hessian = energy.hessian_pattern();
  require_size(energy_hessian.rows(), energy_hessian.cols(), n, n, "energy Hessian pattern");
  energy.evaluate(x, nullptr, &energy_hessian);
  require_finite(energy_hessian, "energy");

  // H_L = d2E - sum mu_k d2c_k. The two patterns differ (contact couples dofs the energy does
  // not, e.g. two layers of the sheet); the sparse difference has the union of the patterns,
  // and as both operands are upper triangles, so is the result.
  Eigen::SparseMatrix<double> lagrangian_hessian;
  Eigen::SparseMatrix<double> active_jacobian;  // rows: the strongly active constraints
  if (m == 0) {
    lagrangian_hessian = energy_hessian;
    active_jacobian.resize(0, n);
  } else {
    Eigen::SparseMatrix<double> constraint_hessian = constraints.hessian_pattern();
    require_size(constraint_hessian.rows(), constraint_hessian.cols(), n, n,
                 "constraint Hessian pattern");
    constraints.weighted_hessian(x, multipliers, constraint_hessian);
    require_finite(constraint_hessian, "multiplier-weighted constraint");
    lagrangian_hessian = energy_hessian - constraint_hessian;

    RowMajorJacobian jacobian = constraints.jacobian_pattern();
    require_size(jacobian.rows(), jacobian.cols(), m, n, "constraint Jacobian pattern");
    Eigen::VectorXd values;
    constraints.evaluate(x, values, &jacobian);
    Eigen::Index active = 0;
    for (Eigen::Index k = 0; k < m; ++k) active += multipliers(k) > active_force_threshold;
    std::vector<Eigen::Triplet<double>> entries;
    active_jacobian.resize(active, n);
    Eigen::Index row = 0;
    for (Eigen::Index k = 0; k < m; ++k) {
      if (!(multipliers(k) > active_force_threshold)) continue;
      for (RowMajorJacobian::InnerIterator it(jacobian, k); it; ++it) {
        if (!std::isfinite(it.value())) {
          throw std::invalid_argument(std::string(kWho) + ": the Jacobian of constraint " +
                                      std::to_string(k) + " has a non-finite entry at dof " +
                                      std::to_string(it.col()));
        }
        entries.emplace_back(row, it.col(), it.value());
      }
      ++row;
    }
    active_jacobian.setFromTriplets(entries.begin(), entries.end());
  }
  lagrangian_hessian.makeCompressed();
  return reduced_hessian_inertia(lagrangian_hessian, active_jacobian, fixed_dofs, options);
}

}  // namespace growshell
