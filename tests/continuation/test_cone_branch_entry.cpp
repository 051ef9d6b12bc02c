// leave_branch_point: the step off the branch point is halved while the corrector cannot
// converge at the start, the costs of the failed attempts are kept, and bad arguments throw.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "solvers/continuation/cone_branch_entry.hpp"

namespace growshell {
namespace {

/// An entry at the branch point x = (1, 0, 0) with the mode (0, 1, 0) and the step 0.005.
ConeBranchEntry unit_entry() {
  ConeBranchEntry e;
  e.found = true;
  e.branch_point.x = Eigen::VectorXd::Unit(3, 0);
  e.branch_point.parameter = 0.25;
  e.mode = Eigen::VectorXd::Unit(3, 1);
  e.switch_step = 0.005;
  e.start = e.branch_point.x + e.switch_step * e.mode;
  return e;
}

/// A tracer whose start converges only within `basin` of the branch point along the mode;
/// it records the steps it was given and charges 3 linearisations per call.
struct BasinTracer {
  double basin;
  std::vector<double> steps_seen;
  BranchTrace operator()(const Eigen::VectorXd& start, const Eigen::VectorXd& mode) {
    const double s = (start - Eigen::VectorXd::Unit(3, 0)).dot(mode);
    steps_seen.push_back(s);
    BranchTrace t;
    t.cost.linearizations = 3;
    t.start_converged = s <= basin;
    t.steps = t.start_converged ? 7 : 0;
    t.message = t.start_converged ? "reached the parameter bound"
                                  : "the start is not an equilibrium the corrector can converge to";
    return t;
  }
};

TEST(LeaveBranchPoint, KeepsTheFirstStepWhereItConverges) {
  BasinTracer tracer{1.0, {}};
  const BranchPointDeparture d = leave_branch_point(
      unit_entry(), [&](const Eigen::VectorXd& x, const Eigen::VectorXd& m) { return tracer(x, m); });
  EXPECT_EQ(d.attempts, 1);
  EXPECT_EQ(d.switch_step, 0.005);
  ASSERT_EQ(tracer.steps_seen.size(), 1u);
  EXPECT_NEAR(tracer.steps_seen[0], 0.005, 1e-15);
  EXPECT_EQ(d.trace.cost.linearizations, 3);
  EXPECT_EQ(d.trace.steps, 7);
}

TEST(LeaveBranchPoint, HalvesTheStepUntilTheStartConverges) {
  BasinTracer tracer{0.0013, {}};  // 0.005 and 0.0025 fail, 0.00125 converges
  const BranchPointDeparture d = leave_branch_point(
      unit_entry(), [&](const Eigen::VectorXd& x, const Eigen::VectorXd& m) { return tracer(x, m); });
  EXPECT_EQ(d.attempts, 3);
  EXPECT_DOUBLE_EQ(d.switch_step, 0.00125);
  ASSERT_EQ(tracer.steps_seen.size(), 3u);
  EXPECT_NEAR(tracer.steps_seen[1], 0.0025, 1e-15);
  EXPECT_NEAR(tracer.steps_seen[2], 0.00125, 1e-15);
  EXPECT_TRUE(d.trace.start_converged);
  EXPECT_EQ(d.trace.steps, 7);
  EXPECT_EQ(d.trace.cost.linearizations, 9);  // the failed attempts' cost is kept
}

TEST(LeaveBranchPoint, GivesUpAfterMaxAttemptsWithTheLastFailure) {
  BasinTracer tracer{1e-6, {}};
  const BranchPointDeparture d = leave_branch_point(
      unit_entry(), [&](const Eigen::VectorXd& x, const Eigen::VectorXd& m) { return tracer(x, m); },
      4);
  EXPECT_EQ(d.attempts, 4);
  EXPECT_EQ(tracer.steps_seen.size(), 4u);
  EXPECT_DOUBLE_EQ(d.switch_step, 0.000625);
  EXPECT_FALSE(d.trace.start_converged);
  EXPECT_EQ(d.trace.cost.linearizations, 12);
  EXPECT_NE(d.trace.message.find("the start is not an equilibrium"), std::string::npos);
}

TEST(LeaveBranchPoint, RejectsAnEntryWithoutBranchPointAndNoAttempts) {
  BasinTracer tracer{1.0, {}};
  const auto call = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& m) { return tracer(x, m); };
  ConeBranchEntry none = unit_entry();
  none.found = false;
  none.message = "no branch point with a 2-fold mode";
  EXPECT_THROW(leave_branch_point(none, call), std::invalid_argument);
  EXPECT_THROW(leave_branch_point(unit_entry(), call, 0), std::invalid_argument);
  EXPECT_TRUE(tracer.steps_seen.empty());
}

}  // namespace
}  // namespace growshell
