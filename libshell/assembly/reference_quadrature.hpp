#pragma once
/// \file
/// The reference (ungrown, stress-free) state sampled at every quadrature point.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "libshell/subdivision/loop_basis.hpp"
#include "libshell/subdivision/triangle_quadrature.hpp"

namespace growshell {

/// Thickness h(X) (metres) as a function of the reference position X (metres).
using ThicknessField = std::function<double(const Eigen::Vector3d& reference_position)>;

/// A thickness field equal to `thickness` everywhere.
ThicknessField constant_thickness(double thickness);

/// Reference limit surface at the quadrature points: element e, rule point q is entry
/// e * points_per_element() + q. Built once from the reference control points; the library
/// never changes it afterwards.
class ReferenceQuadrature {
 public:
  /// `reference_positions`: control points (one row per vertex, metres) of the stress-free
  /// reference; `patches`: the 12 control points of each element; `degree`: exactness of
  /// the triangle rule. Throws std::invalid_argument if the thickness is not finite and > 0
  /// at some quadrature point (naming the element and position) or the reference surface is
  /// degenerate there.
  ReferenceQuadrature(const Eigen::Ref<const Eigen::MatrixX3d>& reference_positions,
                      const std::vector<std::array<int, 12>>& patches, int degree,
                      const ThicknessField& thickness);

  int points_per_element() const { return static_cast<int>(rule_.size()); }
  const std::vector<TriangleQuadraturePoint>& rule() const { return rule_; }
  /// Basis values at rule point q (shared by all elements: every patch is regular).
  const LoopBasisValues& basis(int q) const { return basis_[q]; }
  /// 36 x 15 map from the element's 36 control coordinates (node-major: 3 i + xyz) to the
  /// 15-entry surface jet (a_1, a_2, a_11, a_22, a_12) at rule point q, transposed: jet =
  /// jet_map(q)^T * x_local.
  const Eigen::Matrix<double, 36, 15>& jet_map(int q) const { return jet_map_[q]; }

  const Eigen::Vector3d& position(Eigen::Index i) const { return position_[i]; }
  /// Reference tangents [A_1 A_2] (metres per unit parameter).
  const Eigen::Matrix<double, 3, 2>& tangents(Eigen::Index i) const { return tangents_[i]; }
  double thickness(Eigen::Index i) const { return thickness_[i]; }
  Eigen::Index size() const { return static_cast<Eigen::Index>(position_.size()); }
  /// Largest thickness over all quadrature points (m).
  double max_thickness() const;
  /// Total reference area (m^2).
  double reference_area() const;

 private:
  std::vector<TriangleQuadraturePoint> rule_;
  std::vector<LoopBasisValues> basis_;
  std::vector<Eigen::Matrix<double, 36, 15>> jet_map_;
  std::vector<Eigen::Vector3d> position_;
  std::vector<Eigen::Matrix<double, 3, 2>> tangents_;
  std::vector<double> thickness_;
};

}  // namespace growshell
