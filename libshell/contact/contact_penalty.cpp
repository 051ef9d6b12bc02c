#include "libshell/contact/contact_penalty.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace growshell {

namespace {

void check_stiffness(double stiffness) {
  if (!std::isfinite(stiffness) || stiffness < 0.0)
    throw std::invalid_argument("ContactPenalty: stiffness " + std::to_string(stiffness) +
                                " N/m must be finite and >= 0");
}

/// Throws unless `m` is a compressed n x n matrix with entries in its upper triangle only.
void check_upper_pattern(const Eigen::SparseMatrix<double>& m, Eigen::Index n, const char* name) {
  std::ostringstream s;
  if (m.rows() != n || m.cols() != n) {
    s << "PenalizedEnergy: the " << name << " Hessian pattern is " << m.rows() << " x " << m.cols()
      << ", expected " << n << " x " << n;
    throw std::invalid_argument(s.str());
  }
  if (!m.isCompressed()) {
    s << "PenalizedEnergy: the " << name << " Hessian pattern is not compressed";
    throw std::invalid_argument(s.str());
  }
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, j); it; ++it)
      if (it.row() > j) {
        s << "PenalizedEnergy: the " << name << " Hessian pattern has entry (" << it.row() << ", "
          << j << ") below the diagonal";
        throw std::invalid_argument(s.str());
      }
}

}  // namespace

double contact_stiffness_scale(double youngs_modulus, double thickness, double spacing) {
  const auto check = [](double v, const char* name) {
    if (!std::isfinite(v) || v <= 0.0)
      throw std::invalid_argument(std::string("contact_stiffness_scale: ") + name + " " +
                                  std::to_string(v) + " must be finite and > 0");
  };
  check(youngs_modulus, "youngs_modulus");
  check(thickness, "thickness");
  check(spacing, "spacing");
  return youngs_modulus * spacing * spacing / thickness;
}

double proxy_mean_edge_length(const ContactProxy& proxy) {
  const Eigen::Index n = proxy.edges.rows();
  if (n == 0) throw std::invalid_argument("proxy_mean_edge_length: the proxy has no edges");
  const Eigen::MatrixX3d& X = proxy.reference_positions;
  double sum = 0.0;
  for (Eigen::Index e = 0; e < n; ++e) {
    const int a = proxy.edges(e, 0);
    const int b = proxy.edges(e, 1);
    if (a < 0 || b < 0 || a >= X.rows() || b >= X.rows()) {
      std::ostringstream s;
      s << "proxy_mean_edge_length: edge " << e << " (" << a << ", " << b
        << ") has a vertex outside [0, " << X.rows() << ")";
      throw std::invalid_argument(s.str());
    }
    sum += (X.row(a) - X.row(b)).norm();
  }
  return sum / static_cast<double>(n);
}

// ---- ContactPenalty ------------------------------------------------------------------------

ContactPenalty::ContactPenalty(const ContactProxy& proxy, const ContactCandidates& pairs,
                               double offset, double stiffness, Eigen::Index dimension,
                               ContactGapOptions options)
    : constraints_(proxy, pairs, offset, dimension, options), stiffness_(stiffness) {
  check_stiffness(stiffness);
}

void ContactPenalty::set_stiffness(double stiffness) {
  check_stiffness(stiffness);
  stiffness_ = stiffness;
}

Eigen::Index ContactPenalty::active_pairs(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::Index active = 0;
  for (Eigen::Index k = 0; k < constraints_.count(); ++k)
    if (constraints_.pair_geometry(x, k).distance < offset()) ++active;
  return active;
}

double ContactPenalty::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                Eigen::VectorXd* gradient,
                                Eigen::SparseMatrix<double>* hessian_upper) {
  const Eigen::Index n = dimension();
  if (x.size() != n) {
    std::ostringstream s;
    s << "ContactPenalty::evaluate: x has " << x.size() << " entries, expected dimension " << n;
    throw std::invalid_argument(s.str());
  }
  if (gradient != nullptr) gradient->setZero(n);
  if (hessian_upper != nullptr) {
    constraints_.check_hessian_structure(*hessian_upper, "ContactPenalty::evaluate");
    hessian_upper->coeffs().setZero();
  }
  const double k = stiffness_;
  const double offset = constraints_.offset();
  double energy = 0.0;
  for (Eigen::Index pair = 0; pair < constraints_.count(); ++pair) {
    const ContactPairGeometry g = constraints_.pair_geometry(x, pair);
    if (!(g.distance < offset)) continue;
    const double depth = offset - g.distance;  // > 0: how far inside the offset
    const double m = g.mollifier;
    energy += 0.5 * k * m * depth * depth;
    if (gradient == nullptr && hessian_upper == nullptr) continue;
    const ContactPairDistance D = constraints_.pair_distance(x, pair, hessian_upper != nullptr);
    if (D.on_pair_dofs) {
      // On the limit surface (never mollified): P_k = (k/2) g^2, g = offset - d.
      if (gradient != nullptr)
        constraints_.add_pair_dof_gradient(pair, -k * depth * D.dof_gradient, *gradient);
      if (hessian_upper != nullptr)
        constraints_.add_pair_dof_hessian(
            pair, k * (D.dof_gradient * D.dof_gradient.transpose() - depth * D.dof_hessian),
            *hessian_upper);
      continue;
    }
    const Vector12d& gd = D.gradient;
    const Vector12d& gm = D.mollifier_gradient;
    // P_k = (k/2) m g^2 with g = offset - d, dg = -dd: product rule.
    if (gradient != nullptr)
      constraints_.add_pair_gradient(pair, k * (-m * depth * gd + 0.5 * depth * depth * gm),
                                     *gradient);
    if (hessian_upper != nullptr) {
      const Matrix12d local = k * (m * (gd * gd.transpose() - depth * D.hessian) -
                                   depth * (gm * gd.transpose() + gd * gm.transpose()) +
                                   0.5 * depth * depth * D.mollifier_hessian);
      constraints_.add_pair_hessian(pair, local, *hessian_upper);
    }
  }
  return energy;
}

// ---- PenalizedEnergy -----------------------------------------------------------------------

PenalizedEnergy::PenalizedEnergy(const ShellModel& model, ContactPenalty& penalty)
    : model_(model), penalty_(penalty) {
  const Eigen::Index n = model.dimension();
  if (penalty.dimension() != n) {
    std::ostringstream s;
    s << "PenalizedEnergy: the energy has " << n << " unknowns but the penalty has "
      << penalty.dimension();
    throw std::invalid_argument(s.str());
  }
  const Eigen::SparseMatrix<double> A = model.hessian_pattern();
  const Eigen::SparseMatrix<double> B = penalty.hessian_pattern();
  check_upper_pattern(A, n, "energy");
  check_upper_pattern(B, n, "penalty");

  // Merge column by column (both sorted), recording where every source entry lands.
  std::vector<int> outer(1, 0);
  std::vector<int> inner;
  inner.reserve(static_cast<std::size_t>(A.nonZeros() + B.nonZeros()));
  energy_to_merged_.resize(static_cast<std::size_t>(A.nonZeros()));
  penalty_to_merged_.resize(static_cast<std::size_t>(B.nonZeros()));
  for (Eigen::Index j = 0; j < n; ++j) {
    int a = A.outerIndexPtr()[j];
    const int a_end = A.outerIndexPtr()[j + 1];
    int b = B.outerIndexPtr()[j];
    const int b_end = B.outerIndexPtr()[j + 1];
    while (a < a_end || b < b_end) {
      const int ra = a < a_end ? A.innerIndexPtr()[a] : static_cast<int>(n);
      const int rb = b < b_end ? B.innerIndexPtr()[b] : static_cast<int>(n);
      const int row = std::min(ra, rb);
      const auto position = static_cast<Eigen::Index>(inner.size());
      inner.push_back(row);
      if (ra == row) energy_to_merged_[static_cast<std::size_t>(a++)] = position;
      if (rb == row) penalty_to_merged_[static_cast<std::size_t>(b++)] = position;
    }
    outer.push_back(static_cast<int>(inner.size()));
  }
  const std::vector<double> zeros(inner.size(), 0.0);
  pattern_ = Eigen::Map<const Eigen::SparseMatrix<double>>(
      n, n, static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(), zeros.data());
}

double PenalizedEnergy::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double excess_angle,
                                 Eigen::VectorXd* gradient,
                                 Eigen::SparseMatrix<double>* hessian_upper) const {
  if (hessian_upper != nullptr) {
    bool ok = hessian_upper->rows() == pattern_.rows() &&
              hessian_upper->cols() == pattern_.cols() && hessian_upper->isCompressed() &&
              hessian_upper->nonZeros() == pattern_.nonZeros();
    for (Eigen::Index j = 0; ok && j <= pattern_.cols(); ++j)
      ok = hessian_upper->outerIndexPtr()[j] == pattern_.outerIndexPtr()[j];
    if (!ok) {
      std::ostringstream s;
      s << "PenalizedEnergy::evaluate: the Hessian matrix (" << hessian_upper->rows() << " x "
        << hessian_upper->cols() << ", " << hessian_upper->nonZeros()
        << " entries) does not carry hessian_pattern() (" << pattern_.nonZeros()
        << " entries, compressed)";
      throw std::invalid_argument(s.str());
    }
  }
  Eigen::VectorXd energy_gradient, penalty_gradient;
  Eigen::SparseMatrix<double> energy_hessian, penalty_hessian;
  if (hessian_upper != nullptr) {
    energy_hessian = model_.hessian_pattern();
    penalty_hessian = penalty_.hessian_pattern();
  }
  const double e = model_.evaluate(x, excess_angle, gradient != nullptr ? &energy_gradient : nullptr,
                                   hessian_upper != nullptr ? &energy_hessian : nullptr);
  if (!std::isfinite(e)) return e;
  const double p = penalty_.evaluate(x, gradient != nullptr ? &penalty_gradient : nullptr,
                                     hessian_upper != nullptr ? &penalty_hessian : nullptr);
  if (gradient != nullptr) *gradient = energy_gradient + penalty_gradient;
  if (hessian_upper != nullptr) {
    double* values = hessian_upper->valuePtr();
    std::fill(values, values + hessian_upper->nonZeros(), 0.0);
    const double* ev = energy_hessian.valuePtr();
    for (std::size_t i = 0; i < energy_to_merged_.size(); ++i)
      values[energy_to_merged_[i]] += ev[i];
    const double* pv = penalty_hessian.valuePtr();
    for (std::size_t i = 0; i < penalty_to_merged_.size(); ++i)
      values[penalty_to_merged_[i]] += pv[i];
  }
  return e + p;
}

}  // namespace growshell
