#pragma once
// The contact tests' disc: a coarse graded disc (8 rings, R = 1 m, h = 0.06 m, Y = 1e4 Pa,
// nu = 0.3) grown on the n = 2 e-cone to phi_e = 5 without contact (on first use); its folds'
// gap reaches h near phi_e = 6.0 and first contact under the penalty is at 6.137. With the
// penalty and Ipopt settings the contact tests share.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_free_cone.hpp"
#include "solvers/continuation/growth_path.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace growshell::test_support {

struct GrownDisc {
  ShellModel model;
  std::vector<Eigen::Index> pinned;
  ContactProxy proxy;

  Eigen::VectorXd start_;  // the cone at kStart, grown on first use

  static constexpr double kH = 0.06;
  static constexpr double kStart = 5.0;

  GrownDisc() : model(mesh(), settings()), proxy(make_contact_proxy(model, 1)) {
    const Eigen::VectorXd& X = model.reference_positions();
    pinned = mirror_axis_pinned_dofs(
        Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
        model.sheet_vertices(), model.settings().growth.center);
  }
  const Eigen::VectorXd& start() {
    if (start_.size() == 0) start_ = grown(kStart);
    return start_;
  }
  static TriangleMesh mesh() {
    DiscMeshOptions o;
    o.rings = 8;
    o.grading_exponent = 3.0;
    o.min_spacing = kH / 2;
    return make_disc_mesh(o);
  }
  static ShellModelSettings settings() {
    ShellModelSettings s;
    s.thickness = constant_thickness(kH);
    return s;
  }
  /// The n = 2 cone at phi (grown from a mirror-symmetric perturbation).
  Eigen::VectorXd grown(double phi) {
    const Eigen::VectorXd& X = model.reference_positions();
    Eigen::VectorXd dz = Eigen::VectorXd::Zero(X.size());
    for (Eigen::Index v = 0; v < X.size() / 3; ++v) {
      const double r = std::hypot(X(3 * v), X(3 * v + 1));
      const double t = std::atan2(X(3 * v + 1), X(3 * v));
      dz(3 * v + 2) = 1e-3 * r * r * std::cos(2 * t);
    }
    NewtonOptions n;
    n.gradient_tolerance = 1e-7 * model.natural_force_scale();
    n.decrement_tolerance = 1e-9 * 1e4 * kH * kH * kH;
    GrowthPathOptions steps;
    steps.max_step = 0.5;
    const GrowthPathResult path = grow_along_path(
        model, X + dz, 0.0, phi, pinned, NewtonSolver(n), [&](int) { return dz; }, steps);
    EXPECT_TRUE(path.reached_target) << path.message;
    return path.last.x;
  }
  ContactBranchOptions options() const {
    ContactBranchOptions o;
    o.contact_distance = kH;
    o.exclusion_radius = 0.5 * std::numbers::pi * kH;
    o.candidate_margin = kH;
    o.stiffness = 10.0 * contact_stiffness_scale(1e4, kH, proxy_mean_edge_length(proxy));
    o.violation_tolerance = 0.25 * kH;
    o.arclength.initial_step = 0.02;
    o.arclength.max_step = 0.05;
    o.arclength.min_step = 1e-6;
    o.arclength.gradient_tolerance = 1e-7 * model.natural_force_scale();
    o.arclength.angle_test_max_step = 1e-3;
    o.arclength.max_tangent_angle = 0.5;
    return o;
  }
  // trace_contact_free_cone on this disc: the cone entered from flat by continuation (folds
  // on the mesh's mirror axes) up to 6.6, with the exclusion radius factor * h.
  ContactFreeConeOptions cone_options(double exclusion_factor) const {
    ContactFreeConeOptions o;
    o.arclength.initial_step = 0.025;
    o.arclength.max_step = 0.1;
    o.arclength.min_step = 1e-4;
    o.arclength.gradient_tolerance = 1e-6 * model.natural_force_scale();
    o.arclength.parameter_max = 6.6;
    o.entry.thickness = kH;
    o.entry.radius = 1.0;
    o.contact_distance = kH;
    o.exclusion_radius = exclusion_factor * kH;
    return o;
  }
  // Ipopt on the same scene (contact distance, exclusion and margin as options(), lengths and
  // forces scaled by h and the shell's force scale); each test sets its own tolerances.
  ContactSolveOptions ipopt_options() const {
    ContactSolveOptions o;
    o.contact_distance = kH;
    o.exclusion_radius = 0.5 * std::numbers::pi * kH;
    o.candidate_margin = kH;
    o.minimizer.length_scale = kH;
    o.minimizer.force_scale = model.natural_force_scale();
    return o;
  }
};

inline GrownDisc& disc() {
  static GrownDisc d;
  return d;
}

}  // namespace growshell::test_support
