// trace_branch_in_subspace and resume_branch_in_subspace on the two-fold cone of a small disc:
//  - every sample keeps the reduced state it was traced in and the frame, and its full state
//    is that reduced state expanded and moved into the caller's frame, bit for bit;
//  - a trace resumed from a sample (with its next step) takes the same steps as the trace that
//    went on, to the last bit, where rebuilding the reduced state from x is exact only to
//    rounding;
//  - a sample without reduced coordinates, or one whose state no longer matches them, is
//    projected and traced on along the same branch.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/continuation/cone_branch_entry.hpp"
#include "solvers/continuation/subspace_branch_trace.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace growshell {
namespace {

class SubspaceBranchTrace : public ::testing::Test {
 protected:
  SubspaceBranchTrace() : model_(make_model()), subspace_(two_mirror_subspace(model_, 1e-9)) {
    const Eigen::VectorXd X = model_.reference_positions();
    const Eigen::MatrixX3d P =
        Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
    pinned_ = mirror_axis_pinned_dofs(P, model_.sheet_vertices(), Eigen::Vector3d::Zero());
    options_.initial_step = 0.002;
    options_.max_step = 0.02;
    options_.gradient_tolerance = 1e-9 * model_.natural_force_scale();
    ConeEntryOptions entry;
    entry.folds = 2;
    entry.thickness = 0.04;
    entry.radius = 1.0;
    options_.parameter_max = 0.12;
    entry_ = enter_cone_branch(model_, model_, entry, pinned_, options_);
    options_.parameter_max = entry_.branch_point.parameter + 0.25;
  }

  static ShellModel make_model() {
    DiscMeshOptions mo;
    mo.rings = 6;
    ShellModelSettings s;
    s.thickness = constant_thickness(0.04);
    return ShellModel(make_disc_mesh(mo), s);
  }

  /// The samples of the trace from `start` (with its next step) to the parameter bound.
  std::vector<BranchSample> resumed_from(const BranchSample& start, bool* reduced_used) const {
    ArclengthOptions again = options_;
    again.initial_step = start.next_step;
    std::vector<BranchSample> rest;
    resume_branch_in_subspace(
        model_, subspace_, start, start.tangent_state, start.tangent_parameter, pinned_, again,
        [&](const BranchSample& s) { rest.push_back(s); }, {}, {}, {}, reduced_used);
    return rest;
  }

  ShellModel model_;
  SymmetricSubspace subspace_;
  std::vector<Eigen::Index> pinned_;
  ArclengthOptions options_;
  ConeBranchEntry entry_;
};

TEST_F(SubspaceBranchTrace, AResumedTraceTakesTheSameStepsToTheLastBit) {
  ASSERT_TRUE(entry_.found) << entry_.message;
  std::vector<BranchSample> whole;
  const BranchTrace trace = trace_branch_in_subspace(
      model_, subspace_, entry_.start, entry_.branch_point.parameter, entry_.mode, 0.0, pinned_,
      options_, [&](const BranchSample& s) { whole.push_back(s); });
  ASSERT_TRUE(trace.reached_bound) << trace.message;
  ASSERT_GE(whole.size(), 10u);
  for (const BranchSample& s : whole) {
    ASSERT_EQ(s.reduced_x.size(), subspace_.dimension());
    EXPECT_EQ(s.reduced_frame.apply_inverse(subspace_.expand(s.reduced_x)), s.x);
  }
  for (const std::size_t k : {std::size_t{2}, whole.size() / 2, whole.size() - 3}) {
    bool reduced = false;
    const std::vector<BranchSample> rest = resumed_from(whole[k], &reduced);
    EXPECT_TRUE(reduced);
    ASSERT_EQ(rest.size(), whole.size() - k) << "from sample " << k;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      EXPECT_EQ(rest[i].parameter, whole[k + i].parameter) << "sample " << k + i;
      EXPECT_EQ(rest[i].x, whole[k + i].x) << "sample " << k + i;
      EXPECT_EQ(rest[i].tangent_state, whole[k + i].tangent_state) << "sample " << k + i;
      EXPECT_EQ(rest[i].next_step, whole[k + i].next_step) << "sample " << k + i;
    }
  }
}

TEST_F(SubspaceBranchTrace, ASampleWithoutItsReducedStateIsProjectedOntoTheSameBranch) {
  ASSERT_TRUE(entry_.found) << entry_.message;
  std::vector<BranchSample> whole;
  trace_branch_in_subspace(model_, subspace_, entry_.start, entry_.branch_point.parameter,
                           entry_.mode, 0.0, pinned_, options_,
                           [&](const BranchSample& s) { whole.push_back(s); });
  ASSERT_GE(whole.size(), 10u);
  const std::size_t k = whole.size() / 2;
  BranchSample bare = whole[k];  // e.g. read from a state file of version 2
  bare.reduced_x.resize(0);
  BranchSample moved = whole[k];  // a state changed since its reduced coordinates were taken
  moved.x(5) = std::nextafter(moved.x(5), 1.0);
  for (const BranchSample& start : {bare, moved}) {
    bool reduced = true;
    const std::vector<BranchSample> rest = resumed_from(start, &reduced);
    EXPECT_FALSE(reduced);
    ASSERT_GE(rest.size(), 3u);
    // The same branch: the first steps land on the uninterrupted samples to rounding.
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_NEAR(rest[i].parameter, whole[k + i].parameter, 1e-10) << "sample " << k + i;
      EXPECT_LT((rest[i].x - whole[k + i].x).lpNorm<Eigen::Infinity>(), 1e-9) << k + i;
      EXPECT_EQ(rest[i].reduced_x.size(), subspace_.dimension());
    }
  }
}

}  // namespace
}  // namespace growshell
