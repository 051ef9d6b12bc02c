#include "solvers/newton/rigid_motion_pinning.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/sparse_objective.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "tests/support/max_abs_at.hpp"
#include "tests/support/scientific.hpp"

namespace growshell {
namespace {

using test_support::max_abs_at;
using test_support::scientific;

Eigen::MatrixX3d random_cloud(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixX3d p(n, 3);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) p(i, c) = u(rng);
  }
  return p;
}

Eigen::VectorXd flatten(const Eigen::MatrixX3d& p) {
  Eigen::VectorXd x(3 * p.rows());
  for (Eigen::Index v = 0; v < p.rows(); ++v) x.segment<3>(3 * v) = p.row(v).transpose();
  return x;
}

// Columns: the six rigid velocity fields (translations along x, y, z; rotations about the
// x, y, z axes through the centroid) as 3n-vectors in the vertex-major dof layout.
Eigen::MatrixXd rigid_fields(const Eigen::MatrixX3d& p) {
  const Eigen::RowVector3d centroid = p.colwise().mean();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3 * p.rows(), 6);
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const Eigen::Vector3d r = (p.row(v) - centroid).transpose();
    for (int k = 0; k < 3; ++k) {
      m(3 * v + k, k) = 1.0;
      m.block<3, 1>(3 * v, 3 + k) = Eigen::Vector3d::Unit(k).cross(r);
    }
  }
  return m;
}

double condition_number(const Eigen::MatrixXd& m) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m);
  const Eigen::VectorXd s = svd.singularValues();
  return s(0) / s(s.size() - 1);
}

// Condition number of the pinned dofs' rows of the rigid fields (rotations unscaled).
double pinned_rows_condition(const Eigen::MatrixX3d& p, const std::vector<Eigen::Index>& pins) {
  const Eigen::MatrixXd fields = rigid_fields(p);
  Eigen::MatrixXd restricted(static_cast<Eigen::Index>(pins.size()), 6);
  for (std::size_t r = 0; r < pins.size(); ++r)
    restricted.row(static_cast<Eigen::Index>(r)) = fields.row(pins[r]);
  return condition_number(restricted);
}

// E = sum over edges (|x_i - x_j| - L0)^2: invariant under translations and rotations.
class SpringNetwork : public SparseObjective {
 public:
  SpringNetwork(Eigen::Index vertices, std::vector<std::pair<int, int>> edges,
                std::vector<double> rest)
      : n_(3 * vertices), edges_(std::move(edges)), rest_(std::move(rest)) {}
  Eigen::Index dimension() const override { return n_; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index v = 0; v < n_ / 3; ++v) {
      for (int a = 0; a < 3; ++a) {
        for (int b = a; b < 3; ++b) t.emplace_back(3 * v + a, 3 * v + b, 0.0);
      }
    }
    for (const auto& [i, j] : edges_) {
      const int lo = std::min(i, j);
      const int hi = std::max(i, j);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) t.emplace_back(3 * lo + a, 3 * hi + b, 0.0);
      }
    }
    Eigen::SparseMatrix<double> h(n_, n_);
    h.setFromTriplets(t.begin(), t.end());
    h.makeCompressed();
    return h;
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* g,
                  Eigen::SparseMatrix<double>* h) override {
    double f = 0.0;
    if (g) g->setZero(n_);
    if (h) std::fill(h->valuePtr(), h->valuePtr() + h->nonZeros(), 0.0);
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      const int i = std::min(edges_[e].first, edges_[e].second);
      const int j = std::max(edges_[e].first, edges_[e].second);
      const Eigen::Vector3d d = x.segment<3>(3 * i) - x.segment<3>(3 * j);
      const double l = d.norm();
      const double stretch = l - rest_[e];
      f += stretch * stretch;
      const Eigen::Vector3d u = d / l;
      if (g) {
        g->segment<3>(3 * i) += 2.0 * stretch * u;
        g->segment<3>(3 * j) -= 2.0 * stretch * u;
      }
      if (h) {
        const Eigen::Matrix3d k =
            2.0 * u * u.transpose() +
            2.0 * stretch / l * (Eigen::Matrix3d::Identity() - u * u.transpose());
        for (int a = 0; a < 3; ++a) {
          for (int b = 0; b < 3; ++b) {
            h->coeffRef(3 * i + a, 3 * j + b) -= k(a, b);
            if (a <= b) {
              h->coeffRef(3 * i + a, 3 * i + b) += k(a, b);
              h->coeffRef(3 * j + a, 3 * j + b) += k(a, b);
            }
          }
        }
      }
    }
    return f;
  }
  // Largest |dE/dl| over edges at x: the scale of the internal forces.
  double max_edge_force(const Eigen::VectorXd& x) const {
    double m = 0.0;
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      const auto [i, j] = edges_[e];
      const double l = (x.segment<3>(3 * i) - x.segment<3>(3 * j)).norm();
      m = std::max(m, std::abs(2.0 * (l - rest_[e])));
    }
    return m;
  }

 private:
  Eigen::Index n_;
  std::vector<std::pair<int, int>> edges_;
  std::vector<double> rest_;
};

// k-nearest-neighbour network on a random cloud with rest lengths off by up to 10%: the
// equilibrium carries residual stress, so its internal forces are far from zero.
SpringNetwork make_network(const Eigen::MatrixX3d& p, int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> misfit(0.9, 1.1);
  std::set<std::pair<int, int>> edge_set;
  const int n = static_cast<int>(p.rows());
  for (int i = 0; i < n; ++i) {
    std::vector<std::pair<double, int>> by_distance;
    for (int j = 0; j < n; ++j) {
      if (j != i) by_distance.emplace_back((p.row(i) - p.row(j)).squaredNorm(), j);
    }
    std::sort(by_distance.begin(), by_distance.end());
    for (int m = 0; m < k; ++m) {
      const int j = by_distance[static_cast<std::size_t>(m)].second;
      edge_set.emplace(std::min(i, j), std::max(i, j));
    }
  }
  std::vector<std::pair<int, int>> edges(edge_set.begin(), edge_set.end());
  std::vector<double> rest;
  for (const auto& [i, j] : edges) rest.push_back((p.row(i) - p.row(j)).norm() * misfit(rng));
  return SpringNetwork(p.rows(), std::move(edges), std::move(rest));
}

std::vector<int> all_vertices(Eigen::Index n) {
  std::vector<int> v(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<int>(i);
  return v;
}

TEST(RigidMotionPinning, PinnedSpringNetworkHasNoReactions) {
  const Eigen::MatrixX3d rest = random_cloud(40, 3);
  SpringNetwork network = make_network(rest, 8, 5);
  const std::vector<Eigen::Index> pinned = rigid_motion_pinned_dofs(rest, all_vertices(40));
  ASSERT_EQ(pinned.size(), 6u);

  const Eigen::MatrixX3d start = rest + 0.05 * random_cloud(40, 9);
  NewtonOptions options;
  options.gradient_tolerance = 1e-13;  // internal forces are O(0.1): 1e-12 relative
  const NewtonResult r = NewtonSolver(options).minimize(network, flatten(start), pinned);
  ASSERT_TRUE(r.converged()) << r.message;
  const double force_scale = network.max_edge_force(r.x);
  ASSERT_GT(force_scale, 1e-2);  // residual stress: reactions are not trivially zero
  // Net force and torque of the internal forces vanish identically, and the free gradient is
  // <= 1e-12 relative, so the six reactions are that small times the (small) conditioning of
  // the pinning; 1e-9 relative leaves a wide margin.
  EXPECT_LE(max_abs_at(r.gradient, pinned), 1e-9 * force_scale);
  RecordProperty("reaction_over_force", scientific(max_abs_at(r.gradient, pinned) / force_scale));

  // Control: pinning A and B completely also removes six dofs but fixes |AB|, which a
  // pre-stressed network resists; the reactions are then of the order of the forces.
  std::vector<Eigen::Index> over = {pinned[0], pinned[1], pinned[2]};
  const Eigen::Index b = pinned[3] / 3;
  for (int c = 0; c < 3; ++c) over.push_back(3 * b + c);
  const NewtonResult biased = NewtonSolver(options).minimize(network, flatten(start), over);
  ASSERT_TRUE(biased.converged()) << biased.message;
  EXPECT_GT(max_abs_at(biased.gradient, over), 1e-4 * force_scale);
  RecordProperty("overconstrained_reaction_over_force",
                 scientific(max_abs_at(biased.gradient, over) / force_scale));
}

TEST(RigidMotionPinning, PinnedDofsControlAllRigidMotions) {
  const Eigen::MatrixX3d p = random_cloud(50, 17);
  const std::vector<Eigen::Index> pinned = rigid_motion_pinned_dofs(p, all_vertices(50));
  ASSERT_EQ(pinned.size(), 6u);
  EXPECT_EQ(std::set<Eigen::Index>(pinned.begin(), pinned.end()).size(), 6u);
  const double cond = pinned_rows_condition(p, pinned);
  EXPECT_LT(cond, 1e3);
  RecordProperty("condition_number", scientific(cond));

  // Control: A and B fully pinned leave the spin about AB free -> singular.
  const Eigen::Index a = pinned[0] / 3;
  const Eigen::Index b = pinned[3] / 3;
  const double bad =
      pinned_rows_condition(p, {3 * a, 3 * a + 1, 3 * a + 2, 3 * b, 3 * b + 1, 3 * b + 2});
  EXPECT_GT(bad, 1e12);
  RecordProperty("overconstrained_condition_number", scientific(bad));
}

TEST(RigidMotionPinning, FirstCandidateIsAnchorAndChoiceIsWellSpread) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0,   //
      0.1, 0, 0,  //
      3, 0.5, 0,  //
      1, 2, 0;
  // A = 0; B = 2 (farthest, B - A dominant in x); C = 3 (largest area, normal along z).
  const std::vector<Eigen::Index> dofs = rigid_motion_pinned_dofs(p, {0, 1, 2, 3});
  const std::vector<Eigen::Index> expected = {0, 1, 2, 3 * 2 + 1, 3 * 2 + 2, 3 * 3 + 2};
  EXPECT_EQ(dofs, expected);
}

TEST(RigidMotionPinning, CollinearOrInvalidCandidatesThrow) {
  Eigen::MatrixX3d line(5, 3);
  for (int i = 0; i < 5; ++i) line.row(i) = Eigen::RowVector3d(1.0, 2.0, -1.0) * i;
  line(3, 1) += 1e-9;  // within the 1e-6 relative collinearity tolerance
  EXPECT_THROW(rigid_motion_pinned_dofs(line, {0, 1, 2, 3, 4}), std::invalid_argument);
  const Eigen::MatrixX3d p = random_cloud(5, 1);
  EXPECT_THROW(rigid_motion_pinned_dofs(p, {0, 1}), std::invalid_argument);
  EXPECT_THROW(rigid_motion_pinned_dofs(p, {0, 1, 5}), std::invalid_argument);
  EXPECT_THROW(rigid_motion_pinned_dofs(p, {2, 2, 2}), std::invalid_argument);
  EXPECT_NO_THROW(rigid_motion_pinned_dofs(p, {0, 1, 2}));
}

TEST(RigidMotionPinning, PinsChosenOnTheReferenceLoseTheirLeverArmWhenTheRimWrapsRound) {
  // A disc whose points move round the axis in proportion to their angle, as in an e-cone
  // with excess angle 2 pi w: theta -> (1 + w) theta. With w = 1 the rim point at 90 degrees
  // (the reference pin C of mirror_axis_pinned_dofs) comes round to 180 degrees, in line with
  // the centre A and the rim point at 0 degrees (B): the spin about AB is then nearly free.
  // Pins chosen again on the current positions (A kept) stay well conditioned.
  DiscMeshOptions mo;
  mo.rings = 12;
  const TriangleMesh mesh = make_disc_mesh(mo);
  std::vector<int> sheet;
  for (int v = 0; v < mesh.vertices.rows(); ++v)
    if (mesh.vertices.row(v).head<2>().norm() <= 1.0 + 1e-9) sheet.push_back(v);
  const auto wrapped = [&](double w) {
    Eigen::MatrixX3d p(mesh.vertices.rows(), 3);
    for (int v = 0; v < p.rows(); ++v) {
      const double r = mesh.vertices.row(v).head<2>().norm();
      const double t = std::atan2(mesh.vertices(v, 1), mesh.vertices(v, 0)) * (1.0 + w);
      p.row(v) << r * std::cos(t), r * std::sin(t), 0.3 * r * r * std::cos(2.0 * t);
    }
    return p;
  };
  const std::vector<Eigen::Index> reference_pins =
      mirror_axis_pinned_dofs(mesh.vertices, sheet, Eigen::Vector3d::Zero());
  const double flat_reference = pinned_rigid_motion_condition(wrapped(0.0), reference_pins);
  const double wrapped_reference = pinned_rigid_motion_condition(wrapped(1.0), reference_pins);
  // The library's condition number against the test's own (rotations about the centroid,
  // unscaled; the disc's RMS radius is 0.7, so the two differ but agree on degeneracy).
  EXPECT_LT(pinned_rows_condition(wrapped(0.0), reference_pins), 1e2);
  EXPECT_GT(pinned_rows_condition(wrapped(1.0), reference_pins), 1e6);
  EXPECT_LT(flat_reference, 1e2);
  EXPECT_GT(wrapped_reference, 1e6);

  // well_conditioned_pins keeps good pins and replaces degenerate ones, keeping the anchor.
  EXPECT_EQ(well_conditioned_pins(wrapped(0.0), reference_pins, sheet, 20.0), reference_pins);
  const std::vector<Eigen::Index> repinned =
      well_conditioned_pins(wrapped(1.0), reference_pins, sheet, 20.0);
  const double wrapped_repinned = pinned_rigid_motion_condition(wrapped(1.0), repinned);
  EXPECT_NE(repinned, reference_pins);
  EXPECT_EQ(repinned.front(), reference_pins.front());
  EXPECT_LT(wrapped_repinned, 20.0);
  RecordProperty("condition_reference_pins_flat", scientific(flat_reference));
  RecordProperty("condition_reference_pins_wrapped", scientific(wrapped_reference));
  RecordProperty("condition_repinned_wrapped", scientific(wrapped_repinned));
  std::printf(
      "pinned rigid-motion condition: reference pins %.3g (flat), %.3g (wrapped); "
      "repinned %.3g\n",
      flat_reference, wrapped_reference, wrapped_repinned);

  // Rotations scaled by the RMS radius: the number does not depend on the unit of length.
  Eigen::MatrixX3d big = wrapped(0.3);
  const double in_metres = pinned_rigid_motion_condition(big, repinned);
  big *= 1000.0;
  EXPECT_NEAR(pinned_rigid_motion_condition(big, repinned), in_metres, 1e-9 * in_metres);
  EXPECT_THROW(pinned_rigid_motion_condition(big, {0, 1, 2}), std::invalid_argument);
  EXPECT_THROW(pinned_rigid_motion_condition(big, {0, 1, 2, 3, 4, 3 * big.rows()}),
               std::invalid_argument);
}

}  // namespace
}  // namespace growshell
