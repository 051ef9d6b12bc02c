// solve_contact_equilibrium, near_contact_pairs, contact_zones and contact_plane_angle:
//  - a strip pressed onto a parallel one stops at distance h, its contact forces balance the
//    load, and without load the no-contact fast path is taken;
//  - far from touching the result is plain Newton's, bit for bit;
//  - a pair missed at the start triggers a second round; warm restarts;
//  - after every converged solve no pair is closer than h - violation_tolerance;
//  - relax_with_contact with a bound on the Newton step searches the pairs again before two
//    layers can pass through each other (unbounded, the same relaxation passes through);
//  - near_contact_pairs against brute force with exact distances;
//  - contact zones and plane angles on hand-made pairs with known answers;
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

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/contact_zones.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "support/sheet_states.hpp"

namespace growshell {
namespace {

using test_support::folded_sheet;

constexpr double kPi = 3.14159265358979323846;
using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

StripMeshOptions strip(double length, double width, int cells_x, int cells_y) {
  StripMeshOptions o;
  o.length = length;
  o.width = width;
  o.cells_x = cells_x;
  o.cells_y = cells_y;
  return o;
}

struct TwoStrips {
  static constexpr double kH = 0.02;   // thickness = contact distance (m)
  static constexpr double kRho = 1.0;  // radius of the top strip's unloaded arc (m)
  static constexpr double kMid = 0.3;  // reference x of the top strip's middle column
  static constexpr int kMidColumn = 6;
  // The bottom strip is shifted by 0.113 m in x so that its vertex columns (every 1/3 of
  // 0.05 m on the proxy) miss the top strip's middle line by >= 0.012 m: the touching pairs
  // are then the top's middle-line vertices over the interiors of bottom triangles, with no
  // ties between coincident features.
  static constexpr double kBottomShiftX = 0.113;
  static constexpr double kBottomAwayY = 1.0;  // reference distance of the strips (m)
  // Force unit of the scene: the beam estimate of the contact force is 192 EI delta / l^3 =
  // 3e-3 N for delta = 0.15 h over the free length l = 0.5 m (EI = Y W h^3 / 12).
  static constexpr double kForce = 1e-3;

  StripMeshOptions top_mesh = strip(0.6, 0.1, 12, 2);
  StripMeshOptions bottom_mesh = strip(0.4, 0.2, 8, 4);
  Eigen::Index top_vertices = 0;
  std::vector<int> top_column;  // grid column i of each top-strip vertex
  ShellModel model;
  ContactProxy proxy;
  std::vector<Eigen::Index> bottom_dofs, clamp_dofs, prop_dofs, top_dofs;

  TwoStrips() : model(mesh(), ShellModelSettings{}), proxy(make_contact_proxy(model, 3)) {
    const Eigen::Index n = model.dimension();
    for (Eigen::Index v = 0; v < n / 3; ++v) {
      const bool top = v < top_vertices;
      const int column = top ? top_column[static_cast<std::size_t>(v)] : -2;
      const bool clamped = top && (column <= 1 || column >= top_mesh.cells_x - 1);
      for (int c = 0; c < 3; ++c) {
        if (!top) bottom_dofs.push_back(3 * v + c);
        if (top) top_dofs.push_back(3 * v + c);
        if (clamped) clamp_dofs.push_back(3 * v + c);
      }
      if (top && column == kMidColumn) prop_dofs.push_back(3 * v + 2);
    }
  }

  TriangleMesh mesh() {
    const TriangleMesh a = strip_without_idle_corners(top_mesh, top_column);
    std::vector<int> bottom_column;
    const TriangleMesh b = strip_without_idle_corners(bottom_mesh, bottom_column);
    top_vertices = a.vertices.rows();
    TriangleMesh m;
    m.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
    m.vertices << a.vertices,
        b.vertices.rowwise() + Eigen::RowVector3d(kBottomShiftX, -kBottomAwayY, 0.0);
    m.faces.resize(a.faces.rows() + b.faces.rows(), 3);
    m.faces << a.faces, (b.faces.array() + static_cast<int>(a.vertices.rows())).matrix();
    return m;
  }

  // make_strip_mesh without the ghost corners (cells_x + 1, -1) and (-1, cells_y + 1), which
  // lie in one ghost face each and in no element's control net: free they would be unknowns
  // without energy (a singular Hessian for Ipopt), fixed they have no Hessian entry (which
  // NewtonSolver rejects). `column` receives each kept vertex's grid column i.
  static TriangleMesh strip_without_idle_corners(const StripMeshOptions& o,
                                                 std::vector<int>& column) {
    const TriangleMesh full = make_strip_mesh(o);
    const int idle[2] = {strip_vertex_index(o, o.cells_x + 1, -1),
                         strip_vertex_index(o, -1, o.cells_y + 1)};
    std::vector<int> renumber(static_cast<std::size_t>(full.vertices.rows()), -1);
    TriangleMesh m;
    m.vertices.resize(full.vertices.rows() - 2, 3);
    column.clear();
    int kept = 0;
    for (int v = 0; v < full.vertices.rows(); ++v) {
      if (v == idle[0] || v == idle[1]) continue;
      renumber[static_cast<std::size_t>(v)] = kept;
      m.vertices.row(kept++) = full.vertices.row(v);
      column.push_back(v % (o.cells_x + 3) - 1);
    }
    m.faces.resize(full.faces.rows() - 2, 3);
    int f = 0;
    for (Eigen::Index k = 0; k < full.faces.rows(); ++k) {
      const Eigen::RowVector3i face = full.faces.row(k);
      if ((face.array() == idle[0]).any() || (face.array() == idle[1]).any()) continue;
      for (int c = 0; c < 3; ++c) m.faces(f, c) = renumber[static_cast<std::size_t>(face(c))];
      ++f;
    }
    return m;
  }

  std::vector<Eigen::Index> fixed() const { return joined(bottom_dofs, clamp_dofs); }
  std::vector<Eigen::Index> fixed_and_propped() const { return joined(fixed(), prop_dofs); }
  static std::vector<Eigen::Index> joined(std::vector<Eigen::Index> a,
                                          const std::vector<Eigen::Index>& b) {
    a.insert(a.end(), b.begin(), b.end());
    std::sort(a.begin(), a.end());
    return a;
  }

  // Bottom strip flat in z = 0 under the top strip; top strip on the arc whose lowest control
  // points are at z_low, with the clamped columns lowered by `drop`.
  Eigen::VectorXd state(double z_low, double drop) const {
    Eigen::VectorXd x = model.reference_positions();
    for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
      if (v >= top_vertices) {
        x(3 * v + 1) += kBottomAwayY;
        continue;
      }
      const double s = x(3 * v) - kMid;
      const int column = top_column[static_cast<std::size_t>(v)];
      const bool clamped = column <= 1 || column >= top_mesh.cells_x - 1;
      x(3 * v) = kMid + kRho * std::sin(s / kRho);
      x(3 * v + 2) = z_low + kRho * (1.0 - std::cos(s / kRho)) - (clamped ? drop : 0.0);
    }
    return x;
  }

  // Equilibrium with the clamps lowered by `drop` and the top strip's middle column propped
  // (its control points held at z = z_prop): a smooth, feasible start for the contact solve.
  Eigen::VectorXd propped(double z_prop, double drop) {
    NewtonOptions o;
    o.gradient_tolerance = 1e-10 * kForce;
    const NewtonResult r =
        NewtonSolver(o).minimize(model, state(z_prop, drop), fixed_and_propped());
    EXPECT_TRUE(r.converged()) << r.message;
    return r.x;
  }

  ContactSolveOptions options() const {
    ContactSolveOptions o;
    o.contact_distance = kH;
    o.exclusion_radius = 0.5 * kPi * kH;
    o.candidate_margin = 0.25 * kH;
    o.violation_tolerance = 1e-6 * kH;
    o.minimizer.length_scale = kH;
    o.minimizer.force_scale = kForce;
    o.minimizer.tolerance = 1e-10;
    o.minimizer.acceptable_tolerance = 1e-8;
    o.minimizer.constraint_violation_tolerance = 1e-9 * kH;
    o.minimizer.complementarity_tolerance = 1e-10 * kH * kForce;
    o.minimizer.dual_infeasibility_tolerance = 1e-10 * kForce;
    o.newton.gradient_tolerance = 1e-10 * kForce;
    return o;
  }

  // Lowest proxy vertex of the top strip (m). The bottom strip's proxy lies exactly in z = 0
  // (the limit surface of a flat control net), so this is the layers' distance measured on
  // the proxy.
  double top_lowest(const Eigen::VectorXd& x) const {
    const Eigen::MatrixX3d y = proxy_positions(proxy, x);
    double lowest = std::numeric_limits<double>::infinity();
    for (Eigen::Index p = 0; p < y.rows(); ++p)
      if (proxy.vertex_element(p) < top_elements()) lowest = std::min(lowest, y(p, 2));
    return lowest;
  }
  // Elements are numbered top strip first (its faces come first in the mesh).
  int top_elements() const { return 2 * top_mesh.cells_x * top_mesh.cells_y; }
};

// Smallest exact distance (mollifier off) over all pairs near_contact_pairs finds within
// `distance`, edge-edge pairs included; +infinity if there is none.
double closest_pair(const ContactProxy& proxy, const Eigen::VectorXd& x, double distance,
                    double exclusion_radius) {
  const ContactCandidates near = near_contact_pairs(proxy, x, distance, exclusion_radius);
  if (near.empty()) return std::numeric_limits<double>::infinity();
  ContactGapOptions plain;
  plain.mollify_edge_edge = false;
  ContactGapConstraints c(proxy, near, 0.0, x.size(), plain);
  Eigen::VectorXd d;
  c.evaluate(x, d, nullptr);
  return d.minCoeff();
}

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
  const ContactSolveResult r = solve_contact_equilibrium(s.model, s.proxy, x0, s.fixed(), o);
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
  s.model.evaluate(r.x, &g, nullptr);
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
  const ContactSolveResult r = solve_contact_equilibrium(s.model, s.proxy, x0, s.fixed(), o);
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
  const ContactSolveResult r = solve_contact_equilibrium(s.model, s.proxy, x0, s.fixed(), o);
  const NewtonResult plain = NewtonSolver(o.newton).minimize(s.model, x0, s.fixed());
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
  const ContactSolveResult r = solve_contact_equilibrium(s.model, s.proxy, x0, s.fixed(), o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.rounds, 2);
  EXPECT_TRUE(r.used_contact);
  EXPECT_GT(r.forces.size(), 0);
  EXPECT_NEAR(s.top_lowest(r.x), h, o.violation_tolerance);
  expect_no_pair_too_close(s, o, r);

  o.max_rounds = 1;
  const ContactSolveResult once = solve_contact_equilibrium(s.model, s.proxy, x0, s.fixed(), o);
  EXPECT_FALSE(once.converged);
  EXPECT_EQ(once.rounds, 1);
  EXPECT_FALSE(once.used_contact);
  EXPECT_LT(once.min_distance, h - o.violation_tolerance);
  EXPECT_NE(once.message.find("after 1 rounds"), std::string::npos) << once.message;
  EXPECT_TRUE(once.x.allFinite());
  // x is the state of the last solve: the Newton pass, which ends with the layers 0.83 h
  // apart (measured; 17 iterations in all for the two rounds above).
  EXPECT_TRUE(once.x == NewtonSolver(o.newton).minimize(s.model, x0, s.fixed()).x);
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
  double energy = 0.0;
  std::string message;
  relax_with_contact(s.model, s.proxy, unbounded, held, o, newton, &energy, &message);
  EXPECT_LT(over_bottom(unbounded), -h) << "the unbounded relaxation should pass through";

  newton.max_step_inf_norm = 0.25 * h;
  Eigen::VectorXd bounded = x0;
  ASSERT_TRUE(relax_with_contact(s.model, s.proxy, bounded, held, o, newton, &energy, &message))
      << message;
  EXPECT_GT(over_bottom(bounded), h - 0.01 * h);
  EXPECT_GE(closest_pair(s.proxy, bounded, 2.0 * h, o.exclusion_radius), h - 0.01 * h);
}

// Warm start at a solution: the same pairs and their forces; Ipopt stays put.
TEST(ContactEquilibrium, WarmRestartAtTheSolutionStaysThere) {
  TwoStrips s;
  const double h = TwoStrips::kH;
  const ContactSolveOptions o = s.options();
  const Eigen::VectorXd x0 = s.propped(1.1 * h, 0.25 * h);
  const ContactSolveResult first = solve_contact_equilibrium(s.model, s.proxy, x0, s.fixed(), o);
  ASSERT_TRUE(first.converged) << first.message;
  const ContactSolveResult again =
      solve_contact_equilibrium(s.model, s.proxy, first.x, s.fixed(), o, &first);
  ASSERT_TRUE(again.converged) << again.message;
  // Measured: 12 iterations cold, 1 warm, moving x by 1.2e-11 h and the force sum by 1e-12.
  EXPECT_LE(again.iterations, 5);
  EXPECT_LE((again.x - first.x).lpNorm<Eigen::Infinity>(), 1e-6 * h);
  EXPECT_NEAR(again.forces.sum(), first.forces.sum(), 1e-6 * first.forces.sum());
  expect_no_pair_too_close(s, o, again);
}

// ---------------------------------------------------------------------------------------
// (4) near_contact_pairs returns exactly the pairs whose exact distance is below the query
// distance: compared with every pair of the brute-force broad phase, measured one by one.

/// Reference answer: brute-force candidates at query distance `distance`, kept if their exact
/// (unmollified) distance is below it; with `nearest`, per vertex only the nearest triangle
/// (the first in index order among equals); edge-edge pairs only if `edges`.
ContactCandidates expected_near_pairs(const ContactProxy& proxy, const Eigen::VectorXd& x,
                                      double distance, double exclusion_radius, bool edges,
                                      bool nearest, Eigen::Index* candidates = nullptr) {
  ContactCandidateOptions co;
  co.query_distance = distance;
  co.exclusion_radius = exclusion_radius;
  const ContactCandidates all =
      find_contact_candidates_brute_force(proxy, proxy_positions(proxy, x), co);
  if (candidates != nullptr) *candidates = all.size();
  ContactCandidates out;
  out.vertex_triangle.resize(0, 2);
  out.edge_edge.resize(0, 2);
  if (all.empty()) return out;
  ContactGapOptions plain;
  plain.mollify_edge_edge = false;
  ContactGapConstraints c(proxy, all, 0.0, x.size(), plain);
  std::vector<Eigen::Index> vt, ee;
  const Eigen::Index nvt = all.vertex_triangle.rows();
  for (Eigen::Index k = 0; k < c.count(); ++k) {
    const double d = c.pair_geometry(x, k).distance;
    if (!(d < distance)) continue;
    if (k >= nvt) {
      if (edges) ee.push_back(k - nvt);
      continue;
    }
    if (nearest) {
      // Is there a pair of the same vertex that is nearer, or as near with a lower triangle?
      bool beaten = false;
      for (Eigen::Index m = 0; m < nvt && !beaten; ++m) {
        if (m == k || all.vertex_triangle(m, 0) != all.vertex_triangle(k, 0)) continue;
        const double dm = c.pair_geometry(x, m).distance;
        beaten = dm < distance &&
                 (dm < d || (dm == d && all.vertex_triangle(m, 1) < all.vertex_triangle(k, 1)));
      }
      if (beaten) continue;
    }
    vt.push_back(k);
  }
  out.vertex_triangle.resize(static_cast<Eigen::Index>(vt.size()), 2);
  out.edge_edge.resize(static_cast<Eigen::Index>(ee.size()), 2);
  for (std::size_t i = 0; i < vt.size(); ++i)
    out.vertex_triangle.row(static_cast<Eigen::Index>(i)) = all.vertex_triangle.row(vt[i]);
  for (std::size_t i = 0; i < ee.size(); ++i)
    out.edge_edge.row(static_cast<Eigen::Index>(i)) = all.edge_edge.row(ee[i]);
  return out;
}

void expect_same_pairs(const ContactCandidates& got, const ContactCandidates& want,
                       const std::string& what) {
  ASSERT_EQ(got.vertex_triangle.rows(), want.vertex_triangle.rows()) << what;
  ASSERT_EQ(got.edge_edge.rows(), want.edge_edge.rows()) << what;
  EXPECT_TRUE(got.vertex_triangle == want.vertex_triangle) << what;
  EXPECT_TRUE(got.edge_edge == want.edge_edge) << what;
}

TEST(NearContactPairs, ExactlyThePairsCloserThanTheDistance) {
  DiscMeshOptions mesh;
  mesh.rings = 5;
  ShellModel model(make_disc_mesh(mesh), ShellModelSettings{});
  const ContactProxy proxy = make_contact_proxy(model, 2);
  // Layers 0.08 m apart, wobble 0.01 m: distances between the layers spread over about
  // 0.06 .. 0.1 m, so a query at 0.09 m cuts through the middle of them.
  const Eigen::VectorXd x = folded_sheet(model, 0.0, 0.04, 0.01);
  const double r_ex = 0.2;
  for (const double distance : {0.09, 0.12}) {
    Eigen::Index candidates = 0;
    const ContactCandidates want =
        expected_near_pairs(proxy, x, distance, r_ex, true, false, &candidates);
    const ContactCandidates got = near_contact_pairs(proxy, x, distance, r_ex);
    // Measured: at 0.09 m 1559 vertex-triangle + 4160 edge-edge pairs of 12664 candidates,
    // at 0.12 m 2995 + 7739 of 21475.
    // The filter is exercised: some candidates of the boxes are dropped, both kinds kept.
    EXPECT_GT(want.vertex_triangle.rows(), 0);
    EXPECT_GT(want.edge_edge.rows(), 0);
    EXPECT_LT(want.size(), candidates);
    expect_same_pairs(got, want, "all pairs at " + std::to_string(distance));

    NearPairSelection nearest;
    nearest.edge_edge_pairs = false;
    nearest.nearest_triangle_only = true;
    const ContactCandidates want_nearest =
        expected_near_pairs(proxy, x, distance, r_ex, false, true);
    const ContactCandidates got_nearest = near_contact_pairs(proxy, x, distance, r_ex, nearest);
    EXPECT_LT(want_nearest.vertex_triangle.rows(), want.vertex_triangle.rows());
    expect_same_pairs(got_nearest, want_nearest,
                      "nearest triangles at " + std::to_string(distance));
  }
  // Below the smallest distance between the layers: nothing.
  EXPECT_TRUE(near_contact_pairs(proxy, x, 0.03, r_ex).empty());
}

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
// (5) contact_zones on hand-made pairs with known answers. Identity proxy: the unknowns are
// the points themselves.
ContactProxy identity_proxy(const Eigen::MatrixX3d& points, const Eigen::MatrixX3i& triangles,
                            const Eigen::MatrixX2i& edges = Eigen::MatrixX2i(0, 2)) {
  ContactProxy proxy;
  const Eigen::Index n = 3 * points.rows();
  proxy.map.resize(n, n);
  proxy.map.setIdentity();
  proxy.triangles = triangles;
  proxy.edges = edges;
  proxy.reference_positions = points;
  return proxy;
}

Eigen::VectorXd flatten(const Eigen::MatrixX3d& points) {
  Eigen::VectorXd x(3 * points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) x.segment<3>(3 * i) = points.row(i).transpose();
  return x;
}

// Zone A: three points over and under a large triangle in z = 0 (normals +z, -z, +z), their
// contact points 0.41 and 0.40 m apart in a chain (0.8 m end to end), linked at 0.5 m.
// Zone B, 10 m away: two points over two triangles whose planes have normals n1 (tilted by
// gamma from z about y) and n2 (n1 turned by 0.2 rad about the first triangle's tangent t1).
// Two more pairs far from both carry forces below the active fraction (one tiny, one
// slightly negative, as Ipopt leaves inactive multipliers).
struct ZoneScene {
  static constexpr double kGamma = 1.1;
  Eigen::Vector3d n1, n2;
  Eigen::MatrixX3d points;
  Eigen::MatrixX3i triangles;
  ContactCandidates pairs;
  Eigen::VectorXd forces;

  ZoneScene() {
    n1 = Eigen::Vector3d(std::sin(kGamma), 0.0, std::cos(kGamma));
    const Eigen::Vector3d t1(std::cos(kGamma), 0.0, -std::sin(kGamma)), t2(0.0, 1.0, 0.0);
    const Eigen::Vector3d t2b = std::cos(0.2) * t2 + std::sin(0.2) * n1;
    n2 = t1.cross(t2b);
    const Eigen::Vector3d c(10.0, 0.0, 0.0), c2 = c + 0.2 * t2;
    // 0-2: triangle 0 in z = 0; 3-5: the points of zone A.
    std::vector<Eigen::Vector3d> p = {{0, 0, 0},       {2, 0, 0},        {0, 2, 0},
                                      {0.1, 0.1, 0.1}, {0.5, 0.1, -0.1}, {0.9, 0.1, 0.1}};
    // 6-8: triangle 1 (normal n1); 9-11: triangle 2 (normal n2); 12, 13: points over them.
    p.insert(p.end(), {Eigen::Vector3d(c), Eigen::Vector3d(c + t1), Eigen::Vector3d(c + t2),
                       Eigen::Vector3d(c2), Eigen::Vector3d(c2 + t1), Eigen::Vector3d(c2 + t2b),
                       Eigen::Vector3d(c + 0.2 * t1 + 0.3 * t2 + 0.1 * n1),
                       Eigen::Vector3d(c2 + 0.2 * t1 + 0.05 * t2b + 0.05 * n2)});
    // 14-16: triangle 3, far away; 17, 18: the points of the two inactive pairs.
    p.insert(p.end(), {{-10, 0, 0}, {-9, 0, 0}, {-10, 1, 0}, {-9.8, 0.1, 0.2}, {-9.8, 0.2, -0.3}});
    points.resize(static_cast<Eigen::Index>(p.size()), 3);
    for (std::size_t i = 0; i < p.size(); ++i)
      points.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
    triangles.resize(4, 3);
    triangles << 0, 1, 2, 6, 7, 8, 9, 10, 11, 14, 15, 16;
    pairs.vertex_triangle.resize(7, 2);
    pairs.vertex_triangle << 3, 0, 4, 0, 5, 0, 12, 1, 13, 2, 17, 3, 18, 3;
    pairs.edge_edge.resize(0, 2);
    forces.resize(7);
    forces << 2.0, 1.0, 0.5, 0.7, 0.25, 1e-5, -1e-9;
  }
};

TEST(ContactZones, TwoZonesWithKnownForcesNormalsAndAngle) {
  const ZoneScene z;
  const ContactProxy proxy = identity_proxy(z.points, z.triangles);
  const Eigen::VectorXd x = flatten(z.points);
  ContactGapConstraints gaps(proxy, z.pairs, 0.05, x.size());
  const std::vector<ContactZone> zones = contact_zones(gaps, x, z.forces, 0.5);
  ASSERT_EQ(zones.size(), 2u);
  // Largest total force first; pair lists are constraint indices.
  EXPECT_EQ(zones[0].pairs, (std::vector<Eigen::Index>{0, 1, 2}));
  EXPECT_EQ(zones[1].pairs, (std::vector<Eigen::Index>{3, 4}));
  // Sums of the same three or two doubles: exact up to one rounding each.
  EXPECT_NEAR(zones[0].force, 3.5, 1e-15);
  EXPECT_NEAR(zones[1].force, 0.95, 1e-15);
  // Zone A: the -z normal of the point under the plane is flipped to the strongest pair's +z.
  EXPECT_LE((zones[0].normal - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  // Centroid: force-weighted midpoints of the closest points (vertex and its foot).
  const Eigen::Vector3d centroid_a =
      (2.0 * Eigen::Vector3d(0.1, 0.1, 0.05) + 1.0 * Eigen::Vector3d(0.5, 0.1, -0.05) +
       0.5 * Eigen::Vector3d(0.9, 0.1, 0.05)) /
      3.5;
  EXPECT_LE((zones[0].centroid - centroid_a).norm(), 1e-12);
  // Zone B: force-weighted mean of n1 and n2. The pair normals come from closest points of
  // O(10 m) coordinates, so they carry rounding of about 1e-15 / 0.05 m: 1e-12 is ample.
  const Eigen::Vector3d normal_b = (0.7 * z.n1 + 0.25 * z.n2).normalized();
  EXPECT_LE((zones[1].normal - normal_b).norm(), 1e-12) << zones[1].normal.transpose();
  EXPECT_NEAR(contact_plane_angle(zones), std::acos(normal_b.z()), 1e-12);

  // A link distance below the chain's links splits zone A into its three pairs.
  const std::vector<ContactZone> split = contact_zones(gaps, x, z.forces, 0.3);
  ASSERT_EQ(split.size(), 4u);
  EXPECT_EQ(split[0].pairs, (std::vector<Eigen::Index>{0}));
  EXPECT_EQ(split[1].pairs, (std::vector<Eigen::Index>{1}));
  EXPECT_EQ(split[2].pairs, (std::vector<Eigen::Index>{3, 4}));
  EXPECT_EQ(split[3].pairs, (std::vector<Eigen::Index>{2}));
  // Pair 1's own normal is -z (no stronger pair in its zone to align with).
  EXPECT_LE((split[1].normal - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  // active_fraction 0 admits the tiny positive force (a third zone), never the negative one.
  const std::vector<ContactZone> all = contact_zones(gaps, x, z.forces, 0.5, 0.0);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[2].pairs, (std::vector<Eigen::Index>{5}));
  // No force at all: no zone.
  EXPECT_TRUE(contact_zones(gaps, x, Eigen::VectorXd::Zero(7), 0.5).empty());
  // The normal test: zone B's two normals differ by exactly 0.2 rad, zone A's by 0 (+z, -z).
  EXPECT_EQ(contact_zones(gaps, x, z.forces, 0.5, 1e-3, 0.21).size(), 2u);
  const std::vector<ContactZone> by_normal = contact_zones(gaps, x, z.forces, 0.5, 1e-3, 0.19);
  ASSERT_EQ(by_normal.size(), 3u);
  EXPECT_EQ(by_normal[0].pairs, (std::vector<Eigen::Index>{0, 1, 2}));
  EXPECT_EQ(by_normal[1].pairs, (std::vector<Eigen::Index>{3}));
  EXPECT_EQ(by_normal[2].pairs, (std::vector<Eigen::Index>{4}));
  EXPECT_NEAR(contact_plane_angle({by_normal[1], by_normal[2]}), 0.2, 1e-12);
  EXPECT_THROW(contact_zones(gaps, x, z.forces, 0.5, 1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(contact_zones(gaps, x, z.forces, 0.5, 1e-3, 2.0), std::invalid_argument);
}

// A mollified edge-edge pair pushes with multiplier * mollifier (ContactPairGeometry), and
// that is the force a zone sums and weights its normal with. Edge P along x at height 0.3
// over edge Q at angle alpha = 0.02 in z = 0 (both of length 2): r = sin^2(alpha) / 1e-3 =
// 0.4, m = (2 - r) r = 0.64 (tests/contact). In the same zone a point over a triangle whose
// plane is tilted by beta = 0.4 about y.
TEST(ContactZones, MollifiedEdgePairCountsWithItsForceNotItsMultiplier) {
  const double alpha = 0.02, beta = 0.4;
  const Eigen::Vector3d nt(std::sin(beta), 0.0, std::cos(beta)),
      t1(std::cos(beta), 0.0, -std::sin(beta)), t2(0.0, 1.0, 0.0), c0(0.0, 0.5, 0.0);
  Eigen::MatrixX3d points(8, 3);
  points.row(0) << -1, 0, 0.3;
  points.row(1) << 1, 0, 0.3;
  points.row(2) << -std::cos(alpha), -std::sin(alpha), 0;
  points.row(3) << std::cos(alpha), std::sin(alpha), 0;
  points.row(4) = c0.transpose();
  points.row(5) = (c0 + t1).transpose();
  points.row(6) = (c0 + t2).transpose();
  points.row(7) = (c0 + 0.2 * t1 + 0.3 * t2 + 0.3 * nt).transpose();
  Eigen::MatrixX3i triangles(1, 3);
  triangles << 4, 5, 6;
  Eigen::MatrixX2i edges(2, 2);
  edges << 0, 1, 2, 3;
  const ContactProxy proxy = identity_proxy(points, triangles, edges);
  ContactCandidates pairs;
  pairs.vertex_triangle.resize(1, 2);
  pairs.vertex_triangle << 7, 0;
  pairs.edge_edge.resize(1, 2);
  pairs.edge_edge << 0, 1;
  const Eigen::VectorXd x = flatten(points);
  ContactGapConstraints gaps(proxy, pairs, 0.3, x.size());
  const double r = std::pow(std::sin(alpha), 2) / 1e-3;
  const double m = (2.0 - r) * r;
  ASSERT_NEAR(gaps.pair_geometry(x, 1).mollifier, m, 1e-14);
  const Eigen::Vector2d multipliers(0.5, 1.0);  // vertex-triangle, edge-edge
  const std::vector<ContactZone> zones = contact_zones(gaps, x, multipliers, 1.0);
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_NEAR(zones[0].force, 0.5 + m, 1e-14);
  const Eigen::Vector3d normal = (m * Eigen::Vector3d(0, 0, 1) + 0.5 * nt).normalized();
  EXPECT_LE((zones[0].normal - normal).norm(), 1e-12) << zones[0].normal.transpose();
  // The active test compares forces too: at active_fraction 0.7 the point pair (0.5) stays
  // active against the largest force 0.64 (threshold 0.448), though it would not against the
  // largest multiplier 1.0 (threshold 0.7).
  const std::vector<ContactZone> strong = contact_zones(gaps, x, multipliers, 1.0, 0.7);
  ASSERT_EQ(strong.size(), 1u);
  EXPECT_EQ(strong[0].pairs, (std::vector<Eigen::Index>{0, 1}));
}

TEST(ContactZones, PlaneAngleOfHandMadeZones) {
  ContactZone a, b;
  a.normal = Eigen::Vector3d(0, 0, 1);
  EXPECT_TRUE(std::isnan(contact_plane_angle({})));
  EXPECT_TRUE(std::isnan(contact_plane_angle({a})));
  for (const double gamma : {0.0, 0.3, kPi / 2, 2.0, kPi}) {
    b.normal = Eigen::Vector3d(std::sin(gamma), 0.0, std::cos(gamma));
    // Planes, not normals: gamma and pi - gamma are the same pair of planes.
    const double expected = gamma <= kPi / 2 ? gamma : kPi - gamma;
    // acos loses accuracy only near 0 (dot = 1): 1e-7 there, 1e-12 elsewhere.
    EXPECT_NEAR(contact_plane_angle({a, b}), expected,
                expected < 0.1 || expected > kPi - 0.1 ? 1e-7 : 1e-12)
        << gamma;
  }
}

TEST(ContactZones, RejectsBadInput) {
  const ZoneScene z;
  const ContactProxy proxy = identity_proxy(z.points, z.triangles);
  const Eigen::VectorXd x = flatten(z.points);
  ContactGapConstraints gaps(proxy, z.pairs, 0.05, x.size());
  auto message_of = [](auto&& call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message_of([&] {
              contact_zones(gaps, x, Eigen::VectorXd::Ones(6), 0.5);
            }).find("forces has 6"),
            std::string::npos);
  for (const double bad : {0.0, -1.0, nan})
    EXPECT_NE(message_of([&] { contact_zones(gaps, x, z.forces, bad); }).find("link_distance"),
              std::string::npos)
        << bad;
  for (const double bad : {-0.1, nan})
    EXPECT_NE(
        message_of([&] { contact_zones(gaps, x, z.forces, 0.5, bad); }).find("active_fraction"),
        std::string::npos)
        << bad;
}

// ---------------------------------------------------------------------------------------
// (6) Bad options are rejected with a message naming the option.
TEST(ContactEquilibrium, RejectsBadOptions) {
  TwoStrips s;
  const Eigen::VectorXd x0 = s.state(4.0 * TwoStrips::kH, 0.0);
  auto message_of = [&](const ContactSolveOptions& o, const Eigen::VectorXd& x) {
    try {
      solve_contact_equilibrium(s.model, s.proxy, x, s.fixed(), o);
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
  EXPECT_NE(message_of(good, Eigen::VectorXd::Zero(x0.size() - 1)).find("x0"), std::string::npos);
}

}  // namespace
}  // namespace growshell
