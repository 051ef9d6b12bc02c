// solve_contact_equilibrium:
//  - a strip pressed onto a parallel one stops at distance h, its contact forces balance the
//    load and form one contact zone, and without load the no-contact fast path is taken;
//  - far from touching the result is plain Newton's, bit for bit;
//  - a pair missed at the start triggers a second round; warm restarts;
//  - after every converged solve no pair is closer than h - violation_tolerance;
//  - relax_with_contact with a bound on the Newton step searches the pairs again before two
//    layers can pass through each other (unbounded, the same relaxation passes through);
//  - near_contact_pairs against brute force with exact distances on the pressed strip (on a
//    folded disc: tests/contact/test_near_contact_pairs.cpp; contact zones on hand-made pairs:
//    tests/analysis/test_contact_zones.cpp);
//  - bad options and bad input are rejected with messages naming them.
//
// The shell scene: two strips in one ShellModel (h = 0.02 m, Y = 1e4 Pa, nu = 0.3). The
// bottom strip (0.4 x 0.2 m) lies flat in z = 0 and is held completely. The top strip
// (0.6 x 0.1 m) lies over it as a circular arc of radius 1 m, lowest in its middle, with both
// ends clamped (the ghost column and the first two columns at each end held). The energy has
// no load term (solve_contact_equilibrium takes the ShellModel itself, so a load potential
// cannot be added), so the load is a prescribed displacement: the clamps are lowered by
// `drop` below the arc. An arc whose unloaded lowest point would end below z = h is then
// pressed onto the bottom strip along its middle line, where by symmetry its tangent plane
// is parallel to the bottom strip; the clamps carry the load, so the clamp reactions are the
// applied force. In the reference the two strips lie side by side 1 m apart, so the
// exclusion radius only separates points of the same strip.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/analysis/contact_zones.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/limit_surface_contact.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "support/near_pairs_brute_force.hpp"
#include "support/pressed_strips.hpp"

namespace growshell {
namespace {

using test_support::expect_same_pairs;
using test_support::expected_near_pairs;
using test_support::closest_pair;
using test_support::TwoStrips;

constexpr double kPi = 3.14159265358979323846;
using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// Check 3, after every converged solve: no pair is closer than h - violation_tolerance.
void expect_no_pair_too_close(const TwoStrips& s, const ContactSolveOptions& o,
                              const ContactSolveResult& r) {
  const double closest =
      closest_pair(s.proxy, r.x, o.contact_distance + o.candidate_margin, o.exclusion_radius);
  EXPECT_GE(closest, o.contact_distance - o.violation_tolerance) << "closest pair " << closest;
}

// ---------------------------------------------------------------------------------------
// (1) The pressed strip stops at distance h, the contact forces balance the clamp load, and
// everything is consistent with the KKT conditions.
TEST(ContactEquilibrium, PressedStripStopsAtDistanceHAndForcesBalanceTheLoad) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  const ContactSolveOptions o = s.options();
  // Unloaded, the arc's lowest control points would sit at h + 0.1 h - 0.25 h = 0.85 h: the
  // contact takes up 0.15 h of prescribed displacement. The start is propped at 1.1 h, inside
  // the candidate margin (0.25 h), so the touching pairs are constrained from the first round.
  const Eigen::VectorXd x0 = s.propped(1.1 * h, 0.25 * h);
  const double start_gap = closest_pair(s.proxy, x0, h + o.candidate_margin, o.exclusion_radius);
  ASSERT_GT(start_gap, h);
  ASSERT_LT(start_gap, h + o.candidate_margin);
  const ContactSolveResult r = solve_contact_equilibrium(s.model, 0.0, s.proxy, x0, s.fixed(), o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_TRUE(r.used_contact);
  EXPECT_EQ(r.rounds, 1);
  EXPECT_EQ(r.message, "converged with contact");
  expect_no_pair_too_close(s, o, r);
  for (const Eigen::Index d : s.fixed()) ASSERT_EQ(r.x(d), x0(d)) << "fixed dof " << d;

  // The layers end exactly h apart: within violation_tolerance = 1e-6 h, which Ipopt's
  // constraint_violation_tolerance (1e-9 h) and complementarity (1e-10 h F over forces of
  // ~9 F) both undercut by three decades. Measured: lowest - h = -9.8e-11 h, the same for
  // min_distance (12 Ipopt iterations, 182 constrained pairs).
  const double lowest = s.top_lowest(r.x);
  EXPECT_NEAR(lowest, h, o.violation_tolerance);
  EXPECT_NEAR(r.min_distance, h, o.violation_tolerance);

  // Forces through the exact constraint Jacobian: J^T mu is the contact force on each dof.
  const Eigen::Index n = s.model.dimension();
  ContactGapConstraints gaps(s.proxy, r.pairs, h, n, o.gap);
  RowMajor jac = gaps.jacobian_pattern();
  Eigen::VectorXd c;
  gaps.evaluate(r.x, c, &jac);
  const Eigen::VectorXd push = jac.transpose() * r.forces;
  Eigen::VectorXd g;
  s.model.evaluate(r.x, 0.0, &g, nullptr);
  Eigen::Vector3d on_top = Eigen::Vector3d::Zero(), on_bottom = Eigen::Vector3d::Zero(),
                  clamp = Eigen::Vector3d::Zero();
  for (const Eigen::Index d : s.top_dofs) on_top(d % 3) += push(d);
  for (const Eigen::Index d : s.bottom_dofs) on_bottom(d % 3) += push(d);
  for (const Eigen::Index d : s.clamp_dofs) clamp(d % 3) += g(d);
  Eigen::VectorXd residual = g - push;
  for (const Eigen::Index d : s.fixed()) residual(d) = 0.0;
  const double load = -clamp.z();  // downward pull of the clamps on the strip = applied load (N)
  const double total = r.forces.sum();
  double active = 0.0;
  int active_pairs = 0;
  double worst_active_gap = 0.0;
  for (Eigen::Index k = 0; k < r.forces.size(); ++k) {
    if (r.forces(k) > 1e-3 * r.forces.maxCoeff()) {
      ++active_pairs;
      active += r.forces(k);
      worst_active_gap = std::max(worst_active_gap, std::abs(gaps.pair_geometry(r.x, k).gap));
    }
  }
  // Balance. KKT on the free dofs and the top strip's translation invariance make the
  // vertical contact force on it equal the clamps' pull, to the out-of-balance force summed
  // over its ~220 free dofs (dual tolerance 1e-10 F each): ~2e-8 F against a load of ~9 F,
  // so 1e-6 relative has a 50x margin. Measured: load 8.85e-3 N, relative mismatch 4.9e-14;
  // the free-dof residual is 6.5e-15 N.
  EXPECT_GT(load, 5.0 * TwoStrips::kForce);
  EXPECT_NEAR(on_top.z(), load, 1e-6 * load);
  EXPECT_LE(residual.lpNorm<Eigen::Infinity>(), 1e-10 * TwoStrips::kForce);
  // The bottom strip is flat, so every pair pushes along z with |grad d| = 1 and the sum of
  // the multipliers is the same force; the inactive pairs add their barrier remnants
  // (>= 0, each ~1e-13 N). Measured: 1.3e-12 relative.
  EXPECT_GE(r.forces.minCoeff(), 0.0);
  EXPECT_NEAR(total, load, 1e-6 * load);
  // Action = reaction exactly (the pair weights sum to zero and the proxy map's rows to one):
  // measured 2e-16 relative. Frictionless and flat: no horizontal force on the top strip
  // (measured 2.4e-11 and 4.5e-13 of the load in x, y).
  EXPECT_LE((on_top + on_bottom).norm(), 1e-12 * load);
  EXPECT_LE(std::abs(on_top.x()), 1e-6 * load);
  EXPECT_LE(std::abs(on_top.y()), 1e-6 * load);
  // The pairs that carry the load touch: |gap| <= 1e-6 h (measured 9.8e-11 h). Anticlastic
  // bending curls the strip's long edges down by about nu (W / 2)^2 / (2 rho) = 0.02 h, so
  // the load goes through the two ends of the middle line (measured: 2 pairs carry all of
  // it).
  EXPECT_LE(worst_active_gap, 1e-6 * h);
  EXPECT_EQ(active_pairs, 2);

  // One contact zone (linked at 0.2 m, twice the strip's width) on the middle line, with the
  // bottom strip's normal +z and, by the scene's symmetry under the half turn about the
  // vertical through (0.3, 0), its centroid at (0.3, 0, h / 2). Ipopt's relative tolerance
  // 1e-10 bounds the asymmetry of the two forces; 1e-9 m leaves 100x (measured 7e-12 m).
  const std::vector<ContactZone> zones = contact_zones(gaps, r.x, r.forces, 0.2);
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_NEAR(zones[0].force, active, 1e-12 * active);
  EXPECT_LE((zones[0].normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  EXPECT_LE((zones[0].centroid - Eigen::Vector3d(TwoStrips::kMid, 0, 0.5 * h)).norm(), 1e-9);
  EXPECT_TRUE(std::isnan(contact_plane_angle(zones)));
}

// (1b) Zero load (clamps not lowered, the arc 2 margins clear of the bottom strip): no pair is
// near, the no-contact fast path is used.
TEST(ContactEquilibrium, UnloadedStripUsesTheNoContactFastPath) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  const ContactSolveOptions o = s.options();
  const Eigen::VectorXd x0 = s.state(h + 2.0 * o.candidate_margin, 0.0);
  const ContactSolveResult r = solve_contact_equilibrium(s.model, 0.0, s.proxy, x0, s.fixed(), o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_FALSE(r.used_contact);
  EXPECT_EQ(r.forces.size(), 0);
  EXPECT_TRUE(r.pairs.empty());
  EXPECT_EQ(r.rounds, 1);
  EXPECT_EQ(r.message, "converged without contact");
  EXPECT_EQ(r.min_distance, std::numeric_limits<double>::infinity());
  // The built arc is not exactly the plate's equilibrium (anticlastic bending): Newton moves
  // it by 0.1 h in 4 iterations (measured), its lowest point ending at 1.48 h.
  EXPECT_GT(s.top_lowest(r.x), h + o.candidate_margin);
  expect_no_pair_too_close(s, o, r);
}

// (2) Far from touching: one Newton solve, bit for bit the plain NewtonSolver's result.
TEST(ContactEquilibrium, FarStateEqualsPlainNewtonExactly) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  const ContactSolveOptions o = s.options();
  // Loaded (clamps lowered by 0.5 h, from a kinked start) but with 3 h of clearance.
  const Eigen::VectorXd x0 = s.state(4.0 * h, 0.5 * h);
  const ContactSolveResult r = solve_contact_equilibrium(s.model, 0.0, s.proxy, x0, s.fixed(), o);
  ObjectiveAtParameter energy(s.model, 0.0);
  const NewtonResult plain = NewtonSolver(o.newton).minimize(energy, x0, s.fixed());
  ASSERT_TRUE(plain.converged()) << plain.message;
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_FALSE(r.used_contact);
  EXPECT_EQ(r.rounds, 1);
  EXPECT_EQ(r.forces.size(), 0);
  EXPECT_TRUE(r.pairs.empty());
  EXPECT_GT(plain.iterations, 1);
  EXPECT_EQ(r.iterations, plain.iterations);
  EXPECT_TRUE(r.x == plain.x);
  // Measured: 7 Newton iterations, the strip moving by 0.6 h and ending 3.5 h high.
  expect_no_pair_too_close(s, o, r);
}

// Rounds: with a candidate margin smaller than the start's clearance no pair is near, the
// Newton fast path passes through the bottom strip, and the second round constrains the
// pairs found there. With max_rounds = 1 the same call reports the crossing instead.
TEST(ContactEquilibrium, PairMissedAtTheStartTriggersASecondRound) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  ContactSolveOptions o = s.options();
  o.candidate_margin = 0.05 * h;
  const Eigen::VectorXd x0 = s.propped(1.1 * h, 0.25 * h);
  ASSERT_TRUE(near_contact_pairs(s.proxy, x0, h + o.candidate_margin, o.exclusion_radius).empty());
  const ContactSolveResult r = solve_contact_equilibrium(s.model, 0.0, s.proxy, x0, s.fixed(), o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.rounds, 2);
  EXPECT_TRUE(r.used_contact);
  EXPECT_GT(r.forces.size(), 0);
  EXPECT_NEAR(s.top_lowest(r.x), h, o.violation_tolerance);
  expect_no_pair_too_close(s, o, r);

  o.max_rounds = 1;
  const ContactSolveResult once = solve_contact_equilibrium(s.model, 0.0, s.proxy, x0, s.fixed(), o);
  EXPECT_FALSE(once.converged);
  EXPECT_EQ(once.rounds, 1);
  EXPECT_FALSE(once.used_contact);
  EXPECT_LT(once.min_distance, h - o.violation_tolerance);
  EXPECT_NE(once.message.find("after 1 rounds"), std::string::npos) << once.message;
  EXPECT_TRUE(once.x.allFinite());
  // x is the state of the last solve: the Newton pass, which ends with the layers 0.83 h
  // apart (measured; 17 iterations in all for the two rounds above).
  ObjectiveAtParameter energy(s.model, 0.0);
  EXPECT_TRUE(once.x == NewtonSolver(o.newton).minimize(energy, x0, s.fixed()).x);
}

// relax_with_contact (the penalty relaxation of the growth path) from a start 4 h above the
// bottom strip, with the held end columns 8 h lower, so that the unloaded strip would sag
// far below the bottom one, and a candidate margin of h / 2: no pair is near at the start.
// Unbounded, the first Newton steps carry the top strip through the bottom one, whose
// triangles are not in the penalty, and the relaxation ends on the wrong side. With steps
// bounded by h / 4 each solve stops once a dof has moved h / 8 and the pairs are searched
// again, so the strip is caught at distance h less the penalty's penetration (force / (k x pairs);
// measured 0.0066 h at k = 1e4 N/m, bounded by 0.01 h). Unbounded it ends 4 h below the bottom
// strip.
TEST(RelaxWithContact, BoundedNewtonStepsCannotPassThroughALayer) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  ContactBranchOptions o;
  o.contact_distance = h;
  o.exclusion_radius = 0.5 * kPi * h;
  o.candidate_margin = 0.5 * h;
  o.stiffness = 1e4;
  o.selection = NearPairSelection{false, true};
  // The top strip as the unloaded arc 4 h above the bottom one, except its outermost columns
  // (x <= 0 and x >= 0.6 m, beyond the bottom strip's 0.113 ... 0.513 m by more than
  // h + margin), which are lowered by 8 h and held.
  Eigen::VectorXd x0 = s.state(4.0 * h, 0.0);
  std::vector<Eigen::Index> held = s.bottom_dofs;
  for (Eigen::Index v = 0; v < s.top_vertices; ++v) {
    const int column = s.top_column[static_cast<std::size_t>(v)];
    if (column > 0 && column < s.top_mesh.cells_x) continue;
    x0(3 * v + 2) -= 8.0 * h;
    for (int c = 0; c < 3; ++c) held.push_back(3 * v + c);
  }
  std::sort(held.begin(), held.end());
  ASSERT_TRUE(near_penalty_pairs(s.proxy, x0, o).empty());
  // Lowest point of the top strip's proxy over the bottom strip (m).
  const auto over_bottom = [&](const Eigen::VectorXd& x) {
    const Eigen::MatrixX3d y = proxy_positions(s.proxy, x);
    double lowest = std::numeric_limits<double>::infinity();
    for (Eigen::Index p = 0; p < y.rows(); ++p)
      if (s.proxy.vertex_element(p) < s.top_elements() && y(p, 0) > TwoStrips::kBottomShiftX &&
          y(p, 0) < TwoStrips::kBottomShiftX + s.bottom_mesh.length)
        lowest = std::min(lowest, y(p, 2));
    return lowest;
  };
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-10;
  newton.max_iterations = 400;

  Eigen::VectorXd unbounded = x0;
  relax_with_contact(s.model, 0.0, s.proxy, unbounded, held, o, newton);
  EXPECT_LT(over_bottom(unbounded), -h) << "the unbounded relaxation should pass through";

  newton.max_step_inf_norm = 0.25 * h;
  Eigen::VectorXd bounded = x0;
  const ContactRelaxation relaxed = relax_with_contact(s.model, 0.0, s.proxy, bounded, held, o, newton);
  ASSERT_TRUE(relaxed.relaxed) << relaxed.message;
  // Each bounded solve moves a dof by at most candidate_margin / 4 (+ one capped step), so the
  // way down to the layer takes several solves, each with its own pair search.
  EXPECT_GE(relaxed.solves, 2);
  EXPECT_GE(relaxed.factorizations, relaxed.newton_iterations);
  EXPECT_GT(over_bottom(bounded), h - 0.01 * h);
  EXPECT_GE(closest_pair(s.proxy, bounded, 2.0 * h, o.exclusion_radius), h - 0.01 * h);
}

// Warm start at a solution: the same pairs and their forces; Ipopt stays put.
TEST(ContactEquilibrium, WarmRestartAtTheSolutionStaysThere) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  const ContactSolveOptions o = s.options();
  const Eigen::VectorXd x0 = s.propped(1.1 * h, 0.25 * h);
  const ContactSolveResult first = solve_contact_equilibrium(s.model, 0.0, s.proxy, x0, s.fixed(), o);
  ASSERT_TRUE(first.converged) << first.message;
  const ContactSolveResult again =
      solve_contact_equilibrium(s.model, 0.0, s.proxy, first.x, s.fixed(), o, &first);
  ASSERT_TRUE(again.converged) << again.message;
  // Measured: 12 iterations cold, 1 warm, moving x by 1.2e-11 h and the force sum by 1e-12.
  EXPECT_LE(again.iterations, 5);
  EXPECT_LE((again.x - first.x).lpNorm<Eigen::Infinity>(), 1e-6 * h);
  EXPECT_NEAR(again.forces.sum(), first.forces.sum(), 1e-6 * first.forces.sum());
  expect_no_pair_too_close(s, o, again);
}

// ---------------------------------------------------------------------------------------
// (4) near_contact_pairs (libshell/contact, tested in tests/contact) on the pressed-strip
// scene: exactly the pairs of the brute-force broad phase whose exact distance is below the
// query distance.
TEST(NearContactPairs, TwoStripsAgreeWithBruteForce) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  const Eigen::VectorXd x = s.propped(1.1 * h, 0.25 * h);
  const double r_ex = 0.5 * kPi * h;
  const ContactCandidates want = expected_near_pairs(s.proxy, x, 1.25 * h, r_ex, true, false);
  EXPECT_GT(want.vertex_triangle.rows(), 0);
  expect_same_pairs(near_contact_pairs(s.proxy, x, 1.25 * h, r_ex), want, "two strips");
}

// ---------------------------------------------------------------------------------------
// (5) Bad options are rejected with a message naming the option.
TEST(ContactEquilibrium, RejectsBadOptions) {
  TwoStrips s;
  const Eigen::VectorXd x0 = s.state(4.0 * TwoStrips::kH, 0.0);
  auto message_of = [&](const ContactSolveOptions& o, const Eigen::VectorXd& x) {
    try {
      solve_contact_equilibrium(s.model, 0.0, s.proxy, x, s.fixed(), o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const ContactSolveOptions good = s.options();
  struct Case {
    const char* name;
    double ContactSolveOptions::*field;
    std::vector<double> bad;
  };
  const std::vector<Case> cases = {
      {"contact_distance", &ContactSolveOptions::contact_distance, {0.0, -0.02, nan, inf}},
      {"exclusion_radius", &ContactSolveOptions::exclusion_radius, {0.0, -1.0, nan, inf}},
      {"candidate_margin", &ContactSolveOptions::candidate_margin, {0.0, -1.0, nan, inf}},
      {"violation_tolerance", &ContactSolveOptions::violation_tolerance, {-1e-9, nan, inf}},
  };
  for (const Case& c : cases) {
    for (const double value : c.bad) {
      ContactSolveOptions o = good;
      o.*c.field = value;
      const std::string m = message_of(o, x0);
      EXPECT_NE(m.find(c.name), std::string::npos) << c.name << " = " << value << ": " << m;
    }
  }
  ContactSolveOptions rounds = good;
  rounds.max_rounds = 0;
  EXPECT_NE(message_of(rounds, x0).find("max_rounds"), std::string::npos);
  ContactSolveOptions on_limit_surface = good;
  on_limit_surface.gap.limit_surface = make_limit_surface_contact(s.model, good.exclusion_radius);
  EXPECT_NE(message_of(on_limit_surface, x0).find("gap.limit_surface is not supported"),
            std::string::npos);
  EXPECT_NE(message_of(good, Eigen::VectorXd::Zero(x0.size() - 1)).find("x0"), std::string::npos);
}

}  // namespace
}  // namespace growshell
