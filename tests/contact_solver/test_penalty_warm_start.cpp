// penalty_warm_start: a penalty equilibrium's pair forces as the multipliers of the hard
// constraints, on the pressed-strip scene (tests/support/pressed_strips.hpp):
//  - each force is stiffness x (offset - d_k)_+ of its pair, zero for pairs not penetrating;
//  - they carry the load, within what the penalty's sinking changes of it;
//  - the hard solve from the penalty state, seeded with them, reaches the cold solve's
//    equilibrium, in fewer iterations than from the same state without the seed;
//  - bad arguments are named.
#include "solvers/contact/penalty_warm_start.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "libshell/contact/contact_gap_constraints.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "support/pressed_strips.hpp"

namespace growshell {
namespace {

using test_support::TwoStrips;

// The penalty of the traces: vertex-triangle pairs, nearest triangle only. Its stiffness
// k = 100 N/m lets the two pairs that carry the load (~9e-3 N) sink by about F / (2 k) =
// 4.5e-5 m = 0.002 h.
ContactBranchOptions penalty_options() {
  ContactBranchOptions o;
  o.contact_distance = TwoStrips::kH;
  o.exclusion_radius = 0.5 * TwoStrips::kPi * TwoStrips::kH;
  o.candidate_margin = 0.25 * TwoStrips::kH;
  o.stiffness = 100.0;
  o.selection = NearPairSelection{false, true};
  return o;
}

struct PenaltyState {
  Eigen::VectorXd x;
  ContactCandidates pairs;
};

PenaltyState penalty_equilibrium(TwoStrips& s, const ContactBranchOptions& o) {
  PenaltyState p;
  p.x = s.propped(1.1 * TwoStrips::kH, 0.25 * TwoStrips::kH);
  NewtonOptions newton;
  newton.gradient_tolerance = 1e-10 * TwoStrips::kForce;
  newton.max_iterations = 200;
  const ContactRelaxation relaxed = relax_with_contact(s.model, 0.0, s.proxy, p.x, s.fixed(), o, newton);
  EXPECT_TRUE(relaxed.relaxed) << relaxed.message;
  p.pairs = near_penalty_pairs(s.proxy, p.x, o);
  return p;
}

TEST(PenaltyWarmStart, ForcesAreTheStiffnessTimesThePenetration) {
  TwoStrips s;
  const ContactBranchOptions o = penalty_options();
  const PenaltyState p = penalty_equilibrium(s, o);
  const ContactSolveResult warm =
      penalty_warm_start(s.proxy, p.pairs, p.x, o.contact_distance, o.stiffness);
  ASSERT_EQ(warm.forces.size(), p.pairs.size());
  EXPECT_EQ(warm.pairs.vertex_triangle, p.pairs.vertex_triangle);
  ContactGapConstraints gaps(s.proxy, p.pairs, o.contact_distance, s.model.dimension());
  int penetrating = 0;
  for (Eigen::Index k = 0; k < warm.forces.size(); ++k) {
    const double gap = gaps.pair_geometry(p.x, k).gap;
    const double expected = o.stiffness * std::max(0.0, -gap);
    EXPECT_NEAR(warm.forces(k), expected, 1e-12 * std::max(1.0, expected)) << "pair " << k;
    if (gap < 0.0) ++penetrating;
  }
  // The load goes through the two ends of the middle line (as under the hard constraints:
  // test_contact_equilibrium.cpp), each end as two pairs: the top strip's vertex over a bottom
  // triangle, and the bottom strip's vertex under a top triangle. Measured: sunk by 0.0015 h
  // and 0.0007 h, forces 3.0e-3 and 1.3e-3 N.
  EXPECT_EQ(penetrating, 4);
  EXPECT_GT(warm.forces.maxCoeff(), TwoStrips::kForce);
  EXPECT_LT(warm.forces.maxCoeff() / o.stiffness, 0.01 * TwoStrips::kH);
}

TEST(PenaltyWarmStart, SeedsTheHardSolveWithTheContactForces) {
  TwoStrips s;
  const ContactBranchOptions o = penalty_options();
  const ContactSolveOptions hard = s.options();
  const ContactSolveResult cold = solve_contact_equilibrium(
      s.model, 0.0, s.proxy, s.propped(1.1 * TwoStrips::kH, 0.25 * TwoStrips::kH), s.fixed(), hard);
  ASSERT_TRUE(cold.converged) << cold.message;
  const double load = cold.forces.sum();

  const PenaltyState p = penalty_equilibrium(s, o);
  const ContactSolveResult warm =
      penalty_warm_start(s.proxy, p.pairs, p.x, o.contact_distance, o.stiffness);
  // Every pair pushes along z (the bottom strip is flat and the top one parallel to it where
  // they touch), so the forces' sum is the load either way. The penalty's differs from the
  // hard contact's by the sinking (0.0015 h, 1 % of the 0.15 h of displacement that contact
  // takes up) and by the lever arms of its four pairs; measured -0.64 %.
  const double penalty_load = warm.forces.sum();
  EXPECT_NEAR(penalty_load, load, 0.02 * load);

  const ContactSolveResult seeded =
      solve_contact_equilibrium(s.model, 0.0, s.proxy, p.x, s.fixed(), hard, &warm);
  ASSERT_TRUE(seeded.converged) << seeded.message;
  EXPECT_LE((seeded.x - cold.x).lpNorm<Eigen::Infinity>(), 1e-6 * TwoStrips::kH);
  EXPECT_NEAR(seeded.forces.sum(), load, 1e-6 * load);
  const ContactSolveResult unseeded =
      solve_contact_equilibrium(s.model, 0.0, s.proxy, p.x, s.fixed(), hard);
  ASSERT_TRUE(unseeded.converged) << unseeded.message;
  // Measured: 6 seeded, 12 unseeded (and 12 from the propped start).
  EXPECT_LT(seeded.iterations, unseeded.iterations);
  RecordProperty("seeded_iterations", seeded.iterations);
  RecordProperty("unseeded_iterations", unseeded.iterations);
}

TEST(PenaltyWarmStart, BadArgumentsAreNamed) {
  TwoStrips s;
  const ContactBranchOptions o = penalty_options();
  const Eigen::VectorXd x = s.model.reference_positions();
  const ContactCandidates none;
  EXPECT_THROW(penalty_warm_start(s.proxy, none, x, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(penalty_warm_start(s.proxy, none, x, o.contact_distance, -1.0),
               std::invalid_argument);
  EXPECT_THROW(penalty_warm_start(s.proxy, none, x, o.contact_distance, std::nan("")),
               std::invalid_argument);
  // No pair: no force, and the warm start seeds nothing.
  const ContactSolveResult empty = penalty_warm_start(s.proxy, none, x, o.contact_distance, 1.0);
  EXPECT_EQ(empty.forces.size(), 0);
}

}  // namespace
}  // namespace growshell
