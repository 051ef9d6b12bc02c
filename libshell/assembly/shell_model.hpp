#pragma once
/// \file
/// The discrete energy of a growing Kirchhoff-Love shell on Loop subdivision elements:
/// value, exact gradient and exact sparse Hessian with respect to all control coordinates.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "libshell/assembly/reference_quadrature.hpp"
#include "libshell/energy/circumferential_growth.hpp"
#include "libshell/energy/material.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/triangle_mesh.hpp"
#include "libshell/subdivision/element_lattice_sampling.hpp"
#include "libshell/subdivision/element_patches.hpp"

namespace growshell {

/// What the model contains besides the mesh. The defaults are the paper's scene
/// (Y = 1e4 Pa, nu = 0.3, h = 0.02 m, growth about the origin).
struct ShellModelSettings {
  Material material;
  ThicknessField thickness = constant_thickness(0.02);
  /// Polynomial exactness of the triangle rule (1..6); 2 (three points) is the default.
  int quadrature_degree = 2;
  CircumferentialGrowth growth;
  /// OpenMP threads for assembly; 0 means OpenMP's default. Results are deterministic for a
  /// fixed thread count.
  int threads = 0;
};

/// Energy parts of a configuration (SI units).
struct ShellEnergyBreakdown {
  double stretching = 0.0;  ///< J
  double bending = 0.0;     ///< J
  double bending_density_integral = 0.0;  ///< integral of U_b over the grown reference (1)
  double stretching_density_integral = 0.0;  ///< integral of U_s over the grown reference (m^2)
  double current_area = 0.0;              ///< m^2
  double grown_area = 0.0;                ///< target (grown reference) area, m^2
  double total() const { return stretching + bending; }
  /// Normalised bending energy E_b-hat = (integral of U_b) / current area (1/m^2).
  double normalized_bending() const { return bending_density_integral / current_area; }
};

/// Energy E(x; phi_e) of the sheet, as a family in the excess angle phi_e (radians). Unknowns x:
/// all control points, vertex-major (x[3 v + c], metres), ghost layer included. The reference
/// (stress-free, ungrown) state is the limit surface of the control mesh given at construction;
/// it is never modified. phi_e is an argument of every evaluation; the model holds no growth
/// state, and all its evaluations are const (safe to call from several threads at once, each
/// call using the model's `threads` for its own assembly).
class ShellModel final : public ParametrizedObjective {
 public:
  /// Validates the mesh (see validate_control_mesh), the material and the thickness and
  /// builds the Hessian pattern. Throws MeshError or std::invalid_argument naming the problem.
  ShellModel(const TriangleMesh& reference_control_mesh, ShellModelSettings settings);

  Eigen::Index dimension() const override { return 3 * topology_.num_vertices(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return pattern_; }
  /// E(x; phi_e) (J), with gradient (N) and Hessian upper triangle (N/m) on request. Throws
  /// std::invalid_argument for an x of the wrong size, a Hessian without the model's pattern, or
  /// an excess angle that is not finite or not > -2 pi.
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double excess_angle,
                  Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) const override;
  /// Whether phi_e is finite and > -2 pi (a positive circumferential stretch).
  bool accepts_parameter(double excess_angle) const override;
  /// d(gradient)/d(phi_e) at x (N/rad), exact; throws as evaluate.
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                double excess_angle) const override;

  /// Stretching and bending energy, E_b-hat ingredients and areas at (x, phi_e).
  ShellEnergyBreakdown energy_breakdown(const Eigen::Ref<const Eigen::VectorXd>& x,
                                        double excess_angle) const;

  /// Mean bending energy density U_b of each element (1/m^2), weighted by grown area.
  Eigen::VectorXd element_bending_density(const Eigen::Ref<const Eigen::VectorXd>& x,
                                          double excess_angle) const;

  /// Mean stretching energy density U_s of each element (dimensionless strain squared).
  Eigen::VectorXd element_stretching_density(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             double excess_angle) const;

  /// Energy parts of element e alone at (x, phi_e) (its share of energy_breakdown), 0 <= e <
  /// num_elements(); e is not range-checked.
  ShellEnergyBreakdown element_breakdown(const Eigen::Ref<const Eigen::VectorXd>& x,
                                         double excess_angle, Eigen::Index e) const;

  /// Limit-surface positions (metres) of the element corner vertices, in the order of
  /// sheet_vertices().
  Eigen::MatrixX3d limit_positions(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// Vertices that are corners of elements (the sheet proper, ghost layer excluded), sorted.
  const std::vector<int>& sheet_vertices() const { return sheet_vertices_; }
  /// Reference control points, flattened like x.
  const Eigen::VectorXd& reference_positions() const { return reference_x_; }
  const MeshTopology& topology() const { return topology_; }
  const ElementPatches& patches() const { return patches_; }
  /// The limit-position map at the lattice points (i / n, j / n) of every element
  /// (ElementLatticeSampling), built on first use for each n and kept (copies of the model share
  /// it); safe to call from several threads. Throws as ElementLatticeSampling.
  const ElementLatticeSampling& lattice_sampling(int n) const;
  const ReferenceQuadrature& reference() const { return reference_; }
  const ShellModelSettings& settings() const { return settings_; }
  Eigen::Index num_elements() const { return static_cast<Eigen::Index>(patches_.face.size()); }

  /// Natural force scale Y h^3 / L (N): the nodal force of O(1/L) bending, with h the largest
  /// thickness and L = sqrt(reference area / pi). Use it to scale force tolerances.
  double natural_force_scale() const;

 private:
  int thread_count() const;
  /// Throws std::invalid_argument naming phi_e unless accepts_parameter(phi_e).
  void check_excess_angle(double excess_angle) const;

  ShellModelSettings settings_;
  MeshTopology topology_;
  ElementPatches patches_;
  Eigen::VectorXd reference_x_;
  ReferenceQuadrature reference_;
  std::vector<int> sheet_vertices_;
  std::vector<TargetMetricParts> growth_parts_;  // per quadrature point: abar without phi_e
  Eigen::SparseMatrix<double> pattern_;
  struct LatticeSamplingCache;
  std::shared_ptr<LatticeSamplingCache> lattice_sampling_;
};

}  // namespace growshell
