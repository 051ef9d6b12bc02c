#include "libshell/assembly/reference_quadrature.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace growshell {

ThicknessField constant_thickness(double thickness) {
  return [thickness](const Eigen::Vector3d&) { return thickness; };
}

ReferenceQuadrature::ReferenceQuadrature(
    const Eigen::Ref<const Eigen::MatrixX3d>& reference_positions,
    const std::vector<std::array<int, 12>>& patches, int degree,
    const ThicknessField& thickness)
    : rule_(triangle_quadrature(degree)) {
  if (!thickness) throw std::invalid_argument("thickness field is empty");
  for (const auto& point : rule_) {
    basis_.push_back(evaluate_regular_loop_basis(point.v, point.w));
    const LoopBasisValues& b = basis_.back();
    Eigen::Matrix<double, 12, 5> B;
    B << b.first, b.second;
    Eigen::Matrix<double, 36, 15> map = Eigen::Matrix<double, 36, 15>::Zero();
    for (int i = 0; i < 12; ++i)
      for (int k = 0; k < 5; ++k)
        for (int c = 0; c < 3; ++c) map(3 * i + c, 3 * k + c) = B(i, k);
    jet_map_.push_back(map);
  }
  const std::size_t n = patches.size() * rule_.size();
  position_.reserve(n);
  tangents_.reserve(n);
  thickness_.reserve(n);
  for (std::size_t e = 0; e < patches.size(); ++e) {
    Eigen::Matrix<double, 12, 3> X;
    for (int i = 0; i < 12; ++i) X.row(i) = reference_positions.row(patches[e][i]);
    for (const LoopBasisValues& b : basis_) {
      const Eigen::Vector3d p = X.transpose() * b.value;
      Eigen::Matrix<double, 3, 2> A = X.transpose() * b.first;
      const double h = thickness(p);
      if (!(std::isfinite(h) && h > 0.0)) {
        std::ostringstream msg;
        msg << "thickness h = " << h << " at reference point (" << p.transpose()
            << ") of element " << e << " must be finite and > 0";
        throw std::invalid_argument(msg.str());
      }
      if (!(A.col(0).cross(A.col(1)).norm() > 0.0)) {
        std::ostringstream msg;
        msg << "reference surface of element " << e << " is degenerate at (" << p.transpose()
            << ")";
        throw std::invalid_argument(msg.str());
      }
      position_.push_back(p);
      tangents_.push_back(A);
      thickness_.push_back(h);
    }
  }
}

double ReferenceQuadrature::max_thickness() const {
  return thickness_.empty() ? 0.0 : *std::max_element(thickness_.begin(), thickness_.end());
}

double ReferenceQuadrature::reference_area() const {
  const int m = points_per_element();
  double area = 0.0;
  for (Eigen::Index i = 0; i < size(); ++i)
    area += rule_[i % m].weight * tangents_[i].col(0).cross(tangents_[i].col(1)).norm();
  return area;
}

}  // namespace growshell
