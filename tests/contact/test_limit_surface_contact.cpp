// Gap constraints and the penalty on the limit surface (ContactGapOptions::limit_surface), on
// the contact tests' folded disc: each gap is the distance from the proxy vertex to the limit
// surface (against dense sampling of the surface, and within the proxy's sag of the flat
// triangles' distance), the Jacobian, the weighted Hessian and the penalty's derivatives
// against central differences, one pair per vertex and layer, and the refusal of edge-edge
// pairs.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <span>

#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/limit_surface_contact.hpp"
#include "libshell/subdivision/limit_surface.hpp"
#include "support/dense_symmetric.hpp"
#include "tests/support/expect_invalid_argument.hpp"
#include "tests/support/folded_disc_scene.hpp"

namespace growshell {
namespace {

using test_support::dense_symmetric;
using test_support::expect_invalid_argument_containing;
using test_support::FoldedDiscScene;

constexpr double kOffset = 0.1;           // as the folded disc's other gap tests
constexpr double kExclusionRadius = 0.2;  // as its candidates' (folded_disc_scene.hpp)

/// The folded disc's vertex-triangle candidates only, and the limit-surface options.
struct LimitScene {
  FoldedDiscScene scene;
  ContactCandidates pairs;
  ContactGapOptions options;
  explicit LimitScene(double wobble) : scene(wobble, 1) {
    pairs.vertex_triangle = scene.pairs.vertex_triangle;
    options.limit_surface = make_limit_surface_contact(scene.model, kExclusionRadius);
  }
};

TEST(LimitSurfaceContact, EachGapIsTheDistanceFromTheProxyVertexToTheLimitSurface) {
  const LimitScene s(0.02);
  const ContactGapConstraints c(s.scene.proxy, s.pairs, kOffset, s.scene.model.dimension(),
                                s.options);
  ASSERT_GT(c.count(), 50);
  const Eigen::MatrixX3d positions = control_point_rows(s.scene.x);
  const LimitSurfaceContact& limit = *s.options.limit_surface;
  const ProxySag sag = proxy_sag(s.scene.model, s.scene.proxy, s.scene.x);
  const int samples = 24;
  double worst_above = 0.0, worst_cover = 0.0;
  for (Eigen::Index k = 0; k < c.count(); k += 7) {
    const ContactPairGeometry g = c.pair_geometry(s.scene.x, k);
    EXPECT_NEAR((g.closest_point_first - g.closest_point_second).norm(), g.distance, 1e-14);
    EXPECT_NEAR(g.normal.norm(), 1.0, 1e-14);
    EXPECT_NEAR(g.gap, g.distance - kOffset, 1e-15);
    // Densely sampled, the surface the pair is measured against comes no closer than the
    // distance reported, and not farther than the sampling's covering radius.
    double sampled = std::numeric_limits<double>::infinity(), cover = 0.0;
    const std::span<const int> elements = c.pair_surface_elements(k);
    ASSERT_FALSE(elements.empty());
    for (int e : elements) {
      const LoopPatch& patch = limit.patches.patch[static_cast<std::size_t>(e)];
      for (int i = 0; i <= samples; ++i)
        for (int j = 0; i + j <= samples; ++j) {
          const LimitSurfacePoint x =
              evaluate_limit_surface(positions, patch, double(i) / samples, double(j) / samples);
          sampled = std::min(sampled, (g.closest_point_first - x.position).norm());
          cover = std::max(cover, x.tangents.norm() / samples);
        }
    }
    worst_above = std::max(worst_above, g.distance - sampled);
    worst_cover = std::max(worst_cover, (sampled - g.distance) / cover);
    EXPECT_LE(g.distance, sampled + 1e-13) << "pair " << k;
    EXPECT_LE(sampled - g.distance, cover) << "pair " << k;
    // The flat triangle under the foot lies within the proxy's sag of the surface (sampled,
    // so with a margin).
    ContactCandidates one;
    one.vertex_triangle.resize(1, 2);
    one.vertex_triangle << g.first, g.second;
    const ContactGapConstraints flat(s.scene.proxy, one, kOffset, s.scene.model.dimension());
    EXPECT_LT(std::abs(flat.pair_geometry(s.scene.x, 0).distance - g.distance),
              1.5 * sag.parametric)
        << "pair " << k;
  }
  EXPECT_LT(worst_above, 1e-13);
}

TEST(LimitSurfaceContact, JacobianAndWeightedHessianMatchCentralDifferences) {
  const LimitScene s(0.02);
  const Eigen::Index n = s.scene.model.dimension();
  ContactGapConstraints c(s.scene.proxy, s.pairs, kOffset, n, s.options);
  const Eigen::Index m = c.count();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const double h = 1e-7;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J = c.jacobian_pattern(), Jp = J, Jm = J;
  Eigen::SparseMatrix<double> H = c.hessian_pattern();
  double worst_jacobian = 0.0, worst_hessian = 0.0;
  for (int trial = 0; trial < 2; ++trial) {
    Eigen::VectorXd v(n), w(m);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = U(rng);
    for (Eigen::Index k = 0; k < m; ++k) w[k] = U(rng);
    Eigen::VectorXd values, vp, vm;
    c.evaluate(s.scene.x, values, &J);
    c.evaluate(s.scene.x + h * v, vp, &Jp);
    c.evaluate(s.scene.x - h * v, vm, &Jm);
    const Eigen::VectorXd Jv = J * v;
    worst_jacobian = std::max(worst_jacobian, ((vp - vm) / (2.0 * h) - Jv).cwiseAbs().maxCoeff() /
                                                  (1.0 + Jv.cwiseAbs().maxCoeff()));
    c.weighted_hessian(s.scene.x, w, H);
    const Eigen::VectorXd fd =
        (Eigen::VectorXd(Jp.transpose() * w) - Eigen::VectorXd(Jm.transpose() * w)) / (2.0 * h);
    const Eigen::VectorXd Hv = dense_symmetric(H) * v;
    worst_hessian =
        std::max(worst_hessian, (fd - Hv).cwiseAbs().maxCoeff() / (1.0 + Hv.cwiseAbs().maxCoeff()));
  }
  // As the flat triangles' test (h = 1e-7 m): truncation h^2 |c'''| and rounding 1e-16 / h.
  EXPECT_LT(worst_jacobian, 1e-6);
  EXPECT_LT(worst_hessian, 1e-6);
}

TEST(LimitSurfaceContact, PenaltyGradientAndHessianMatchCentralDifferences) {
  const LimitScene s(0.02);
  const Eigen::Index n = s.scene.model.dimension();
  ContactPenalty penalty(s.scene.proxy, s.pairs, kOffset, 3e3, n, s.options);
  const ContactGapConstraints& c = penalty.constraints();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const double h = 1e-6;
  Eigen::SparseMatrix<double> H = penalty.hessian_pattern();
  Eigen::VectorXd g, gp, gm;
  int smooth_trials = 0;
  double worst_value = 0.0, worst_gradient = 0.0;
  for (int trial = 0; trial < 10 && smooth_trials < 3; ++trial) {
    Eigen::VectorXd v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = U(rng);
    // Central differences need every pair on one side of d = offset, where the Hessian jumps.
    bool smooth = true;
    for (Eigen::Index p = 0; p < c.count() && smooth; ++p) {
      const bool inside = c.pair_geometry(s.scene.x, p).distance < kOffset;
      for (const double sign : {1.0, -1.0})
        smooth =
            smooth && (c.pair_geometry(s.scene.x + sign * h * v, p).distance < kOffset) == inside;
    }
    if (!smooth) continue;
    ++smooth_trials;
    const double P = penalty.evaluate(s.scene.x, &g, &H);
    ASSERT_GT(P, 0.0);
    const double Pp = penalty.evaluate(s.scene.x + h * v, &gp, nullptr);
    const double Pm = penalty.evaluate(s.scene.x - h * v, &gm, nullptr);
    worst_value =
        std::max(worst_value, std::abs((Pp - Pm) / (2.0 * h) - g.dot(v)) / std::abs(g.dot(v)));
    const Eigen::VectorXd Hv = dense_symmetric(H) * v;
    worst_gradient = std::max(worst_gradient, ((gp - gm) / (2.0 * h) - Hv).cwiseAbs().maxCoeff() /
                                                  Hv.cwiseAbs().maxCoeff());
  }
  EXPECT_EQ(smooth_trials, 3);
  EXPECT_LT(worst_value, 1e-6);
  EXPECT_LT(worst_gradient, 1e-5);
}

TEST(LimitSurfaceContact, KeepsOnePairPerVertexAndLayer) {
  // With every near triangle of a vertex as candidates, the pairs of one vertex whose
  // triangles lie in each other's neighbourhoods would measure the same foot: one is kept.
  const LimitScene s(0.02);
  const ContactGapConstraints c(s.scene.proxy, s.pairs, kOffset, s.scene.model.dimension(),
                                s.options);
  const LimitSurfaceContact& limit = *s.options.limit_surface;
  const auto element_of = [&](Eigen::Index row) {
    return s.scene.proxy.triangle_element(s.pairs.vertex_triangle(row, 1));
  };
  ASSERT_GT(s.pairs.vertex_triangle.rows(), c.count());  // the folded disc has repeats
  // Every candidate pair is covered by a kept pair of its vertex within its neighbourhood.
  std::vector<std::pair<int, int>> kept;  // (vertex, element) of the kept pairs, in order
  for (Eigen::Index r = 0; r < s.pairs.vertex_triangle.rows(); ++r) {
    const int vertex = s.pairs.vertex_triangle(r, 0);
    const auto& around = limit.neighbourhoods[static_cast<std::size_t>(element_of(r))];
    bool covered = false;
    for (const auto& [v, e] : kept)
      covered = covered || (v == vertex && std::binary_search(around.begin(), around.end(), e));
    if (!covered) kept.emplace_back(vertex, element_of(r));
  }
  ASSERT_EQ(static_cast<Eigen::Index>(kept.size()), c.count());
  for (Eigen::Index k = 0; k < c.count(); ++k)
    EXPECT_EQ(c.pair_geometry(s.scene.x, k).first, kept[static_cast<std::size_t>(k)].first);
}

TEST(LimitSurfaceContact, RefusesEdgeEdgePairsAndTheFlatDerivatives) {
  const LimitScene s(0.02);
  ASSERT_GT(s.scene.pairs.edge_edge.rows(), 0);
  expect_invalid_argument_containing(
      [&] {
        ContactGapConstraints(s.scene.proxy, s.scene.pairs, kOffset, s.scene.model.dimension(),
                              s.options);
      },
      "edge-edge pairs: on the limit surface only vertex-triangle pairs are measured");
  const ContactGapConstraints c(s.scene.proxy, s.pairs, kOffset, s.scene.model.dimension(),
                                s.options);
  EXPECT_TRUE(c.measures_limit_surface());
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(s.scene.model.dimension());
  EXPECT_THROW(c.add_pair_gradient(0, Vector12d::Zero(), gradient), std::logic_error);
}

}  // namespace
}  // namespace growshell
