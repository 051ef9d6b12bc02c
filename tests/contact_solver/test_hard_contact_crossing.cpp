// hard_contact_energy_crossing (branch samples re-solved under Ipopt's hard constraints):
//  - the slope it reports, partial E / partial phi at the re-solved state, is the derivative of
//    the re-solved energy along the constrained branch (the envelope theorem it rests on),
//    checked against re-solves at neighbouring phi_e;
//  - every re-solved sample keeps every pair of the sheet at distance >= h - tol;
//  - a sample whose solve fails is reported, named and left out of the crossing;
//  - bad input is rejected naming the branch and sample.
// Scene: the contact tests' coarse disc (tests/support/grown_disc.hpp), followed with the
// penalty from phi_e = 6.0 into contact.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/hard_contact_crossing.hpp"
#include "support/grown_disc.hpp"

namespace growshell {
namespace {

using test_support::disc;
using test_support::GrownDisc;

HardContactCrossingOptions hard_options(const GrownDisc& d) {
  HardContactCrossingOptions o;
  o.solve = d.ipopt_options();
  o.solve.edge_edge_pairs = true;
  o.solve.violation_tolerance = 1e-3 * GrownDisc::kH;
  o.solve.minimizer.tolerance = 1e-9;
  o.solve.minimizer.constraint_violation_tolerance = 1e-9 * GrownDisc::kH;
  o.solve.minimizer.complementarity_tolerance =
      1e-10 * d.model.natural_force_scale() * GrownDisc::kH;
  o.solve.newton.gradient_tolerance = 1e-9 * d.model.natural_force_scale();
  o.zone_link_distance = 0.1;
  o.penalty_stiffness = d.options().stiffness;  // warm start from the penalty's forces
  return o;
}

// A stable sample of the symmetric branch in contact (penalty), shared by the tests.
const BranchSample& touching_sample() {
  static const BranchSample sample = [] {
    GrownDisc& d = disc();
    // First contact is at 6.137 and the stability loss at 6.408 on this disc.
    const double phi0 = 6.0;
    const Eigen::VectorXd x = d.grown(phi0);
    ContactBranchOptions o = d.options();
    o.arclength.parameter_max = 6.2;
    o.arclength.max_steps = 12;
    BranchSample last;
    trace_contact_branch(d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned,
                         o, [&](const ContactBranchSample& s) {
                           if (s.active_pairs > 0 && s.sample.negative_eigenvalues == 0)
                             last = s.sample;
                         });
    return last;
  }();
  return sample;
}

BranchSample at_parameter(BranchSample s, double phi) {
  s.parameter = phi;
  return s;
}

TEST(HardContactCrossing, SlopeIsTheDerivativeOfTheResolvedEnergyAlongTheConstrainedBranch) {
  GrownDisc& d = disc();
  const BranchSample& s = touching_sample();
  ASSERT_GT(s.x.size(), 0) << "the penalty trace found no stable sample in contact";
  const double phi = s.parameter;
  const double delta = 2e-3;
  // The same penalty state re-solved at phi and at phi + delta (a feasible start for both).
  const std::vector<BranchSample> a = {s, at_parameter(s, phi + delta)};
  const HardContactCrossingOptions o = hard_options(d);
  const HardContactCrossing r = hard_contact_energy_crossing(d.model, d.proxy, a, {}, d.pinned, o);
  ASSERT_EQ(r.a.size(), 2u);
  for (const HardContactSample& h : r.a) {
    std::printf(
        "phi_e = %.6f: %d rounds, %d iterations, %.1f s, max |x - x_penalty| %.3g m, "
        "energy %.10g (penalty state %.10g)\n",
        h.parameter, h.rounds, h.iterations, h.seconds, h.max_state_difference, h.energy,
        h.start_energy);
    ASSERT_TRUE(h.converged) << "at phi_e = " << h.parameter << ": " << h.message;
    EXPECT_GT(h.active_pairs, 0) << "at phi_e = " << h.parameter;
    // Hard constraints: no pair of the sheet (edge-edge pairs included, nearest triangle or
    // not) closer than h less the solve's violation tolerance.
    const ContactCandidates close =
        near_contact_pairs(d.proxy, h.x, GrownDisc::kH - o.solve.violation_tolerance,
                           o.solve.exclusion_radius, NearPairSelection{true, false});
    EXPECT_TRUE(close.empty()) << close.vertex_triangle.rows() << " + " << close.edge_edge.rows()
                               << " pairs closer than h at phi_e = " << h.parameter;
    EXPECT_GE(h.min_distance, GrownDisc::kH - o.solve.violation_tolerance);
  }
  // Envelope theorem: dE*/dphi = partial E / partial phi at x*. The difference quotient of the
  // two re-solved energies equals the mean of their slopes up to delta^2 E''' / 12 ~ 1e-7 E
  // (trapezoidal rule); the energies themselves are resolved far below that (second order in
  // the state's tolerance). Measured: 6e-7 relative (4e-8 from a cold start).
  const double quotient = (r.a[1].energy - r.a[0].energy) / delta;
  const double slope = 0.5 * (r.a[0].energy_slope + r.a[1].energy_slope);
  std::printf(
      "phi_e = %.6f: mean slope %.10g, difference quotient of the re-solves %.10g "
      "(relative %.2e)\n",
      phi, slope, quotient, std::abs(quotient - slope) / std::abs(slope));
  EXPECT_NEAR(quotient, slope, 1e-5 * std::abs(slope));
  // The measure that tells a sample that stayed on its branch from one that relaxed onto
  // another: small here; a sample whose energy is off by a tenth of the
  // energy change (as a jump to another branch would be, and far more) shows as 0.1.
  EXPECT_LT(branch_continuity_mismatch(r.a[0], r.a[1]), 1e-5);
  HardContactSample jumped = r.a[1];
  jumped.energy += 0.1 * std::abs(r.a[1].energy_slope) * delta;
  EXPECT_NEAR(branch_continuity_mismatch(r.a[0], jumped), 0.1, 1e-3);
  EXPECT_THROW(branch_continuity_mismatch(r.a[0], r.a[0]), std::invalid_argument);
  EXPECT_TRUE(r.crossings.empty());
  EXPECT_FALSE(r.message.empty()) << "branch b is empty: no crossing can be located";
}

TEST(HardContactCrossing, AFailedSolveIsNamedAndLeftOutOfTheCrossing) {
  // The flat disc re-solved at phi_e = 0.2 and 0.3 (grown in plane, far from contact: the
  // no-contact fast path) with one Newton iteration allowed: neither solve can converge.
  GrownDisc& d = disc();
  BranchSample s;
  s.x = d.model.reference_positions();
  HardContactCrossingOptions o = hard_options(d);
  o.solve.newton.max_iterations = 1;
  o.solve.minimizer.max_iterations = 1;
  o.solve.max_rounds = 1;
  const std::vector<BranchSample> a = {at_parameter(s, 0.2), at_parameter(s, 0.3)};
  const HardContactCrossing r = hard_contact_energy_crossing(d.model, d.proxy, a, a, d.pinned, o);
  ASSERT_EQ(r.a.size(), 2u);
  ASSERT_EQ(r.b.size(), 2u);
  EXPECT_FALSE(r.a[0].converged);
  EXPECT_FALSE(r.b[1].converged);
  EXPECT_TRUE(std::isfinite(r.a[0].energy)) << "the last iterate is kept and evaluated";
  EXPECT_TRUE(r.crossings.empty());
  EXPECT_NE(r.message.find("branch a sample 0"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("branch b sample 1"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("fewer than two converged samples"), std::string::npos) << r.message;
}

// Samples of E = cos(phi) with their exact slopes lie on one smooth branch; a sample replaced by
// one of another branch (E shifted by 1e-2, a jump of the size seen when a skewed state slides
// onto the symmetric one) ends the stretch on its side, whichever side of the anchor it is.
TEST(HardContactCrossing, ContinuousStretchEndsWhereASampleLeftTheBranch) {
  std::vector<HardContactSample> samples;
  for (int i = 0; i < 8; ++i) {
    HardContactSample s;
    s.parameter = 5.9 + 0.05 * i;
    s.energy = std::cos(s.parameter);
    s.energy_slope = -std::sin(s.parameter);
    s.converged = true;
    samples.push_back(s);
  }
  // On the branch the trapezoidal miss is dphi^2 |E'''| / 12 / |E'| ~ 2e-4 here.
  for (std::size_t i = 0; i + 1 < samples.size(); ++i)
    EXPECT_LT(branch_continuity_mismatch(samples[i], samples[i + 1]), 1e-3);
  EXPECT_EQ(continuous_stretch(samples, 3, 0.05), std::make_pair(std::size_t{0}, std::size_t{7}));
  std::vector<HardContactSample> jumped = samples;
  jumped[6].energy += 1e-2;
  jumped[1].energy -= 1e-2;
  EXPECT_GT(branch_continuity_mismatch(jumped[5], jumped[6]), 0.05);
  EXPECT_EQ(continuous_stretch(jumped, 3, 0.05), std::make_pair(std::size_t{2}, std::size_t{5}));
  EXPECT_EQ(continuous_stretch(jumped, 6, 0.05), std::make_pair(std::size_t{6}, std::size_t{6}));
  EXPECT_THROW(continuous_stretch(jumped, 8, 0.05), std::invalid_argument);
  EXPECT_THROW(continuous_stretch(jumped, 3, 0.0), std::invalid_argument);
}

TEST(HardContactCrossing, BadInputIsRejectedByName) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& X = d.model.reference_positions();
  BranchSample good;
  good.parameter = 1.0;
  good.x = X;
  BranchSample wrong = good;
  wrong.x = X.head(X.size() - 3);
  const HardContactCrossingOptions o = hard_options(d);
  const auto message = [&](const std::vector<BranchSample>& a, const std::vector<BranchSample>& b,
                           const std::vector<Eigen::Index>& pins,
                           const HardContactCrossingOptions& options) -> std::string {
    try {
      hard_contact_energy_crossing(d.model, d.proxy, a, b, pins, options);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message({good}, {good, wrong}, d.pinned, o).find("branch b sample 1"),
            std::string::npos);
  BranchSample nan = good;
  nan.x(4) = std::nan("");
  EXPECT_NE(message({nan}, {}, d.pinned, o).find("branch a sample 0"), std::string::npos);
  std::vector<Eigen::Index> five(d.pinned.begin(), d.pinned.end() - 1);
  EXPECT_NE(message({good}, {}, five, o).find("six rigid-motion pins"), std::string::npos);
  HardContactCrossingOptions bad = o;
  bad.slope_step = 0.0;
  EXPECT_NE(message({good}, {}, d.pinned, bad).find("slope_step"), std::string::npos);
  bad = o;
  bad.max_pin_condition = 1.0;
  EXPECT_NE(message({good}, {}, d.pinned, bad).find("max_pin_condition"), std::string::npos);
  bad = o;
  bad.max_branch_mismatch = 0.0;
  EXPECT_NE(message({good}, {}, d.pinned, bad).find("max_branch_mismatch"), std::string::npos);
  bad = o;
  bad.zone_link_distance = -1.0;
  EXPECT_NE(message({good}, {}, d.pinned, bad).find("zone_link_distance"), std::string::npos);
}

}  // namespace
}  // namespace growshell
