#pragma once
/// \file
/// Self-contact as a penalty energy (the quadratic repulsion of Stoop et al. 2010), on the
/// control dofs of the shell, and the adaptor that adds it to the shell energy, so that the
/// Newton solver minimises both and continuation follows both in the excess angle.
///
///   P(x) = (k / 2) sum_pairs m_k(x) max(0, offset - d_k(x))^2
///
/// over the candidate pairs of a ContactGapConstraints (same pairs, distances, regions, proxy
/// map and zero-distance floor; see contact_gap_constraints.hpp). m_k is the IPC edge-edge
/// mollifier (1 for vertex-triangle pairs, and for all pairs with
/// ContactGapOptions::mollify_edge_edge off): it multiplies the potential as in IPC, so that
/// the terms of nearly parallel edges, whose distance Hessian grows like 1 / sin(angle) and
/// whose region switches at sin^2 = 1e-10 with a tiny jump in d, fade out (m ~ 2e-7 at the
/// switch). Otherwise P is C1 in x: the distance is C1 across region boundaries and
/// max(0, .)^2 is C1 at d_k = offset; its Hessian, that of the classified regions, jumps there.
///
/// Stiffness scale. k (N/m) is the force per metre of penetration of one pair. A natural
/// choice is contact_stiffness_scale(Y, h, l) = Y l^2 / h, l the proxy spacing: with about
/// one pair per proxy vertex (area l^2), a contact pressure p then penetrates by about
/// delta = p h / Y, the elastic compression of the two half-thicknesses (h in total) between
/// the touching mid-surfaces, so the penalty mimics the sheets' own through-thickness
/// stiffness. For l = h it equals Y h, the sheet's in-plane stiffness, so the penalty does not
/// spoil the Hessian's conditioning more than stretching does; under bending loads
/// (nodal forces ~ Y h^3 / R) the penetration is delta / h ~ h^3 / (R l^2). Several pairs act
/// per proxy vertex in practice (a vertex over a triangle, the triangle's vertices over the
/// other layer, crossing edges), so the effective pressure stiffness is a small multiple of
/// k / l^2. Raise k to reduce penetration (at the cost of conditioning).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "core/parametrized_objective.hpp"
#include "core/sparse_objective.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"

namespace growshell {

/// Natural penalty stiffness Y l^2 / h (N/m) for Young's modulus Y (Pa), thickness h (m) and
/// proxy spacing l (m) (see the file comment). Throws std::invalid_argument naming the
/// argument unless all three are finite and > 0.
double contact_stiffness_scale(double youngs_modulus, double thickness, double spacing);

/// Mean length (m) of the proxy's edges in its reference state (ContactProxy::edges on
/// reference_positions): the spacing l of contact_stiffness_scale. Throws
/// std::invalid_argument if the proxy has no edges or an edge index is out of range.
double proxy_mean_edge_length(const ContactProxy& proxy);

/// The penalty P(x) of the file comment as a SparseObjective (J for k in N/m and lengths in
/// m). Unknowns and pair order as in ContactGapConstraints. Hessian pattern: the upper
/// triangle of the union of the pairs' stencils, fixed for the object's lifetime (equal to
/// ContactGapConstraints::hessian_pattern()).
class ContactPenalty final : public SparseObjective {
 public:
  /// Penalty of the pairs `pairs` of `proxy`, contact distance `offset` (m), stiffness
  /// `stiffness` (N/m, finite, >= 0), over `dimension` unknowns. Throws std::invalid_argument
  /// for a bad stiffness and as ContactGapConstraints for the rest.
  ContactPenalty(const ContactProxy& proxy, const ContactCandidates& pairs, double offset,
                 double stiffness, Eigen::Index dimension, ContactGapOptions options = {});

  Eigen::Index dimension() const override { return constraints_.dimension(); }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    return constraints_.hessian_pattern();
  }

  /// P(x) (J); gradient dP/dx (N) and the upper triangle of d2P/dx2 (N/m) on request.
  /// Pairs with d_k >= offset contribute nothing (not even to the Hessian). Throws
  /// std::invalid_argument if x has the wrong size, the Hessian does not carry the pattern, or
  /// a primitive is degenerate at x (naming the pair).
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override;

  /// Number of pairs with d_k(x) < offset (those that contribute).
  Eigen::Index active_pairs(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// Stiffness k (N/m).
  double stiffness() const { return stiffness_; }
  /// Changes k (N/m, finite, >= 0; throws std::invalid_argument otherwise); e.g. for
  /// continuation in k.
  void set_stiffness(double stiffness);
  /// Contact distance (m).
  double offset() const { return constraints_.offset(); }
  /// The pairs' gaps, geometry and stencils (the penalty's building blocks).
  const ContactGapConstraints& constraints() const { return constraints_; }

 private:
  ContactGapConstraints constraints_;
  double stiffness_ = 0.0;
};

/// Shell + penalty, the one adaptor of the two: E(x; phi_e) + P(x) for a ShellModel E and a
/// ContactPenalty P of the same dimension, with the merged (union) Hessian pattern. As a
/// ParametrizedObjective in phi_e it is the family that pseudo-arclength continuation follows
/// through contact, and, at one phi_e (ObjectiveAtParameter), what NewtonSolver minimises and
/// the stability layer factorises (P does not depend on phi_e, so d(gradient)/d(phi_e) is the
/// shell's). The Hessian pattern is fixed for the adaptor's lifetime, i.e. for one pair set.
/// Holds references: both objects must outlive the adaptor. A change of the penalty that keeps
/// its pattern (its stiffness) takes effect at the next evaluate.
class PenalizedEnergy final : public ParametrizedObjective {
 public:
  /// Throws std::invalid_argument if the dimensions differ or a pattern is not a compressed
  /// n x n upper triangle.
  PenalizedEnergy(const ShellModel& model, ContactPenalty& penalty);

  Eigen::Index dimension() const override { return model_.dimension(); }
  /// Union of the two upper-triangular patterns.
  Eigen::SparseMatrix<double> hessian_pattern() const override { return pattern_; }

  /// E(x; phi_e) + P(x), with summed gradient and Hessian on request. If E is not finite it is
  /// returned as is (the outside-the-domain signal of SparseObjective) without evaluating P.
  /// Throws std::invalid_argument if the Hessian does not carry hessian_pattern(), and
  /// whatever E and P throw.
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double excess_angle,
                  Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) const override;

  bool accepts_parameter(double lambda) const override { return model_.accepts_parameter(lambda); }
  /// d(gradient)/d(phi_e) at x: the shell's (P does not depend on phi_e).
  Eigen::VectorXd gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                double excess_angle) const override {
    return model_.gradient_parameter_derivative(x, excess_angle);
  }

  const ShellModel& model() const { return model_; }
  ContactPenalty& penalty() const { return penalty_; }

 private:
  const ShellModel& model_;
  ContactPenalty& penalty_;
  Eigen::SparseMatrix<double> pattern_;
  // Position in pattern_'s value array of every stored entry of each part's pattern.
  std::vector<Eigen::Index> energy_to_merged_;
  std::vector<Eigen::Index> penalty_to_merged_;
};

}  // namespace growshell
