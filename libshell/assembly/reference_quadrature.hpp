#pragma once
/// \file
/// The reference (ungrown, stress-free) state sampled at every quadrature point.

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "libshell/subdivision/element_patches.hpp"
#include "libshell/subdivision/loop_basis.hpp"
#include "libshell/subdivision/triangle_quadrature.hpp"

namespace growshell {

/// Thickness h(X) (metres) as a function of the reference position X (metres).
using ThicknessField = std::function<double(const Eigen::Vector3d& reference_position)>;

/// A thickness field equal to `thickness` everywhere.
ThicknessField constant_thickness(double thickness);

/// The 5 columns [dN/dv, dN/dw, d2N/dv2, d2N/dw2, d2N/dvdw] of a patch's basis functions at one
/// point (one row per control point): the map from control points to the surface jet
/// (a_1, a_2, a_11, a_22, a_12) = X^T B, with X the patch's control points as rows.
template <int Nodes>
using JetDerivatives = Eigen::Matrix<double, Nodes, 5>;

/// Reference limit surface at the quadrature points: element e, rule point q is entry
/// e * points_per_element() + q. Built once from the reference control points; the library
/// never changes it afterwards.
class ReferenceQuadrature {
 public:
  /// `reference_positions`: control points (one row per vertex, metres) of the stress-free
  /// reference; `patches`: the elements' patches; `degree`: exactness of the triangle rule.
  /// Throws std::invalid_argument if the thickness is not finite and > 0 at some quadrature
  /// point (naming the element and position) or the reference surface is degenerate there.
  ReferenceQuadrature(const Eigen::Ref<const Eigen::MatrixX3d>& reference_positions,
                      const ElementPatches& patches, int degree, const ThicknessField& thickness);

  int points_per_element() const { return static_cast<int>(rule_.size()); }
  const std::vector<TriangleQuadraturePoint>& rule() const { return rule_; }
  /// Jet derivatives at rule point q of every regular element (they share them).
  const JetDerivatives<12>& regular_derivatives(int q) const { return regular_[static_cast<std::size_t>(q)]; }
  /// True if element e is a regular 12-node patch.
  bool is_regular(Eigen::Index e) const { return irregular_slot_[static_cast<std::size_t>(e)] < 0; }
  /// Jet derivatives at rule point q of element e, which must have an extraordinary corner
  /// (!is_regular(e)); one row per control point of its patch.
  const JetDerivatives<Eigen::Dynamic>& irregular_derivatives(Eigen::Index e, int q) const {
    return irregular_[static_cast<std::size_t>(irregular_slot_[static_cast<std::size_t>(e)] *
                                                points_per_element() + q)];
  }

  const Eigen::Vector3d& position(Eigen::Index i) const { return position_[i]; }
  /// Reference tangents [A_1 A_2] (metres per unit parameter).
  const Eigen::Matrix<double, 3, 2>& tangents(Eigen::Index i) const { return tangents_[i]; }
  double thickness(Eigen::Index i) const { return thickness_[i]; }
  Eigen::Index size() const { return static_cast<Eigen::Index>(position_.size()); }
  /// Largest thickness over all quadrature points (m).
  double max_thickness() const;
  /// Total reference area (m^2).
  double reference_area() const;
  /// Lumped reference area of every control vertex (m^2; one entry per row of the reference
  /// positions): the integral of its basis function over the elements, i.e. the row sums of
  /// the consistent mass matrix for unit areal density, by the same rule as the energy. The
  /// basis functions are non-negative and sum to one, so the entries are >= 0 and add up to
  /// reference_area(); a vertex that supports no element (none in a ghosted mesh) gets 0.
  const Eigen::VectorXd& vertex_areas() const { return vertex_areas_; }

 private:
  std::vector<TriangleQuadraturePoint> rule_;
  std::vector<JetDerivatives<12>> regular_;
  std::vector<int> irregular_slot_;  // per element: -1, or its index among irregular elements
  std::vector<JetDerivatives<Eigen::Dynamic>> irregular_;
  std::vector<Eigen::Vector3d> position_;
  std::vector<Eigen::Matrix<double, 3, 2>> tangents_;
  std::vector<double> thickness_;
  Eigen::VectorXd vertex_areas_;
};

}  // namespace growshell
