#include "libshell/analysis/elastic_stretches.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "libshell/energy/circumferential_growth.hpp"

namespace growshell {
namespace {

/// The current tangents [a_1 a_2] of element e at rule point q for the control points x.
Eigen::Matrix<double, 3, 2> current_tangents(const ShellModel& model,
                                             const Eigen::Ref<const Eigen::VectorXd>& x,
                                             Eigen::Index e, int q) {
  const ReferenceQuadrature& reference = model.reference();
  const LoopPatch& patch = model.patches().patch[static_cast<std::size_t>(e)];
  const bool regular = reference.is_regular(e);
  Eigen::Matrix<double, 3, 2> a = Eigen::Matrix<double, 3, 2>::Zero();
  for (int n = 0; n < patch.size(); ++n) {
    const Eigen::Vector3d p = x.segment<3>(3 * patch.control[static_cast<std::size_t>(n)]);
    for (int c = 0; c < 2; ++c)
      a.col(c) += (regular ? reference.regular_derivatives(q)(n, c)
                           : reference.irregular_derivatives(e, q)(n, c)) * p;
  }
  return a;
}

}  // namespace

std::vector<PointStretches> elastic_stretches(const ShellModel& model,
                                              const Eigen::Ref<const Eigen::VectorXd>& x,
                                              double excess_angle, double max_radius) {
  if (x.size() != model.dimension())
    throw std::invalid_argument("elastic_stretches: x has " + std::to_string(x.size()) +
                                " entries, the model " + std::to_string(model.dimension()));
  if (!(max_radius >= 0.0))
    throw std::invalid_argument("elastic_stretches: max_radius must be >= 0");
  const ReferenceQuadrature& reference = model.reference();
  const CircumferentialGrowth& growth = model.settings().growth;
  const int per_element = reference.points_per_element();
  std::vector<PointStretches> out;
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    for (int q = 0; q < per_element; ++q) {
      const Eigen::Index i = e * per_element + q;
      const double r = (reference.position(i) - growth.center).head<2>().norm();
      if (r > max_radius) continue;
      const Eigen::Matrix<double, 3, 2> t = current_tangents(model, x, e, q);
      const Eigen::Matrix2d a = t.transpose() * t;
      const Eigen::Matrix2d abar =
          target_metric(growth, reference.position(i), reference.tangents(i), excess_angle);
      // The eigenvalues of abar^-1 a are those of the symmetric L^-1 a L^-T, abar = L L^T.
      const Eigen::Matrix2d L = abar.llt().matrixL();
      const Eigen::Matrix2d half = L.triangularView<Eigen::Lower>().solve(a);
      const Eigen::Matrix2d m = L.triangularView<Eigen::Lower>().solve(half.transpose());
      const Eigen::Vector2d squared =
          Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(0.5 * (m + m.transpose())).eigenvalues();
      out.push_back({r, std::sqrt(std::max(squared(0), 0.0)), std::sqrt(std::max(squared(1), 0.0))});
    }
  }
  return out;
}

}  // namespace growshell
