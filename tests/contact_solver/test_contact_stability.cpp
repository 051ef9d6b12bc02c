// contact_constrained_inertia: the reduced Hessian of the Lagrangian E - sum mu_k c_k of a
// shell with contact gaps, against a dense computation from the same pieces (energy Hessian,
// multiplier-weighted constraint Hessian, active Jacobian, dense null space on the free
// dofs); the plain inertia of the energy when no multiplier reaches the threshold; the sign of
// the constraint curvature on a particle pushed onto a point obstacle, where the answer is
// known in closed form; coinciding contact pairs; bad input.
//
// The shell scene (as in tests/contact): a 4-ring unit disc (h = 0.02 m, default material)
// folded about its diameter X = 0 over a half cylinder of radius 0.04 m, with a smooth generic
// wobble of 0.01 m, so the half X > 0 lies over the half X < 0 about 0.08 m apart. The state is
// not an equilibrium; the counts are of the Lagrangian's Hessian there, which is all the
// function computes (at a KKT point they decide stability). The vertices with reference
// X < -0.5 are held, which removes the rigid motions.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_stability.hpp"
#include "support/dense_symmetric.hpp"
#include "support/sheet_states.hpp"
#include "support/strict_contact_solve_options.hpp"

namespace growshell {
namespace {

using test_support::dense_symmetric;
using test_support::folded_sheet;

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

struct FoldedDisc {
  ShellModel model;
  ContactProxy proxy;
  Eigen::VectorXd x;
  std::vector<Eigen::Index> fixed, free;

  FoldedDisc()
      : model(make_disc_mesh([] {
                DiscMeshOptions o;
                o.rings = 4;
                return o;
              }()),
              ShellModelSettings{}),
        proxy(make_contact_proxy(model, 1)),
        x(folded_sheet(model, 0.0, 0.04, 0.01)) {
    const Eigen::VectorXd reference = model.reference_positions();
    for (Eigen::Index d = 0; d < reference.size(); ++d) {
      (reference(3 * (d / 3)) < -0.5 ? fixed : free).push_back(d);
    }
  }

  // Pairs closer than 0.09 m; the solver's defaults (nearest triangle per vertex, no
  // edge-edge pairs) unless `edge_edge`. Offset 0.07 m (the values of c do not enter).
  ContactGapConstraints gaps(bool edge_edge) const {
    NearPairSelection selection;
    selection.edge_edge_pairs = edge_edge;
    selection.nearest_triangle_only = true;
    return ContactGapConstraints(proxy, near_contact_pairs(proxy, x, 0.09, 0.2, selection), 0.07,
                                 model.dimension());
  }
};

// Dense reference: eigenvalues of Z^T (H_E - sign * W) Z on the free dofs, W = sum_k
// weights_k d2c_k/dx2, Z an orthonormal basis of the null space of the rows `active` of the
// constraint Jacobian (from a Householder QR of J_a^T).
Eigen::VectorXd dense_reduced_eigenvalues(const Eigen::MatrixXd& energy_hessian,
                                          const Eigen::MatrixXd& weighted_hessian, double sign,
                                          const Eigen::MatrixXd& jacobian,
                                          const std::vector<Eigen::Index>& active,
                                          const std::vector<Eigen::Index>& free) {
  const Eigen::MatrixXd h = (energy_hessian - sign * weighted_hessian)(free, free);
  const auto nf = static_cast<Eigen::Index>(free.size());
  const auto m = static_cast<Eigen::Index>(active.size());
  Eigen::MatrixXd z = Eigen::MatrixXd::Identity(nf, nf);
  if (m > 0) {
    const Eigen::MatrixXd j_a = jacobian(active, free);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(j_a.transpose());
    const Eigen::MatrixXd q = qr.householderQ();
    z = q.rightCols(nf - m);
  }
  const Eigen::MatrixXd reduced = z.transpose() * h * z;
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (reduced + reduced.transpose()))
      .eigenvalues();
}

int count_below(const Eigen::VectorXd& e, double value) {
  return static_cast<int>((e.array() < value).count());
}

double relative_gap(const Eigen::VectorXd& e) {
  return e.cwiseAbs().minCoeff() / e.cwiseAbs().maxCoeff();
}

// ---------------------------------------------------------------------------------------
// The library's count equals the dense one over four decades of multipliers. Every ninth pair
// is strongly active (mu in [1.5, 2.5] s, threshold s); the others carry mu in [0, 0.9] s,
// below the threshold but in the Hessian. s is in units of the shell's natural force scale F
// (0.079 N): at 0.01 F the constraint curvature is negligible, at 100 F it dominates. The two
// dense variants that a wrong implementation would compute, +W instead of -W and W from the
// active multipliers only, differ from the right count at some scales, so the comparison can
// tell them apart.
TEST(ContactStability, MatchesDenseReducedHessianOfTheLagrangian) {
  FoldedDisc scene;
  ContactGapConstraints gaps = scene.gaps(false);
  const Eigen::Index m = gaps.count();
  ASSERT_EQ(m, 43);  // measured: vertex-triangle pairs of 43 vertices
  const double force = scene.model.natural_force_scale();

  Eigen::SparseMatrix<double> energy_upper = scene.model.hessian_pattern();
  scene.model.evaluate(scene.x, 0.0, nullptr, &energy_upper);
  const Eigen::MatrixXd energy_hessian = dense_symmetric(energy_upper);
  RowMajor jacobian_sparse = gaps.jacobian_pattern();
  Eigen::VectorXd values;
  gaps.evaluate(scene.x, values, &jacobian_sparse);
  const Eigen::MatrixXd jacobian = Eigen::MatrixXd(jacobian_sparse);

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int flipped_differs = 0, dropped_differs = 0;
  for (const double s : {0.01, 1.0, 10.0, 100.0}) {
    Eigen::VectorXd mu(m);
    Eigen::VectorXd mu_active = Eigen::VectorXd::Zero(m);
    std::vector<Eigen::Index> active;
    for (Eigen::Index k = 0; k < m; ++k) {
      if (k % 9 == 0) {
        mu(k) = s * force * (1.5 + unit(rng));
        mu_active(k) = mu(k);
        active.push_back(k);
      } else {
        mu(k) = s * force * 0.9 * unit(rng);
      }
    }
    ObjectiveAtParameter rest_energy(scene.model, 0.0);  // no growth in these scenes
    const ReducedInertia r =
        contact_constrained_inertia(rest_energy, gaps, scene.x, mu, s * force, scene.fixed);

    Eigen::SparseMatrix<double> w = gaps.hessian_pattern();
    gaps.weighted_hessian(scene.x, mu, w);
    const Eigen::VectorXd e = dense_reduced_eigenvalues(energy_hessian, dense_symmetric(w), 1.0,
                                                        jacobian, active, scene.free);
    // Premise: the dense signs are not round-off (measured gaps 1e-7 .. 1e-5 of the largest
    // eigenvalue, against a dense error of order 1e-15).
    ASSERT_GT(relative_gap(e), 1e-9) << "scale " << s;
    EXPECT_EQ(r.negative, count_below(e, 0.0)) << "scale " << s;
    EXPECT_EQ(r.zero, 0) << "scale " << s;
    EXPECT_EQ(r.constraints, 5);
    EXPECT_EQ(r.free_dofs, static_cast<int>(scene.free.size()));
    RecordProperty("negative_at_scale_" + std::to_string(static_cast<int>(100 * s)), r.negative);

    const Eigen::VectorXd flipped = dense_reduced_eigenvalues(
        energy_hessian, dense_symmetric(w), -1.0, jacobian, active, scene.free);
    flipped_differs += count_below(flipped, 0.0) != r.negative;
    Eigen::SparseMatrix<double> w_active = gaps.hessian_pattern();
    gaps.weighted_hessian(scene.x, mu_active, w_active);
    const Eigen::VectorXd dropped = dense_reduced_eigenvalues(
        energy_hessian, dense_symmetric(w_active), 1.0, jacobian, active, scene.free);
    dropped_differs += count_below(dropped, 0.0) != r.negative;
  }
  EXPECT_GE(flipped_differs, 1);
  EXPECT_GE(dropped_differs, 1);
  RecordProperty("scales_where_flipped_sign_differs", flipped_differs);
  RecordProperty("scales_where_dropping_inactive_differs", dropped_differs);
}

// No multiplier above the threshold: no constraint restricts the directions, and with zero
// (or negligible) multipliers the count is the plain inertia of the energy Hessian on the free
// dofs (the folded, wobbled disc is far from equilibrium: measured 41 negative eigenvalues of
// 192, smallest |eigenvalue| 1.8e-3 N/m against 240 N/m).
TEST(ContactStability, NoActivePairGivesThePlainInertiaOfTheEnergy) {
  FoldedDisc scene;
  ContactGapConstraints gaps = scene.gaps(false);
  const double force = scene.model.natural_force_scale();
  Eigen::SparseMatrix<double> energy_upper = scene.model.hessian_pattern();
  scene.model.evaluate(scene.x, 0.0, nullptr, &energy_upper);
  const Eigen::MatrixXd h = dense_symmetric(energy_upper)(scene.free, scene.free);
  const Eigen::VectorXd e = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(h).eigenvalues();
  ASSERT_GT(relative_gap(e), 1e-9);
  const int plain = count_below(e, 0.0);
  EXPECT_GT(plain, 0);
  EXPECT_EQ(reduced_hessian_inertia(energy_upper, Eigen::SparseMatrix<double>(0, scene.model.dimension()),
                                    scene.fixed)
                .negative,
            plain);

  // Zero multipliers, threshold 0 (strictly above is active): nothing active.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(gaps.count());
  ObjectiveAtParameter rest_energy(scene.model, 0.0);  // no growth in these scenes
  const ReducedInertia r0 = contact_constrained_inertia(rest_energy, gaps, scene.x, zero, 0.0,
                                                        scene.fixed);
  EXPECT_EQ(r0.constraints, 0);
  EXPECT_EQ(r0.negative, plain);
  EXPECT_EQ(r0.zero, 0);
  EXPECT_EQ(r0.free_dofs, static_cast<int>(scene.free.size()));
  // Barrier remnants like Ipopt's (1e-9 F) below a threshold of 1e-6 F: the same counts (their
  // Hessian contribution, ~1e-9 F / 0.06 m = 1e-9 N/m, is far below the smallest eigenvalue).
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd remnants(gaps.count());
  for (Eigen::Index k = 0; k < remnants.size(); ++k) remnants(k) = 1e-9 * force * unit(rng);
  const ReducedInertia r1 = contact_constrained_inertia(rest_energy, gaps, scene.x, remnants,
                                                        1e-6 * force, scene.fixed);
  EXPECT_EQ(r1.constraints, 0);
  EXPECT_EQ(r1.negative, plain);
  EXPECT_EQ(r1.zero, 0);
}

// ---------------------------------------------------------------------------------------
// A particle p pushed with force F onto a point obstacle a (a corner of a held triangle) at
// contact distance r: c = |p - a| - r, active with mu = F. With tangential springs k and a
// normal spring k_n, E = F n.p + k |P_t (p - p0)|^2 / 2 + k_n (n.(p - p0))^2 / 2, d2E/dp2 is
// positive definite, but d2c/dp2 = P_t / r, so H_L = (k - F / r) P_t + k_n n n^T, and on the
// tangent plane of the contact Z^T H_L Z = (k - F / r) I_2: a ball balanced on a ball is
// unstable unless the springs hold it, whatever the sign of d2E. The wrong sign of the
// constraint term (E + mu c) would make it stable for every k. The energy's Hessian pattern
// (p's 3 x 3 block) differs from the constraint's (all four points), so the patterns are
// merged.
class ParticleEnergy : public SparseObjective {
 public:
  ParticleEnergy(Eigen::Vector3d normal, Eigen::Vector3d p0, double force, double k, double k_n)
      : n_(normal), p0_(p0), force_(force), k_(k), k_n_(k_n) {}
  Eigen::Index dimension() const override { return 12; }
  Eigen::SparseMatrix<double> hessian_pattern() const override {
    Eigen::SparseMatrix<double> h(12, 12);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r <= c; ++r) h.insert(r, c) = 1.0;
    h.makeCompressed();
    return h;
  }
  double evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                  Eigen::SparseMatrix<double>* hessian_upper) override {
    const Eigen::Matrix3d tangential = Eigen::Matrix3d::Identity() - n_ * n_.transpose();
    const Eigen::Matrix3d stiffness = k_ * tangential + k_n_ * n_ * n_.transpose();
    const Eigen::Vector3d u = x.head<3>() - p0_;
    if (gradient != nullptr) {
      *gradient = Eigen::VectorXd::Zero(12);
      gradient->head<3>() = force_ * n_ + stiffness * u;
    }
    if (hessian_upper != nullptr) {
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r <= c; ++r) hessian_upper->coeffRef(r, c) = stiffness(r, c);
    }
    return force_ * n_.dot(x.head<3>()) + 0.5 * u.dot(stiffness * u);
  }

 private:
  Eigen::Vector3d n_, p0_;
  double force_, k_, k_n_;
};

struct ParticleOnAPoint {
  static constexpr double kR = 0.1;     // contact distance r (m)
  static constexpr double kForce = 2.0;  // F (N); F / r = 20 N/m
  const Eigen::Vector3d normal = Eigen::Vector3d(-1.0, -1.0, 1.0).normalized();
  ContactProxy proxy;
  ContactCandidates pairs;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(12);
  std::vector<Eigen::Index> fixed = {3, 4, 5, 6, 7, 8, 9, 10, 11};  // the triangle

  ParticleOnAPoint() {
    // Points: p, then the triangle a = 0, b = e_x, c = e_y in z = 0; p's projection
    // (-r/sqrt(3), -r/sqrt(3), 0) lies in the Voronoi region of vertex a.
    Eigen::MatrixX3d points(4, 3);
    points.row(0) = kR * normal.transpose();
    points.row(1) << 0, 0, 0;
    points.row(2) << 1, 0, 0;
    points.row(3) << 0, 1, 0;
    proxy.map.resize(12, 12);
    proxy.map.setIdentity();
    proxy.triangles.resize(1, 3);
    proxy.triangles << 1, 2, 3;
    proxy.edges.resize(3, 2);
    proxy.edges << 1, 2, 1, 3, 2, 3;
    proxy.reference_positions = points;
    pairs.vertex_triangle.resize(1, 2);
    pairs.vertex_triangle << 0, 0;
    pairs.edge_edge.resize(0, 2);
    for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = points.row(i).transpose();
  }
  ParticleEnergy energy(double k) const {
    return ParticleEnergy(normal, x.head<3>(), kForce, k, 50.0);
  }
};

TEST(ContactStability, ParticlePushedOntoAPointNeedsSpringsStifferThanForceOverDistance) {
  ParticleOnAPoint s;
  ContactGapConstraints gaps(s.proxy, s.pairs, ParticleOnAPoint::kR, 12);
  // Premises: the pair touches (c = 0 to round-off) in the vertex region, and mu = F is the KKT
  // multiplier: dE/dx = mu dc/dx on the free dofs.
  const ContactPairGeometry g = gaps.pair_geometry(s.x, 0);
  ASSERT_EQ(g.point_triangle_region, PointTriangleRegion::VertexA);
  ASSERT_NEAR(g.gap, 0.0, 1e-15);
  const Eigen::VectorXd mu = Eigen::VectorXd::Constant(1, ParticleOnAPoint::kForce);
  {
    ParticleEnergy e = s.energy(1.0);
    Eigen::VectorXd gradient, values;
    e.evaluate(s.x, &gradient, nullptr);
    RowMajor j = gaps.jacobian_pattern();
    gaps.evaluate(s.x, values, &j);
    const Eigen::VectorXd residual = gradient - Eigen::MatrixXd(j).transpose() * mu;
    ASSERT_LE(residual.head<3>().lpNorm<Eigen::Infinity>(), 1e-14);
  }
  const double critical = ParticleOnAPoint::kForce / ParticleOnAPoint::kR;  // 20 N/m
  for (const double k : {0.5 * critical, 0.99 * critical}) {
    ParticleEnergy e = s.energy(k);
    const ReducedInertia r = contact_constrained_inertia(e, gaps, s.x, mu, 0.0, s.fixed);
    EXPECT_EQ(r.negative, 2) << "k " << k;
    EXPECT_EQ(r.zero, 0);
    EXPECT_EQ(r.constraints, 1);
    EXPECT_EQ(r.free_dofs, 3);
    // Threshold above F: the contact no longer restricts the directions but its curvature
    // stays in H_L; the normal direction is held by k_n, so the count is again 2.
    const ReducedInertia free = contact_constrained_inertia(e, gaps, s.x, mu, 3.0, s.fixed);
    EXPECT_EQ(free.negative, 2) << "k " << k;
    EXPECT_EQ(free.constraints, 0);
  }
  for (const double k : {1.01 * critical, 4.0 * critical}) {
    ParticleEnergy e = s.energy(k);
    const ReducedInertia r = contact_constrained_inertia(e, gaps, s.x, mu, 0.0, s.fixed);
    EXPECT_EQ(r.negative, 0) << "k " << k;
    EXPECT_EQ(r.zero, 0);
  }
}

// Coinciding pairs: with edge-edge pairs, a vertex-triangle pair whose closest feature is an
// edge or a vertex measures the same distance as an edge-edge pair in an endpoint region, with
// an identical Jacobian row (measured on this scene: 68 of 274 pairs duplicate another). Both
// strongly active, the Jacobian is rank deficient and the count would be wrong; it is an error.
TEST(ContactStability, CoincidingActivePairsAreReportedAsRankDeficient) {
  FoldedDisc scene;
  ContactGapConstraints gaps = scene.gaps(true);
  RowMajor jacobian_sparse = gaps.jacobian_pattern();
  Eigen::VectorXd values;
  gaps.evaluate(scene.x, values, &jacobian_sparse);
  const Eigen::MatrixXd j = Eigen::MatrixXd(jacobian_sparse);
  Eigen::Index first = -1, second = -1;
  for (Eigen::Index a = 0; a < j.rows() && first < 0; ++a) {
    for (Eigen::Index b = a + 1; b < j.rows(); ++b) {
      if ((j.row(a) - j.row(b)).norm() <= 1e-12 * j.row(a).norm()) {
        first = a;
        second = b;
        break;
      }
    }
  }
  ASSERT_GE(first, 0) << "no coinciding pairs found";
  ASSERT_NE(gaps.pair_type(first), gaps.pair_type(second));
  const double force = scene.model.natural_force_scale();
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(gaps.count());
  mu(first) = mu(second) = force;
  ObjectiveAtParameter rest_energy(scene.model, 0.0);  // no growth in these scenes
  std::string message = "no exception";
  try {
    contact_constrained_inertia(rest_energy, gaps, scene.x, mu, 0.1 * force, scene.fixed);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("rank deficient"), std::string::npos) << message;
  EXPECT_NE(message.find("1 of its 2 rows"), std::string::npos) << message;
  // Either one alone is fine.
  mu(second) = 0.0;
  EXPECT_EQ(contact_constrained_inertia(rest_energy, gaps, scene.x, mu, 0.1 * force, scene.fixed)
                .constraints,
            1);
}

// ---------------------------------------------------------------------------------------
// End to end: a contact equilibrium from solve_contact_equilibrium is a strict local minimum.
// The scene of test_contact_equilibrium.cpp, built more simply: a top strip (0.6 x 0.1 m,
// h = 0.02 m) bent into an arc of radius 1 m over a flat bottom strip (0.4 x 0.2 m, held),
// its clamped ends (two grid columns and the ghost column at each end) lowered by 0.25 h so
// that it presses onto the bottom strip; the two ghost corners of each strip that lie in no
// element are held too (they carry no energy). Ipopt starts from the built arc 1.1 h above the
// bottom strip.
TEST(ContactStability, PressedStripEquilibriumIsStable) {
  constexpr double h = 0.02, rho = 1.0, mid = 0.3;
  StripMeshOptions top;
  top.length = 0.6;
  top.width = 0.1;
  top.cells_x = 12;
  top.cells_y = 2;
  StripMeshOptions bottom;
  bottom.length = 0.4;
  bottom.width = 0.2;
  bottom.cells_x = 8;
  bottom.cells_y = 4;
  const TriangleMesh a = make_strip_mesh(top);
  const TriangleMesh b = make_strip_mesh(bottom);
  const Eigen::Index top_vertices = a.vertices.rows();
  TriangleMesh mesh;
  // The bottom strip lies 1 m away in the reference (so the exclusion radius only separates
  // points of one strip) and is shifted by 0.113 m in x so that no proxy vertex of one strip
  // lies exactly over an edge of the other.
  mesh.vertices.resize(top_vertices + b.vertices.rows(), 3);
  mesh.vertices << a.vertices, b.vertices.rowwise() + Eigen::RowVector3d(0.113, -1.0, 0.0);
  mesh.faces.resize(a.faces.rows() + b.faces.rows(), 3);
  mesh.faces << a.faces, (b.faces.array() + static_cast<int>(top_vertices)).matrix();
  ShellModel model(mesh, ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 3);
  const Eigen::Index n = model.dimension();

  std::vector<Eigen::Index> fixed;
  Eigen::VectorXd x0 = model.reference_positions();
  const std::vector<int> idle = {strip_vertex_index(top, top.cells_x + 1, -1),
                                 strip_vertex_index(top, -1, top.cells_y + 1)};
  for (Eigen::Index v = 0; v < n / 3; ++v) {
    bool held = v >= top_vertices || std::find(idle.begin(), idle.end(), v) != idle.end();
    if (v < top_vertices) {
      const int column = static_cast<int>(v % (top.cells_x + 3)) - 1;
      const bool clamped = column <= 1 || column >= top.cells_x - 1;
      held = held || clamped;
      const double s = x0(3 * v) - mid;
      x0(3 * v) = mid + rho * std::sin(s / rho);
      x0(3 * v + 2) = 1.1 * h + rho * (1.0 - std::cos(s / rho)) - (clamped ? 0.25 * h : 0.0);
    } else {
      x0(3 * v + 1) += 1.0;
    }
    if (held)
      for (int c = 0; c < 3; ++c) fixed.push_back(3 * v + c);
  }

  const double force = 1e-3;  // N, the scene's contact force scale
  const ContactSolveOptions o = test_support::strict_contact_solve_options(h, force);
  const ContactSolveResult r = solve_contact_equilibrium(model, 0.0, proxy, x0, fixed, o);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_TRUE(r.used_contact) << r.message;

  ContactGapConstraints gaps(proxy, r.pairs, h, n, o.gap);
  // Strongly active: above 1e-3 of the largest force. Ipopt's barrier remnants on the other
  // pairs are ~1e-13 N (tolerance 1e-10 h F over gaps of order h), eight decades lower.
  const double threshold = 1e-3 * r.forces.maxCoeff();
  ObjectiveAtParameter rest_energy(model, 0.0);  // no growth in these scenes
  const ReducedInertia inertia =
      contact_constrained_inertia(rest_energy, gaps, r.x, r.forces, threshold, fixed);
  EXPECT_EQ(inertia.negative, 0);
  EXPECT_EQ(inertia.zero, 0);
  EXPECT_GE(inertia.constraints, 1);
  RecordProperty("pairs", static_cast<int>(gaps.count()));
  RecordProperty("strongly_active_pairs", inertia.constraints);

  // The same from the dense pieces, with the smallest reduced eigenvalue clearly positive.
  Eigen::SparseMatrix<double> energy_upper = model.hessian_pattern();
  model.evaluate(r.x, 0.0, nullptr, &energy_upper);
  Eigen::SparseMatrix<double> w = gaps.hessian_pattern();
  gaps.weighted_hessian(r.x, r.forces, w);
  RowMajor jacobian = gaps.jacobian_pattern();
  Eigen::VectorXd values;
  gaps.evaluate(r.x, values, &jacobian);
  std::vector<Eigen::Index> active, free;
  for (Eigen::Index k = 0; k < gaps.count(); ++k)
    if (r.forces(k) > threshold) active.push_back(k);
  for (Eigen::Index d = 0; d < n; ++d)
    if (std::find(fixed.begin(), fixed.end(), d) == fixed.end()) free.push_back(d);
  const Eigen::VectorXd e =
      dense_reduced_eigenvalues(dense_symmetric(energy_upper), dense_symmetric(w), 1.0,
                                Eigen::MatrixXd(jacobian), active, free);
  EXPECT_GT(e.minCoeff(), 1e-9 * e.maxCoeff());
  EXPECT_EQ(inertia.constraints, static_cast<int>(active.size()));
  RecordProperty("smallest_reduced_eigenvalue_relative", std::to_string(e.minCoeff() / e.maxCoeff()));
}

TEST(ContactStability, RejectsBadInputNamingIt) {
  ParticleOnAPoint s;
  ContactGapConstraints gaps(s.proxy, s.pairs, ParticleOnAPoint::kR, 12);
  ParticleEnergy e = s.energy(1.0);
  const Eigen::VectorXd mu = Eigen::VectorXd::Constant(1, 1.0);
  auto message_of = [&](const std::function<void()>& call) {
    try {
      call();
    } catch (const std::invalid_argument& ex) {
      return std::string(ex.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(e, gaps, Eigen::VectorXd::Zero(9), mu, 0.0, s.fixed);
            }).find("x has size 9, expected 12"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(e, gaps, s.x, Eigen::VectorXd::Zero(2), 0.0, s.fixed);
            }).find("multipliers has size 2, expected 1"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(e, gaps, s.x, Eigen::VectorXd::Constant(1, -1.0), 0.0,
                                          s.fixed);
            }).find("multiplier 0 is -1"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(
                  e, gaps, s.x, Eigen::VectorXd::Constant(1, std::numeric_limits<double>::quiet_NaN()),
                  0.0, s.fixed);
            }).find("multiplier 0"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(e, gaps, s.x, mu, -1.0, s.fixed);
            }).find("active_force_threshold"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(e, gaps, s.x, mu, 0.0, {12});
            }).find("fixed dof 12"),
            std::string::npos);
  ContactGapConstraints wider(s.proxy, s.pairs, ParticleOnAPoint::kR, 13);
  EXPECT_NE(message_of([&] {
              contact_constrained_inertia(e, wider, s.x, mu, 0.0, s.fixed);
            }).find("the energy has 12 unknowns but the constraints have 13"),
            std::string::npos);
}

}  // namespace
}  // namespace growshell
