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
    const Eigen::Ref<const Eigen::MatrixX3d>& reference_positions, const ElementPatches& patches,
    int degree, const ThicknessField& thickness)
    : rule_(triangle_quadrature(degree)) {
  if (!thickness) throw std::invalid_argument("thickness field is empty");
  std::vector<Eigen::VectorXd> regular_values;  // basis values of a regular patch per rule point
  for (const auto& point : rule_) {
    const LoopBasisValues b = evaluate_regular_loop_basis(point.v, point.w);
    JetDerivatives<12> B;
    B << b.first, b.second;
    regular_.push_back(B);
    regular_values.push_back(b.value);
  }
  const std::size_t n_el = patches.patch.size();
  irregular_slot_.assign(n_el, -1);
  const std::size_t n = n_el * rule_.size();
  position_.reserve(n);
  tangents_.reserve(n);
  thickness_.reserve(n);
  int irregular_count = 0;
  vertex_areas_ = Eigen::VectorXd::Zero(reference_positions.rows());
  for (std::size_t e = 0; e < n_el; ++e) {
    const LoopPatch& patch = patches.patch[e];
    Eigen::MatrixX3d X(patch.size(), 3);
    for (int i = 0; i < patch.size(); ++i)
      X.row(i) = reference_positions.row(patch.control[static_cast<std::size_t>(i)]);
    if (!patch.is_regular()) irregular_slot_[e] = irregular_count++;
    for (std::size_t q = 0; q < rule_.size(); ++q) {
      Eigen::VectorXd value;
      Eigen::Matrix<double, Eigen::Dynamic, 2> first;
      if (patch.is_regular()) {
        value = regular_values[q];
        first = regular_[q].leftCols<2>();
      } else {
        const PatchBasis b = evaluate_patch_basis(patch, rule_[q].v, rule_[q].w);
        JetDerivatives<Eigen::Dynamic> B(patch.size(), 5);
        B << b.first, b.second;
        irregular_.push_back(B);
        value = b.value;
        first = b.first;
      }
      const Eigen::Vector3d p = X.transpose() * value;
      const Eigen::Matrix<double, 3, 2> A = X.transpose() * first;
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
      const double dA = rule_[q].weight * A.col(0).cross(A.col(1)).norm();
      for (int i = 0; i < patch.size(); ++i)
        vertex_areas_(patch.control[static_cast<std::size_t>(i)]) += dA * value(i);
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
