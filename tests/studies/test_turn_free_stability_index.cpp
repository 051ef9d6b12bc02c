// TurnFreeStabilityIndex: the stability index of a cone without the pattern's turn is a
// property of the state, not of where it sits in space. A rigid rotation of an equilibrium
// that leaves the trace's pins without their lever arm (the pinned rim vertex carried onto
// the line through the centre along which the sheet then lies) must give the same index: the
// count re-chooses its pins there.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <stdexcept>
#include <vector>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/rigid_motion.hpp"
#include "solvers/continuation/cone_branch_entry.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace growshell {
namespace {

Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>> as_rows(const Eigen::VectorXd& x) {
  return {x.data(), x.size() / 3, 3};
}

struct DiscCone {
  ShellModel model;
  std::vector<Eigen::Index> pins;
  explicit DiscCone(ShellModel m) : model(std::move(m)) {
    pins = mirror_axis_pinned_dofs(as_rows(model.reference_positions()), model.sheet_vertices(),
                                   Eigen::Vector3d::Zero());
  }
};

/// The n-fold cone 0.3 past its branch point on the 6-ring hexagonal disc at h = 0.04.
BranchSample traced_cone(DiscCone& disc, int folds) {
  ArclengthOptions o;
  o.initial_step = 0.002;
  o.max_step = 0.02;
  o.gradient_tolerance = 1e-9 * disc.model.natural_force_scale();
  o.parameter_max = 0.12;
  ConeEntryOptions entry;
  entry.thickness = 0.04;
  entry.radius = 1.0;
  entry.folds = folds;
  const ConeBranchEntry e = enter_cone_branch(disc.model, disc.model, entry, disc.pins, o);
  if (!e.found) throw std::runtime_error(e.message);
  o.parameter_max = e.branch_point.parameter + 0.3;
  o.max_steps = 12;
  std::vector<BranchSample> samples;
  trace_branch_along(disc.model, e.start, e.branch_point.parameter, e.mode, 0.0, disc.pins, o,
                     [&](const BranchSample& s) { samples.push_back(s); });
  if (samples.empty()) throw std::runtime_error("no cone sample");
  return samples.back();
}

DiscCone hexagonal_disc() {
  DiscMeshOptions mo;
  mo.rings = 6;
  ShellModelSettings s;
  s.thickness = constant_thickness(0.04);
  return DiscCone(ShellModel(make_disc_mesh(mo), s));
}

TEST(TurnFreeStabilityIndex, IsTheSameForEveryRigidPlacementOfTheCone) {
  for (const int folds : {2, 3}) {
    DiscCone disc = hexagonal_disc();
    const BranchSample cone = traced_cone(disc, folds);
    TurnFreeStabilityIndex index(disc.model, disc.model, disc.pins);
    const int placed = index.at(cone.x, cone.parameter);
    EXPECT_EQ(index.last_pins(), disc.pins) << "the trace's pins hold this state";

    // Turn the sheet about the centre vertex so that the pinned rim vertex B lies straight
    // above it: the two pins on B then no longer stop the spin about the line AB.
    const Eigen::Index a = disc.pins[0] / 3, b = disc.pins[3] / 3;
    const Eigen::Vector3d centre = cone.x.segment<3>(3 * a);
    RigidMotion turn;
    turn.rotation =
        Eigen::Quaterniond::FromTwoVectors(cone.x.segment<3>(3 * b) - centre, Eigen::Vector3d::UnitZ())
            .toRotationMatrix();
    turn.translation = centre - turn.rotation * centre;
    const Eigen::VectorXd turned = turn.apply(cone.x);
    ASSERT_GT(pinned_rigid_motion_condition(as_rows(turned), disc.pins), 1e8)
        << "the rotation must leave the trace's pins without a lever arm";

    EXPECT_EQ(index.at(turned, cone.parameter), placed) << "n = " << folds;
    EXPECT_NE(index.last_pins(), disc.pins);
    EXPECT_LE(pinned_rigid_motion_condition(as_rows(turned), index.last_pins()),
              TurnFreeStabilityIndex::kDefaultMaxPinCondition);
    std::printf("n = %d: index %d at phi_e = %.4f\n", folds, placed, cone.parameter);
  }
}

TEST(TurnFreeStabilityIndex, NeedsSixPinsAndAConditionOfAtLeastOne) {
  DiscCone disc = hexagonal_disc();
  std::vector<Eigen::Index> five(disc.pins.begin(), disc.pins.begin() + 5);
  EXPECT_THROW(TurnFreeStabilityIndex(disc.model, disc.model, five), std::invalid_argument);
  EXPECT_THROW(TurnFreeStabilityIndex(disc.model, disc.model, disc.pins, 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
