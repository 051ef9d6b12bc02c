// trace_contact_branch (pseudo-arclength continuation through self-contact with the penalty):
//  - far from contact it is the plain continuation of the shell energy, sample for sample;
//  - through first contact every converged sample keeps every pair of the sheet (all
//    vertex-triangle and edge-edge pairs, not only the penalised ones) at distance >= h - tol,
//    with tol the penalty's penetration bound, and the penalty forces appear;
//  - each sample's energy slope is dE/dphi along the branch (checked against the energies of
//    neighbouring samples where the branch is smooth, before contact);
//  - the stability index along the branch equals the negative count of the Lagrangian Hessian
//    reduced to the active constraints (computed independently);
//  - penalty and Ipopt agree as the stiffness grows (state difference ~ 1/k);
//  - traced in the disc's two-mirror subspace, the symmetric branch has the full-space
//    branch's energies and stability loss, and every sample keeps both mirrors;
//  - trace_econe_branches: first contact, the symmetric branch's stability loss, a lower
//    skewed state found and followed; from a state with both mirrors a mode odd under one is
//    pushed one way, the other push relaxing to a state of the same energy;
//  - grow_with_contact: every state through contact a strict minimum (reduced Lagrangian count
//    0), no pair closer than h - h/20; a path split at a step and grown on from its last
//    state gives the same states (what a resumed winding relies on);
//  - with a phase condition, c . x keeps its start value over every segment, and each sample's
//    phase_force is the multiplier recomputed from the gradient (NaN without a condition);
//  - bad options are rejected naming the field.
//
// Scene: a coarse graded disc (8 rings, R = 1 m, h = 0.06 m, Y = 1e4 Pa, nu = 0.3) grown on
// the n = 2 e-cone to phi_e = 5 without contact; its folds' gap reaches h near phi_e = 6.0.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/limit_surface_contact.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_free_cone.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/contact_stability.hpp"
#include "solvers/contact/econe_branches.hpp"
#include "solvers/continuation/growth_path.hpp"
#include "solvers/continuation/phase_conditioned_family.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"
#include "solvers/stability/mode_symmetry_class.hpp"
#include "support/grown_disc.hpp"

namespace growshell {
namespace {

using test_support::disc;
using test_support::GrownDisc;

/// The grown disc's fold pattern has crept round against the mesh (natural growth steps), so
/// its mirrors are not the mesh's: the cone entered by continuation instead, whose folds lie
/// on the mesh's mirror axes, cut back before first contact (phi_e 6.0).
ContactFreeCone mirror_aligned_cone(GrownDisc& d) {
  ContactFreeConeOptions cone_options = d.cone_options(0.5 * std::numbers::pi);
  cone_options.arclength.gradient_tolerance = 1e-7 * d.model.natural_force_scale();
  cone_options.arclength.parameter_max = 6.0;
  return trace_contact_free_cone(d.model, d.proxy, d.pinned, cone_options);
}

// A smooth axisymmetric bump of 0.2 h on x, none at the pinned dofs (they keep x's gauge).
Eigen::VectorXd pushed_by_bump(const GrownDisc& d, const Eigen::VectorXd& x) {
  Eigen::VectorXd pushed = x;
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double r2 = x(3 * v) * x(3 * v) + x(3 * v + 1) * x(3 * v + 1);
    pushed(3 * v + 2) += 0.2 * GrownDisc::kH * std::exp(-4.0 * r2);
  }
  for (const Eigen::Index i : d.pinned) pushed(i) = x(i);
  return pushed;
}

// The relaxation of starts with the corrector's force tolerance, 100 iterations.
NewtonOptions start_relaxation_for(const ContactBranchOptions& o) {
  NewtonOptions relaxation;
  relaxation.gradient_tolerance = o.arclength.gradient_tolerance;
  relaxation.max_iterations = 100;
  return relaxation;
}

TEST(ContactBranch, FarFromContactItIsThePlainContinuation) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  const double phi0 = GrownDisc::kStart;
  ContactBranchOptions o = d.options();
  o.arclength.max_steps = 4;
  std::vector<ContactBranchSample> with_contact;
  const ContactBranchTrace t = trace_contact_branch(
      d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, o,
      [&](const ContactBranchSample& s) { with_contact.push_back(s); });
  EXPECT_EQ(t.steps, 4);
  std::vector<BranchSample> plain;
  ArclengthOptions a = o.arclength;
  trace_branch_along(d.model, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, a,
                     [&](const BranchSample& s) { plain.push_back(s); });
  ASSERT_EQ(with_contact.size(), plain.size());
  for (std::size_t i = 0; i < plain.size(); ++i) {
    // Same corrector on the same energy (no pair near); only the segment restarts re-correct
    // the start, which moves it within the corrector tolerance (1e-7 Y h^3 / R in force, i.e.
    // ~1e-10 m here).
    EXPECT_NEAR(with_contact[i].sample.parameter, plain[i].parameter, 1e-9);
    EXPECT_LT((with_contact[i].sample.x - plain[i].x).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_EQ(with_contact[i].active_pairs, 0);
    EXPECT_EQ(with_contact[i].penalty_energy, 0.0);
  }
  // dE/dphi along the branch: the centred difference of neighbouring samples' energies equals
  // the mean of their slopes up to dphi^2 E'''/12 (dphi <= 0.05, E''' ~ E: ~2e-4 relative).
  for (std::size_t i = 1; i < with_contact.size(); ++i) {
    const ContactBranchSample& a = with_contact[i - 1];
    const ContactBranchSample& b = with_contact[i];
    const double dphi = b.sample.parameter - a.sample.parameter;
    ASSERT_GT(dphi, 1e-3);
    const double ea = a.stretching_energy + a.bending_energy;
    const double eb = b.stretching_energy + b.bending_energy;
    EXPECT_NEAR((eb - ea) / dphi, 0.5 * (a.energy_slope + b.energy_slope),
                1e-3 * std::abs(a.energy_slope))
        << "between phi_e = " << a.sample.parameter << " and " << b.sample.parameter;
  }
}

// ContactBranchOptions::start_relaxation: a start the corrector cannot converge (here one
// iteration allowed for a start pushed off the branch) is relaxed by minimisation at its
// phi_e and the trace goes on from the minimum, the branch's state there; without it the
// trace ends at the start, naming it.
TEST(ContactBranch, AStartTheCorrectorCannotConvergeIsRelaxedAndTheTraceGoesOn) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  const Eigen::VectorXd pushed = pushed_by_bump(d, x);
  ContactBranchOptions o = d.options();
  o.arclength.max_steps = 3;
  o.arclength.start_corrector_iterations = 1;
  o.start_residual_backtracks = 0;  // no second try with halved updates
  const auto trace = [&](const ContactBranchOptions& options,
                         std::vector<ContactBranchSample>& samples) {
    return trace_contact_branch(d.model, d.proxy, pushed, GrownDisc::kStart,
                                Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, options,
                                [&](const ContactBranchSample& s) { samples.push_back(s); });
  };
  std::vector<ContactBranchSample> ended;
  const ContactBranchTrace without = trace(o, ended);
  EXPECT_TRUE(ended.empty());
  EXPECT_EQ(without.steps, 0);
  EXPECT_NE(without.message.find("segment start at phi_e = 5.000000 did not converge"),
            std::string::npos)
      << without.message;

  o.start_relaxation = start_relaxation_for(o);
  std::vector<ContactBranchSample> samples;
  const ContactBranchTrace with = trace(o, samples);
  EXPECT_EQ(with.cost.relaxed_starts, 1);
  EXPECT_EQ(with.steps, 3) << with.message;
  ASSERT_FALSE(samples.empty());
  // The trace starts on the branch at phi_e = 5: an equilibrium with the unpushed state's
  // energy. (Not the same state: the fold pattern's turn against the mesh is nearly free, and
  // the minimum reached lies 1.2e-3 m from it, a tenth of the push.)
  const ContactBranchSample& first = samples.front();
  EXPECT_NEAR(first.sample.parameter, GrownDisc::kStart, 1e-12);
  Eigen::VectorXd g;
  const double e = d.model.evaluate(first.sample.x, GrownDisc::kStart, &g, nullptr);
  for (const Eigen::Index i : d.pinned) g[i] = 0.0;
  EXPECT_LE(g.lpNorm<Eigen::Infinity>(), o.arclength.gradient_tolerance);
  const double e0 = d.model.evaluate(x, GrownDisc::kStart, nullptr, nullptr);
  EXPECT_NEAR(e, e0, 1e-8 * e0);
  EXPECT_LT((first.sample.x - x).cwiseAbs().maxCoeff(), 0.2 * 0.2 * GrownDisc::kH);
}

// The same in the mirror subspace: the start, pushed by an axisymmetric bump that keeps both
// mirrors, is relaxed in the full space on pair sets closed under the mirrors, and the trace
// goes on in the subspace with every sample mirror-symmetric (up to the rigid motion of its
// frame) and an equilibrium of the full space's energy.
TEST(ContactBranch, InASubspaceAStartThatCannotConvergeIsRelaxedAndKeepsTheSymmetry) {
  GrownDisc& d = disc();
  const ContactFreeCone cone = mirror_aligned_cone(d);
  ASSERT_TRUE(cone.found) << cone.message;
  const double phi0 = cone.start.parameter;
  const Eigen::VectorXd& x = cone.start.x;
  const Eigen::VectorXd pushed = pushed_by_bump(d, x);
  auto subspace = std::make_shared<const SymmetricSubspace>(two_mirror_subspace(d.model, 1e-9));
  ContactBranchOptions o = d.options();
  o.symmetric_subspace = subspace;
  o.arclength.max_steps = 3;
  o.arclength.start_corrector_iterations = 1;
  o.start_residual_backtracks = 0;
  const auto trace = [&](const ContactBranchOptions& options,
                         std::vector<ContactBranchSample>& samples) {
    return trace_contact_branch(d.model, d.proxy, pushed, phi0, Eigen::VectorXd::Zero(x.size()),
                                1.0, d.pinned, options,
                                [&](const ContactBranchSample& s) { samples.push_back(s); });
  };
  std::vector<ContactBranchSample> ended;
  const ContactBranchTrace without = trace(o, ended);
  EXPECT_TRUE(ended.empty());
  EXPECT_NE(without.message.find("did not converge"), std::string::npos) << without.message;

  o.start_relaxation = start_relaxation_for(o);
  std::vector<ContactBranchSample> samples;
  const ContactBranchTrace with = trace(o, samples);
  EXPECT_EQ(with.cost.relaxed_starts, 1);
  EXPECT_EQ(with.steps, 3) << with.message;
  ASSERT_EQ(samples.size(), 4u);
  for (const ContactBranchSample& s : samples) {
    const Eigen::VectorXd aligned = subspace->aligning_motion(s.sample.x).apply(s.sample.x);
    EXPECT_LT(subspace->asymmetry(aligned), 1e-10) << "at phi_e = " << s.sample.parameter;
  }
  // The first sample: an equilibrium at phi0 of the full energy with the pairs near it.
  const ContactBranchSample& first = samples.front();
  EXPECT_NEAR(first.sample.parameter, phi0, 1e-12);
  const ContactCandidates near =
      near_contact_pairs(d.proxy, first.sample.x, o.contact_distance + o.candidate_margin,
                         o.exclusion_radius, o.selection);
  ContactPenalty penalty(d.proxy, near, o.contact_distance, o.stiffness, x.size(), o.gap);
  PenalizedEnergy energy(d.model, penalty);
  Eigen::VectorXd g;
  energy.evaluate(first.sample.x, phi0, &g, nullptr);
  for (const Eigen::Index i : d.pinned) g[i] = 0.0;
  // An equivariant gradient's entries are its reduced entries over the square root of the
  // orbit size, so the corrector's reduced tolerance bounds it (measured: 0.01 of it).
  EXPECT_LE(g.lpNorm<Eigen::Infinity>(), o.arclength.gradient_tolerance);
}

// ContactBranchOptions::stability_index_for_segment: the samples carry the caller's count, and
// it is made once per segment with the segment's energy, of which each sample of the segment is
// an equilibrium (its gradient, pinned dofs aside, below the corrector's tolerance (inf-norm)
// at the sample's excess angle).
TEST(ContactBranch, TheCallersStabilityIndexIsCalledWithTheSegmentsEnergy) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  ContactBranchOptions o = d.options();
  o.arclength.max_steps = 3;
  int calls = 0, segments = 0;
  double worst = 0.0;
  o.stability_index_for_segment = [&](const ParametrizedObjective& energy,
                                      const SymmetricSubspace* subspace) {
    ++segments;
    EXPECT_EQ(subspace, nullptr);
    return [&](const BranchSample& s) {
      ++calls;
      Eigen::VectorXd g;
      energy.evaluate(s.x, s.parameter, &g, nullptr);
      for (const Eigen::Index dof : d.pinned) g(dof) = 0.0;
      worst = std::max(worst, g.cwiseAbs().maxCoeff() / o.arclength.gradient_tolerance);
      return 7;
    };
  };
  std::vector<ContactBranchSample> samples;
  const ContactBranchTrace t = trace_contact_branch(
      d.model, d.proxy, x, GrownDisc::kStart, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, o,
      [&](const ContactBranchSample& s) { samples.push_back(s); });
  EXPECT_EQ(t.steps, 3);
  ASSERT_EQ(samples.size(), 4u);
  for (const ContactBranchSample& s : samples) EXPECT_EQ(s.sample.negative_eigenvalues, 7);
  EXPECT_GE(calls, 4);
  EXPECT_EQ(segments, t.cost.segments);
  EXPECT_LT(worst, 1.0);
  EXPECT_TRUE(t.special_points.empty());
}

// ArclengthOptions::max_special_points holds for the whole trace, not each pair-set segment:
// with two steps a segment, the trace ends at the first change of the stability index, inside
// a segment (located by bisection) or where a segment's corrected start has it.
TEST(ContactBranch, MaxSpecialPointsEndsTheWholeTraceNotItsSegment) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  ContactBranchOptions o = d.options();
  o.steps_per_segment = 2;
  o.arclength.max_steps = 40;
  o.arclength.max_special_points = 1;
  struct Run {
    ContactBranchTrace trace;
    std::vector<ContactBranchSample> samples;
  };
  const auto run = [&](const ContactBranchOptions& options) {
    Run r;
    r.trace = trace_contact_branch(d.model, d.proxy, x, GrownDisc::kStart,
                                   Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, options,
                                   [&](const ContactBranchSample& s) { r.samples.push_back(s); });
    return r;
  };

  // An index that changes at phi_star, past the first segment.
  const double phi_star = GrownDisc::kStart + 0.2;
  o.stability_index_for_segment = [phi_star](const ParametrizedObjective&,
                                             const SymmetricSubspace*) {
    return [phi_star](const BranchSample& s) { return s.parameter > phi_star ? 1 : 0; };
  };
  const Run inside = run(o);
  EXPECT_TRUE(inside.trace.reached_bound);
  EXPECT_EQ(inside.trace.message, "found max_special_points special points");
  ASSERT_EQ(inside.trace.special_points.size(), 1u);
  EXPECT_NEAR(inside.trace.special_points[0].parameter, phi_star,
              o.arclength.special_point_tolerance);
  EXPECT_GE(inside.trace.cost.segments, 3);
  ASSERT_FALSE(inside.samples.empty());
  const BranchSample& end = inside.samples.back().sample;
  EXPECT_EQ(end.negative_eigenvalues, 1);
  EXPECT_GT(end.parameter, phi_star);
  EXPECT_LE(end.parameter, phi_star + 2 * o.arclength.max_step);
  EXPECT_EQ(end.parameter, inside.trace.last.sample.parameter);

  // An index that changes from the third segment on: at that segment's corrected start.
  int segments = 0;
  o.stability_index_for_segment = [&segments](const ParametrizedObjective&,
                                              const SymmetricSubspace*) {
    const int index = ++segments >= 3 ? 1 : 0;
    return [index](const BranchSample&) { return index; };
  };
  const Run boundary = run(o);
  EXPECT_TRUE(boundary.trace.reached_bound);
  EXPECT_EQ(boundary.trace.message, "found max_special_points special points");
  ASSERT_EQ(boundary.trace.special_points.size(), 1u);
  EXPECT_EQ(boundary.trace.special_points[0].negative_after, 1);
  EXPECT_EQ(segments, 3);
  EXPECT_EQ(boundary.trace.steps, 4);  // two segments of two steps
  EXPECT_EQ(boundary.samples.size(), 5u);
  EXPECT_EQ(boundary.trace.last.sample.negative_eigenvalues, 1);

  // Without the limit the same trace goes on past it.
  segments = 0;
  o.arclength.max_special_points = 0;
  o.arclength.max_steps = 8;
  const Run unlimited = run(o);
  EXPECT_EQ(unlimited.trace.message, "reached max_steps");
  EXPECT_EQ(unlimited.trace.special_points.size(), 1u);
  EXPECT_EQ(unlimited.trace.steps, 8);
}

TEST(ContactBranch, ThroughContactNoPairComesCloserThanTheThicknessLessTheTolerance) {
  GrownDisc& d = disc();
  const double phi0 = GrownDisc::kStart;
  const Eigen::VectorXd& x = d.start();
  ContactBranchOptions o = d.options();
  o.arclength.parameter_max = 6.5;
  o.arclength.max_steps = 60;
  std::vector<ContactBranchSample> samples;
  std::vector<Eigen::VectorXd> states;
  const ContactBranchTrace t = trace_contact_branch(
      d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, o,
      [&](const ContactBranchSample& s) {
        samples.push_back(s);
        states.push_back(s.sample.x);
      });
  EXPECT_TRUE(t.reached_bound) << t.message;
  ASSERT_GT(samples.size(), 5u);
  EXPECT_GT(samples.back().sample.parameter, 6.5);
  // Penetration bound: the largest penalty force over k. The pairs carry forces of order
  // Y h^3 / R... per pair; with k = 10 Y l^2 / h that is far below h / 10. Assert h / 20.
  const double tol = GrownDisc::kH / 20;
  int touching = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const ContactCandidates close =
        near_contact_pairs(d.proxy, states[i], GrownDisc::kH - tol, o.exclusion_radius,
                           NearPairSelection{true, false});
    EXPECT_TRUE(close.empty()) << "sample " << i << " at phi_e = " << samples[i].sample.parameter
                               << " has " << close.vertex_triangle.rows() << " + "
                               << close.edge_edge.rows() << " pairs closer than h - h/20";
    if (samples[i].active_pairs > 0) {
      ++touching;
      EXPECT_GT(samples[i].forces.maxCoeff(), 0.0);
      EXPECT_GT(samples[i].penalty_energy, 0.0);
      EXPECT_LT(samples[i].min_distance, GrownDisc::kH);
      EXPECT_GT(samples[i].min_distance, GrownDisc::kH - tol);
    }
  }
  EXPECT_GT(touching, 2) << "the folds did not touch below phi_e = 6.5";
  // Stability under contact: the negative count of the penalised Hessian (from the
  // continuation's LDL^T) equals that of the Lagrangian Hessian reduced to the tangent space of
  // the active pairs, with the penalty forces as multipliers (Debreu's lemma, file comment of
  // contact_branch.hpp), computed independently from the inertia of the KKT matrix.
  int compared = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].active_pairs == 0) continue;
    ObjectiveAtParameter energy(d.model, samples[i].sample.parameter);
    ContactGapConstraints gaps(d.proxy, samples[i].pairs, GrownDisc::kH, d.model.dimension());
    const ReducedInertia reduced =
        contact_constrained_inertia(energy, gaps, states[i], samples[i].forces, 0.0, d.pinned);
    EXPECT_EQ(reduced.negative, samples[i].sample.negative_eigenvalues)
        << "at phi_e = " << samples[i].sample.parameter;
    EXPECT_EQ(reduced.constraints, samples[i].active_pairs);
    ++compared;
  }
  EXPECT_GT(compared, 2);

  // Penalty against Ipopt at the last stable sample in contact: the penalty minimiser tends to
  // the constrained one like 1/k (the penetration is f/k), so each tenfold stiffness shrinks
  // the distance between the two states about tenfold.
  std::size_t last = samples.size();
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (samples[i].active_pairs > 0 && samples[i].sample.negative_eigenvalues == 0) last = i;
  ASSERT_LT(last, samples.size()) << "no stable sample in contact";
  const double phi = samples[last].sample.parameter;
  ContactSolveOptions ip = d.ipopt_options();
  ip.violation_tolerance = 1e-3 * GrownDisc::kH;
  ip.minimizer.tolerance = 1e-10;
  ip.minimizer.constraint_violation_tolerance = 1e-9 * GrownDisc::kH;
  ip.minimizer.complementarity_tolerance = 1e-10 * d.model.natural_force_scale() * GrownDisc::kH;
  ip.newton.gradient_tolerance = 1e-9 * d.model.natural_force_scale();
  const ContactSolveResult constrained =
      solve_contact_equilibrium(d.model, phi, d.proxy, states[last], d.pinned, ip);
  ASSERT_TRUE(constrained.converged) << constrained.message;
  ASSERT_TRUE(constrained.used_contact);
  const ContactCandidates pairs = samples[last].pairs;
  std::vector<double> error;
  for (const double factor : {1.0, 10.0, 100.0}) {
    ContactPenalty penalty(d.proxy, pairs, GrownDisc::kH, factor * o.stiffness,
                           d.model.dimension());
    PenalizedEnergy family(d.model, penalty);
    ObjectiveAtParameter energy(family, phi);
    NewtonOptions n;
    n.gradient_tolerance = 1e-9 * d.model.natural_force_scale();
    const NewtonResult r = NewtonSolver(n).minimize(energy, constrained.x, d.pinned);
    ASSERT_TRUE(r.converged()) << r.message;
    error.push_back((r.x - constrained.x).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(error[0], 0.05 * GrownDisc::kH);
  EXPECT_LT(error[1], error[0] / 5) << error[0] << " -> " << error[1];
  EXPECT_LT(error[2], error[1] / 5) << error[1] << " -> " << error[2];
  EXPECT_FALSE(samples.front().active_pairs > 0) << "already touching at the start";
}

// The same trace with the pairs measured on the limit surface (ContactGapOptions::
// limit_surface, study.contact_surface = limit_surface): the gaps keep to the thickness less
// the penalty's penetration, and the continuation's negative count is the Lagrangian's reduced
// to the active limit-surface gaps' tangent space (the pairs' exact Jacobian and Hessian of
// limit_surface_distance.hpp enter both).
TEST(ContactBranch, OnTheLimitSurfaceTheGapsKeepTheThicknessAndTheIndexIsTheReducedLagrangians) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  ContactBranchOptions o = d.options();
  o.arclength.parameter_max = 6.5;
  o.arclength.max_steps = 60;
  o.gap.limit_surface = make_limit_surface_contact(d.model, o.exclusion_radius);
  std::vector<ContactBranchSample> samples;
  const ContactBranchTrace t = trace_contact_branch(
      d.model, d.proxy, x, GrownDisc::kStart, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, o,
      [&](const ContactBranchSample& s) { samples.push_back(s); });
  EXPECT_TRUE(t.reached_bound) << t.message;
  ASSERT_GT(samples.size(), 5u);
  const double tol = GrownDisc::kH / 20;
  int compared = 0;
  for (const ContactBranchSample& s : samples) {
    if (s.active_pairs == 0) continue;
    EXPECT_LT(s.min_distance, GrownDisc::kH);
    EXPECT_GT(s.min_distance, GrownDisc::kH - tol);
    EXPECT_GT(s.penalty_energy, 0.0);
    // Every gap of the sample's own set, measured on the limit surface, above h - h/20.
    ContactGapConstraints gaps(d.proxy, s.pairs, GrownDisc::kH, d.model.dimension(), o.gap);
    ASSERT_TRUE(gaps.measures_limit_surface());
    Eigen::VectorXd values;
    gaps.evaluate(s.sample.x, values, nullptr);
    EXPECT_GT(values.minCoeff(), -tol) << "at phi_e = " << s.sample.parameter;
    ObjectiveAtParameter energy(d.model, s.sample.parameter);
    const ReducedInertia reduced =
        contact_constrained_inertia(energy, gaps, s.sample.x, s.forces, 0.0, d.pinned);
    EXPECT_EQ(reduced.negative, s.sample.negative_eigenvalues)
        << "at phi_e = " << s.sample.parameter;
    EXPECT_EQ(reduced.constraints, s.active_pairs);
    ++compared;
  }
  EXPECT_GT(compared, 2) << "the folds did not touch below phi_e = 6.5";
}

// Sets of every near triangle (NearPairSelection::nearest_triangle_only off, as the
// econe_contact scene key study.contact_vertex_triangles = every_near_triangle sets): through
// first contact every sample's set holds each vertex-triangle pair closer than the contact
// distance (every pair that the penalty of all near triangles acts on; a set of the nearest
// triangle per vertex misses those of the vertex's other triangles), and the penalty is a
// function of the state alone: on its own set and on a set rebuilt at the sample it is the
// same to rounding, so a rebuild changes no force.
TEST(ContactBranch, SetsOfEveryNearTriangleHoldTheClosePairsAndDoNotChangeTheEnergy) {
  GrownDisc& d = disc();
  const double phi0 = GrownDisc::kStart;
  const Eigen::VectorXd& x = d.start();
  ContactBranchOptions o = d.options();
  o.selection = NearPairSelection{false, false};
  o.arclength.parameter_max = 6.5;
  o.arclength.max_steps = 60;
  std::vector<ContactBranchSample> samples;
  const ContactBranchTrace t = trace_contact_branch(
      d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, o,
      [&](const ContactBranchSample& s) { samples.push_back(s); });
  EXPECT_TRUE(t.reached_bound) << t.message;
  ASSERT_GT(samples.size(), 5u);
  int touching = 0, several_triangles = 0;
  for (const ContactBranchSample& s : samples) {
    const ContactCandidates close = near_contact_pairs(
        d.proxy, s.sample.x, GrownDisc::kH, o.exclusion_radius, NearPairSelection{false, false});
    for (Eigen::Index i = 0; i < close.vertex_triangle.rows(); ++i) {
      bool held = false;
      for (Eigen::Index j = 0; j < s.pairs.vertex_triangle.rows() && !held; ++j)
        held = s.pairs.vertex_triangle.row(j) == close.vertex_triangle.row(i);
      EXPECT_TRUE(held) << "at phi_e = " << s.sample.parameter << " the pair ("
                        << close.vertex_triangle(i, 0) << ", " << close.vertex_triangle(i, 1)
                        << ") is not in the set";
    }
    if (s.active_pairs == 0) continue;
    ++touching;
    std::set<int> vertices;
    for (Eigen::Index j = 0; j < s.pairs.vertex_triangle.rows(); ++j)
      vertices.insert(s.pairs.vertex_triangle(j, 0));
    if (static_cast<Eigen::Index>(vertices.size()) < s.pairs.vertex_triangle.rows())
      ++several_triangles;
    const ContactCandidates rebuilt = near_contact_pairs(
        d.proxy, s.sample.x, GrownDisc::kH + o.candidate_margin, o.exclusion_radius, o.selection);
    ContactPenalty own(d.proxy, s.pairs, GrownDisc::kH, o.stiffness, d.model.dimension());
    ContactPenalty fresh(d.proxy, rebuilt, GrownDisc::kH, o.stiffness, d.model.dimension());
    Eigen::VectorXd g_own, g_fresh;
    const double p_own = own.evaluate(s.sample.x, &g_own, nullptr);
    const double p_fresh = fresh.evaluate(s.sample.x, &g_fresh, nullptr);
    EXPECT_NEAR(p_own, p_fresh, 1e-12 * p_own) << "at phi_e = " << s.sample.parameter;
    EXPECT_LT((g_own - g_fresh).cwiseAbs().maxCoeff(), 1e-12 * g_own.cwiseAbs().maxCoeff())
        << "at phi_e = " << s.sample.parameter;
  }
  EXPECT_GT(touching, 2) << "the folds did not touch below phi_e = 6.5";
  EXPECT_EQ(several_triangles, touching) << "sets with one triangle per vertex";
}

// The symmetric branch traced among the states with both mirrors
// (ContactBranchOptions::symmetric_subspace) is the full-space branch: same energies, same
// stability loss (now an index of the full Hessian), and every sample has both mirrors up to a
// rigid motion (the trace runs in the subspace's frame and hands states back in the caller's).
TEST(ContactBranch, InTheMirrorSubspaceTheSymmetricBranchKeepsItsMirrorsAndItsStabilityLoss) {
  GrownDisc& d = disc();
  const ContactFreeCone cone = mirror_aligned_cone(d);
  ASSERT_TRUE(cone.found) << cone.message;
  const double phi0 = cone.start.parameter;
  const Eigen::VectorXd x = cone.start.x;
  ContactBranchOptions o = d.options();
  o.arclength.parameter_max = 6.5;
  o.arclength.max_steps = 80;
  struct Trace {
    std::vector<ContactBranchSample> samples;
    std::vector<SpecialPoint> special;
  };
  const auto run = [&](const ContactBranchOptions& options) {
    Trace t;
    const ContactBranchTrace r = trace_contact_branch(
        d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, options,
        [&](const ContactBranchSample& s) { t.samples.push_back(s); },
        [&](const SpecialPoint& sp) { t.special.push_back(sp); });
    EXPECT_TRUE(r.reached_bound) << r.message;
    return t;
  };
  const Trace full = run(o);
  auto subspace = std::make_shared<const SymmetricSubspace>(two_mirror_subspace(d.model, 1e-9));
  o.symmetric_subspace = subspace;
  const Trace reduced = run(o);
  ASSERT_GT(reduced.samples.size(), 10u);
  // The start, symmetrised and corrected, handed back where it was: it moves by the order of
  // its own asymmetry (the full-space cone trace keeps the mirrors only to its tolerance).
  const double start_asymmetry = subspace->asymmetry(subspace->aligning_motion(x).apply(x));
  EXPECT_LT(start_asymmetry, 1e-3 * GrownDisc::kH);  // measured 2.3e-5 m
  EXPECT_LT((reduced.samples.front().sample.x - x).cwiseAbs().maxCoeff(), 1.5 * start_asymmetry);
  int touching = 0;
  for (const ContactBranchSample& s : reduced.samples) {
    const Eigen::VectorXd aligned = subspace->aligning_motion(s.sample.x).apply(s.sample.x);
    EXPECT_LT(subspace->asymmetry(aligned), 1e-10) << "at phi_e = " << s.sample.parameter;
    touching += s.active_pairs > 0;
  }
  EXPECT_GT(touching, 3);
  // The stability loss: the first change of the full Hessian's count, a branch point.
  const auto first_loss = [](const Trace& t) {
    for (const SpecialPoint& sp : t.special)
      if (sp.negative_before == 0 && sp.negative_after > 0) return sp;
    ADD_FAILURE() << "no stability loss";
    return SpecialPoint{};
  };
  const SpecialPoint loss_full = first_loss(full), loss_reduced = first_loss(reduced);
  EXPECT_EQ(loss_reduced.kind, SpecialPoint::Kind::BranchPoint);
  EXPECT_LE(loss_reduced.bracket_width, 1e-6);
  // The subspace's penalty is the symmetrised one (pairs chosen with index tie-breaks enter
  // with their mirror images' weights), which can move the loss; on this disc it does not
  // (6.4076577 both ways; on the paper's disc by 1e-4).
  EXPECT_NEAR(loss_reduced.parameter, loss_full.parameter, 1e-4);
  // Energies along the branch: the full branch's, Hermite-interpolated with its slopes.
  const auto energy = [](const ContactBranchSample& s) {
    return s.stretching_energy + s.bending_energy + s.penalty_energy;
  };
  int compared = 0;
  for (const ContactBranchSample& s : reduced.samples) {
    const double p = s.sample.parameter;
    for (std::size_t i = 1; i < full.samples.size(); ++i) {
      const ContactBranchSample& a = full.samples[i - 1];
      const ContactBranchSample& b = full.samples[i];
      if (!(a.sample.parameter <= p && p <= b.sample.parameter)) continue;
      const double hstep = b.sample.parameter - a.sample.parameter,
                   t = (p - a.sample.parameter) / hstep;
      const double interpolated = (2 * t * t * t - 3 * t * t + 1) * energy(a) +
                                  (t * t * t - 2 * t * t + t) * hstep * a.energy_slope +
                                  (-2 * t * t * t + 3 * t * t) * energy(b) +
                                  (t * t * t - t * t) * hstep * b.energy_slope;
      // Measured: 1.7e-8 relative at most (the interpolation's own error).
      EXPECT_NEAR(energy(s), interpolated, 1e-6 * energy(s)) << "at phi_e = " << p;
      ++compared;
      break;
    }
  }
  EXPECT_GT(compared, 10);
}

// trace_econe_branches on the same disc: the symmetric branch to phi_e = 6.5, then the state
// there pushed along its lowest mode and relaxed. Values of the coarse disc (8 rings), not of
// the paper's: first contact at 6.137, stability loss at 6.408, and at 6.6 a skewed state
// 1.4 % below the symmetric one whose branch is stable and in contact down to 6.296.
TEST(EconeBranches, SymmetricBranchLosesStabilityAndALowerSkewedStateIsFollowed) {
  GrownDisc& d = disc();
  EconeBranchOptions o;
  o.contact = d.options();
  o.contact.arclength.gradient_tolerance = 1e-5 * d.model.natural_force_scale();
  o.contact.arclength.min_step = 1e-4;  // the skewed branch stalls at 6.296: give up early
  o.symmetric_end = 6.5;
  o.skewed_end = 6.5;
  o.max_steps_per_branch = 40;
  o.relaxation.gradient_tolerance = 1e-5 * d.model.natural_force_scale();
  o.relaxation.max_iterations = 400;
  // Ipopt with hard constraints on vertex-triangle and edge-edge pairs checks the skewed state.
  ContactSolveOptions ipopt = d.ipopt_options();
  ipopt.edge_edge_pairs = true;
  ipopt.violation_tolerance = 1e-2 * GrownDisc::kH;
  ipopt.minimizer.tolerance = 1e-8;
  ipopt.minimizer.constraint_violation_tolerance = 1e-6 * GrownDisc::kH;
  ipopt.minimizer.complementarity_tolerance = 1e-8 * d.model.natural_force_scale() * GrownDisc::kH;
  ipopt.newton.gradient_tolerance = 1e-6 * d.model.natural_force_scale();
  o.verify_with_ipopt = ipopt;
  std::vector<std::pair<EconeBranch, ContactBranchSample>> samples;
  EconeBranchCallbacks callbacks;
  callbacks.on_sample = [&](EconeBranch b, const ContactBranchSample& s) { samples.push_back({b, s}); };
  const EconeBranchResult r =
      trace_econe_branches(d.model, d.proxy, d.start(), GrownDisc::kStart, d.pinned, o, callbacks);
  ASSERT_TRUE(r.first_contact.has_value());
  EXPECT_GT(r.first_contact->parameter, 6.0);
  EXPECT_LT(r.first_contact->parameter, 6.3);
  EXPECT_LE(r.first_contact->bracket_width, 1e-6);
  ASSERT_TRUE(r.stability_loss.has_value());
  EXPECT_EQ(r.stability_loss->kind, SpecialPoint::Kind::BranchPoint);
  EXPECT_GT(r.stability_loss->parameter, r.first_contact->parameter);
  EXPECT_LT(r.stability_loss->parameter, 6.5);
  EXPECT_LE(r.stability_loss->bracket_width, 1e-6);
  ASSERT_TRUE(r.skewed_found) << r.skewed_message;
  EXPECT_LT(r.skewed_relaxed_energy, (1.0 - 1e-2) * r.symmetric_top_energy) << r.skewed_message;
  // Under hard constraints that also keep crossing edges h apart the skewed state rises (the
  // penalty lets edges between proxy vertices come to 0.92 h on this coarse proxy) but stays
  // below the symmetric one: 2.681 against 2.703 J at phi_e = 6.6.
  ASSERT_TRUE(r.ipopt_checked);
  EXPECT_TRUE(r.ipopt_converged) << r.ipopt_message;
  EXPECT_GE(r.ipopt_min_distance, GrownDisc::kH - 1e-2 * GrownDisc::kH);
  EXPECT_GT(r.ipopt_energy, r.penalty_elastic_energy);
  EXPECT_LT(r.ipopt_energy, r.symmetric_top_energy);
  // The skewed branch is followed from the relaxed state: it starts stable and in contact.
  int skewed = 0;
  for (const auto& [branch, s] : samples) {
    // The penalty acts on vertex-triangle pairs (as the paper's): no such pair of the sheet,
    // nearest triangle or not, closer than h - h/20. Edges crossing between proxy vertices are
    // not penalised; where the skewed cone's wings slide across each other they come to
    // 0.921 h on this coarse proxy (spacing 2.4 h): bounded at 0.9 h here (docs/contact.md).
    const ContactCandidates close =
        near_contact_pairs(d.proxy, s.sample.x, GrownDisc::kH - GrownDisc::kH / 20,
                           o.contact.exclusion_radius, NearPairSelection{false, false});
    EXPECT_TRUE(close.empty()) << to_string(branch) << " at phi_e = " << s.sample.parameter;
    const ContactCandidates crossing_edges =
        near_contact_pairs(d.proxy, s.sample.x, 0.9 * GrownDisc::kH, o.contact.exclusion_radius,
                           NearPairSelection{true, false});
    EXPECT_TRUE(crossing_edges.empty()) << to_string(branch) << " at phi_e = " << s.sample.parameter;
    if (branch != EconeBranch::Skewed) continue;
    if (skewed++ == 0) {
      EXPECT_EQ(s.sample.negative_eigenvalues, 0);
      EXPECT_GT(s.active_pairs, 0);
      EXPECT_NEAR(s.sample.parameter, r.symmetric.last.sample.parameter, 1e-9);
    }
  }
  EXPECT_GT(skewed, 3);
}

// The skewed search from a state with both mirrors: a negative mode odd under a mirror is
// pushed one way only, since the opposite push is (up to the pins) the first's mirror image.
// Checked here independently: the push left out, relaxed by hand, reaches the search's energy.
TEST(EconeBranches, ASearchModeOddUnderAMirrorIsPushedOneWayAndTheOtherWayRelaxesToItsImage) {
  GrownDisc& d = disc();
  const ContactFreeCone cone = mirror_aligned_cone(d);
  ASSERT_TRUE(cone.found) << cone.message;
  EconeBranchOptions o;
  o.contact = d.options();
  o.contact.symmetric_subspace =
      std::make_shared<const SymmetricSubspace>(two_mirror_subspace(d.model, 1e-9));
  o.symmetric_end = 6.5;  // past the stability loss at 6.408: the top has a negative mode
  o.max_steps_per_branch = 80;
  o.relaxation.gradient_tolerance = 1e-7 * d.model.natural_force_scale();
  o.relaxation.max_iterations = 400;
  o.one_push_per_mirror_pair = true;
  // The skewed branch itself is not what this test is about: its traces end at once.
  o.skewed_min = 6.499;
  o.skewed_end = 6.5;
  const EconeBranchResult r =
      trace_econe_branches(d.model, d.proxy, cone.start.x, cone.start.parameter, d.pinned, o, {});
  ASSERT_TRUE(r.stability_loss.has_value());
  EXPECT_EQ(r.skewed_pushes_skipped_as_images, 1) << r.skewed_message;
  EXPECT_EQ(r.skewed_pushes_relaxed, 1) << r.skewed_message;
  EXPECT_NE(r.skewed_message.find("push -1: not relaxed, next to the image of push 1"),
            std::string::npos)
      << r.skewed_message;
  ASSERT_TRUE(r.skewed_found) << r.skewed_message;

  // The push the search left out, by hand, as the search makes it.
  const Eigen::VectorXd& top = r.symmetric.last.sample.x;
  const double phi = r.symmetric.last.sample.parameter;
  const std::vector<Eigen::Index> pins = rigid_pins_for_state(d.model, top, d.pinned, o.contact);
  PenalizedShell near(d.model, d.proxy, near_penalty_pairs(d.proxy, top, o.contact), o.contact);
  ObjectiveAtParameter near_at(near.energy, phi);
  EigenpairOptions eig;
  eig.count = 1;
  const Eigenpairs lowest = lowest_eigenpairs(near_at, top, pins, eig);
  ASSERT_LT(lowest.values[0], 0.0);
  // The mode, without the rigid motion the pins gave it, lies in a class odd under a mirror,
  // taken in the frame where the mirrors are the coordinate planes.
  const SymmetricSubspace& mirrors = *o.contact.symmetric_subspace;
  const RigidMotion frame = mirrors.aligning_motion(top);
  const Eigen::VectorXd mode = lowest.vectors.col(0);
  const ModeSymmetryClass c = mode_symmetry_class(
      mirrors.group(), without_rigid_velocity(frame.apply(top), frame.rotate(mode)));
  EXPECT_FALSE(c.trivial());
  EXPECT_GT(c.weight, 0.99);  // measured 0.9959
  Eigen::VectorXd y = top - (o.push * GrownDisc::kH / mode.cwiseAbs().maxCoeff()) * mode;
  const ContactRelaxation relaxed =
      relax_with_contact(d.model, phi, d.proxy, y, pins, o.contact, o.relaxation);
  ASSERT_TRUE(relaxed.relaxed) << relaxed.message;
  // It relaxes to a state of the search's energy, 1.4 % below the symmetric top. The two
  // differ by the relaxations' tolerance, the mode's part outside its class and the
  // nearest-triangle pair sets, which the mirrors do not map onto themselves
  // (docs/contact.md); measured 5.5e-9 relative with a tolerance 1e-7 of the force scale.
  EXPECT_NEAR(relaxed.energy, r.skewed_relaxed_energy, 1e-7 * r.skewed_relaxed_energy);
  EXPECT_LT(relaxed.energy, (1.0 - 1e-2) * r.symmetric_top_energy);
}

// grow_with_contact: natural steps through first contact, each a strict minimum of shell +
// penalty. Checked independently: the reduced Lagrangian Hessian of every contact state has no
// negative eigenvalue, and no vertex-triangle pair is closer than h - h/20.
TEST(ContactGrowth, StepsThroughContactAreStableAndKeepTheThickness) {
  GrownDisc& d = disc();
  ContactGrowthOptions o;
  o.contact = d.options();
  o.newton.gradient_tolerance = 1e-6 * d.model.natural_force_scale();
  o.newton.max_iterations = 200;
  o.max_step = 0.2;
  std::vector<ContactGrowthPoint> points;
  const ContactGrowthResult r = grow_with_contact(
      d.model, d.proxy, d.start(), GrownDisc::kStart, 6.4, d.pinned, o,
      [&](const ContactGrowthPoint& p) { points.push_back(p); });
  EXPECT_TRUE(r.reached_target) << r.message;
  ASSERT_FALSE(points.empty());
  EXPECT_NEAR(points.back().sample.sample.parameter, 6.4, 1e-12);
  int touching = 0;
  for (const ContactGrowthPoint& p : points) {
    const ContactBranchSample& s = p.sample;
    const ContactCandidates close =
        near_contact_pairs(d.proxy, s.sample.x, GrownDisc::kH - GrownDisc::kH / 20,
                           o.contact.exclusion_radius, NearPairSelection{false, false});
    EXPECT_TRUE(close.empty()) << "at phi_e = " << s.sample.parameter;
    if (s.active_pairs == 0) continue;
    ++touching;
    ObjectiveAtParameter energy(d.model, s.sample.parameter);
    ContactGapConstraints gaps(d.proxy, s.pairs, GrownDisc::kH, d.model.dimension());
    const ReducedInertia reduced =
        contact_constrained_inertia(energy, gaps, s.sample.x, s.forces, 0.0, d.pinned);
    EXPECT_EQ(reduced.negative, 0) << "at phi_e = " << s.sample.parameter;
  }
  EXPECT_GT(touching, 0) << "no contact below phi_e = 6.4";
}

// grow_with_contact carries from one step to the next only the state, the step and the pins,
// which each point reports: a path stopped at an intermediate excess angle and started again
// from its last point (what resuming a killed winding does) gives the same states, through
// first contact, as the path grown in one go.
TEST(ContactGrowth, APathSplitAtAnyStepGivesTheSameStates) {
  GrownDisc& d = disc();
  ContactGrowthOptions o;
  o.contact = d.options();
  o.contact.selection = NearPairSelection{false, false};  // as the econe_contact winding
  o.newton.gradient_tolerance = 1e-6 * d.model.natural_force_scale();
  o.newton.max_iterations = 200;
  o.max_step = 0.2;
  std::vector<ContactGrowthPoint> whole, split;
  const auto keep = [](std::vector<ContactGrowthPoint>& into) {
    return [&into](const ContactGrowthPoint& p) { into.push_back(p); };
  };
  const ContactGrowthResult r = grow_with_contact(d.model, d.proxy, d.start(), GrownDisc::kStart,
                                                  6.4, d.pinned, o, keep(whole));
  ASSERT_TRUE(r.reached_target) << r.message;
  // Stopped after its step to 6.2 (contact starts near 6.14), then grown on from that state.
  const ContactGrowthResult first = grow_with_contact(d.model, d.proxy, d.start(),
                                                      GrownDisc::kStart, 6.2, d.pinned, o,
                                                      keep(split));
  ASSERT_TRUE(first.reached_target) << first.message;
  // The state before the last, for the continued path's predictor: the first part's point
  // before its last (at 6.0).
  ASSERT_GE(split.size(), 2u);
  EXPECT_EQ(first.before_last.parameter, split[split.size() - 2].sample.sample.parameter);
  EXPECT_EQ(first.before_last.x, split[split.size() - 2].sample.sample.x);
  EXPECT_GT(r.predicted_steps, 0);
  // Started again as a resumed winding is: from the point's state, step and pins.
  ContactGrowthOptions again = o;
  again.initial_step = first.last.sample.sample.next_step;
  EXPECT_GT(again.initial_step, 0.0);
  EXPECT_LE(again.initial_step, o.max_step);
  EXPECT_FALSE(first.last.pins.empty());
  const ContactGrowthResult rest =
      grow_with_contact(d.model, d.proxy, first.last.sample.sample.x,
                        first.last.sample.sample.parameter, 6.4, first.last.pins, again,
                        keep(split), &first.before_last);
  ASSERT_TRUE(rest.reached_target) << rest.message;
  EXPECT_GT(r.predicted_steps, 0);
  ASSERT_EQ(split.size(), whole.size());
  int touching = 0;
  for (std::size_t k = 0; k < whole.size(); ++k) {
    const BranchSample& a = whole[k].sample.sample;
    const BranchSample& b = split[k].sample.sample;
    EXPECT_NEAR(a.parameter, b.parameter, 1e-12);  // 5 + 6 x 0.2 against 6.2
    EXPECT_LE((a.x - b.x).lpNorm<Eigen::Infinity>(), 1e-10 * GrownDisc::kH)
        << "at phi_e = " << a.parameter;
    EXPECT_EQ(whole[k].sample.active_pairs, split[k].sample.active_pairs);
    touching += whole[k].sample.active_pairs > 0;
  }
  EXPECT_GT(touching, 0) << "the split path never reached contact";
}

// The secant predictor changes where each step's minimisation starts, not where it ends: the
// path through first contact with and without it gives the same energies, the same states up
// to the nearly free turn of the pattern, and the same pairs in contact; it takes most steps
// from the prediction, and discards it where contact stops the sheet short of it.
TEST(ContactGrowth, ThePredictorMovesTheStartOfEachStepNotItsMinimum) {
  GrownDisc& d = disc();
  ContactGrowthOptions o;
  o.contact = d.options();
  o.contact.selection = NearPairSelection{false, false};
  o.newton.gradient_tolerance = 1e-6 * d.model.natural_force_scale();
  o.newton.max_iterations = 200;
  o.max_step = 0.1;  // predictions within the candidate margin (h), so that they are tried
  ContactGrowthOptions without = o;
  without.secant_predictor = false;
  std::vector<ContactGrowthPoint> a, b;
  const ContactGrowthResult with_it = grow_with_contact(
      d.model, d.proxy, d.start(), GrownDisc::kStart, 6.4, d.pinned, o,
      [&](const ContactGrowthPoint& p) { a.push_back(p); });
  const ContactGrowthResult plain = grow_with_contact(
      d.model, d.proxy, d.start(), GrownDisc::kStart, 6.4, d.pinned, without,
      [&](const ContactGrowthPoint& p) { b.push_back(p); });
  ASSERT_TRUE(with_it.reached_target) << with_it.message;
  ASSERT_TRUE(plain.reached_target) << plain.message;
  EXPECT_EQ(plain.predicted_steps + plain.discarded_predictions, 0);
  // Every step but the first (which has no state before it) may start from a prediction;
  // most do.
  EXPECT_LE(with_it.predicted_steps + with_it.discarded_predictions,
            with_it.steps - 1 + with_it.failed_steps);
  EXPECT_GE(with_it.predicted_steps, with_it.steps / 2);
  int flagged = 0;
  for (const ContactGrowthPoint& p : a) flagged += p.from_prediction;
  EXPECT_EQ(flagged, with_it.predicted_steps);
  ASSERT_EQ(a.size(), b.size());
  int touching = 0;
  double largest = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].sample.sample.parameter, b[k].sample.sample.parameter);
    largest = std::max(largest, (a[k].sample.sample.x - b[k].sample.sample.x).lpNorm<Eigen::Infinity>());
    const auto energy = [](const ContactBranchSample& s) {
      return s.stretching_energy + s.bending_energy + s.penalty_energy;
    };
    EXPECT_NEAR(energy(a[k].sample), energy(b[k].sample), 1e-10 * energy(b[k].sample))
        << "at phi_e = " << a[k].sample.sample.parameter;
    EXPECT_EQ(a[k].sample.active_pairs, b[k].sample.active_pairs);
    touching += a[k].sample.active_pairs > 0;
  }
  // The states differ along the nearly free turn of the fold pattern, which the Newton
  // decrement test leaves unconverged: 1.4e-3 h at most (measured; energies to 7e-13).
  EXPECT_LE(largest, 1e-2 * GrownDisc::kH);
  EXPECT_GT(touching, 0) << "the path never reached contact";

  // Each point's work adds up to the path's counts: its failed step sizes, its discarded
  // predictions, and at least one relaxation (one Newton solve) and one Cholesky test per
  // point; every Newton iteration factorises at least once, a stability test once more.
  int halvings = 0, discarded = 0;
  for (const ContactGrowthPoint& p : a) {
    const ContactStepWork& w = p.work;
    halvings += w.halvings;
    discarded += w.prediction_discarded;
    EXPECT_GE(w.tries, 1 + w.halvings + p.saddle_escapes);
    EXPECT_GE(w.solves, w.tries);
    EXPECT_GE(w.stability_tests, 1);
    EXPECT_GE(w.factorizations, w.newton_iterations + w.stability_tests);
    // An eigensolve follows a failed Cholesky test only; a push follows a saddle only.
    EXPECT_LE(w.eigen_solves, w.stability_tests);
    EXPECT_GE(w.eigen_solves, p.saddle_escapes);
  }
  EXPECT_EQ(halvings, with_it.failed_steps);
  // A point has at most one prediction, so this holds while no step size fails.
  if (with_it.failed_steps == 0) {
    EXPECT_EQ(discarded, with_it.discarded_predictions);
  }
}

TEST(ContactGrowth, BadOptionsAreRejectedByName) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.model.reference_positions();
  const auto message = [&](const ContactGrowthOptions& o) {
    try {
      grow_with_contact(d.model, d.proxy, x, 0.0, 0.1, d.pinned, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ContactGrowthOptions o;
  o.contact = d.options();
  o.initial_step = 2.0 * o.max_step;
  EXPECT_NE(message(o).find("initial_step"), std::string::npos);
  o.initial_step = -1.0;
  EXPECT_NE(message(o).find("initial_step"), std::string::npos);
  o.initial_step = 0.0;
  o.min_step = 2.0 * o.max_step;
  EXPECT_NE(message(o).find("min_step"), std::string::npos);
  o.min_step = 1e-3;
  o.max_saddle_escapes = -1;
  EXPECT_NE(message(o).find("max_saddle_escapes"), std::string::npos);
  o.max_saddle_escapes = 3;
  BranchSample previous;
  previous.x = x.head(x.size() - 3);
  previous.parameter = -0.1;
  try {
    grow_with_contact(d.model, d.proxy, x, 0.0, 0.1, d.pinned, o, {}, &previous);
    ADD_FAILURE() << "a previous state of the wrong size was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("previous state"), std::string::npos) << e.what();
  }
}

// ContactBranchOptions::phase_functional: every segment holds c . x at the value it had at the
// trace's start (each segment starts on the previous one's hyperplane), and each sample
// reports the force that holds it there, recomputed here from the gradient; without a
// functional that force is NaN.
TEST(ContactBranch, APhaseConditionHoldsItsValueOverEverySegmentAndReportsItsForce) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  const double phi0 = GrownDisc::kStart;
  // The out-of-plane displacement's sin(2 theta) component, weighted by the radius: zero
  // where the pattern has a mirror on the x axis, changed to first order by its turn.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(x.size());
  const Eigen::VectorXd& X = d.model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    c(3 * v + 2) = std::hypot(X(3 * v), X(3 * v + 1)) *
                   std::sin(2.0 * std::atan2(X(3 * v + 1), X(3 * v)) + 0.3);
  ContactBranchOptions o = d.options();
  o.arclength.max_steps = 5;
  o.steps_per_segment = 2;
  o.phase_functional = c;
  std::vector<ContactBranchSample> held;
  const ContactBranchTrace t =
      trace_contact_branch(d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0,
                           d.pinned, o, [&](const ContactBranchSample& s) { held.push_back(s); });
  EXPECT_EQ(t.steps, 5) << t.message;
  EXPECT_GE(t.cost.segments, 3);
  ASSERT_EQ(held.size(), 6u);
  const double value = c.dot(x);
  const Eigen::VectorXd unit = c.normalized();
  double largest = 0.0;
  for (const ContactBranchSample& s : held) {
    EXPECT_NEAR(c.dot(s.sample.x), value, 1e-12 * c.norm()) << "at phi_e " << s.sample.parameter;
    Eigen::VectorXd g;
    d.model.evaluate(s.sample.x, s.sample.parameter, &g, nullptr);
    const double mu = phase_multiplier(g, unit, d.pinned);
    EXPECT_NEAR(s.phase_force, std::abs(mu), 1e-9 * std::max(1.0, std::abs(mu)));
    // The gradient is mu c on the free dofs: an equilibrium up to the condition's force.
    for (const Eigen::Index i : d.pinned) g(i) = 0.0;
    Eigen::VectorXd free_unit = unit;
    for (const Eigen::Index i : d.pinned) free_unit(i) = 0.0;
    EXPECT_LT((g + mu * free_unit).lpNorm<Eigen::Infinity>(), 10 * o.arclength.gradient_tolerance);
    largest = std::max(largest, s.phase_force);
  }
  // The functional is not the pattern's own phase (its offset 0.3), so it holds a real force.
  EXPECT_GT(largest, 10 * o.arclength.gradient_tolerance);
  // Without a condition the samples say there is none.
  o.phase_functional.resize(0);
  o.arclength.max_steps = 1;
  trace_contact_branch(
      d.model, d.proxy, x, phi0, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, o,
      [&](const ContactBranchSample& s) { EXPECT_TRUE(std::isnan(s.phase_force)); });
}

TEST(ContactBranch, BadOptionsAreRejectedByName) {
  GrownDisc& d = disc();
  const Eigen::VectorXd x = d.model.reference_positions();
  const auto expect_message = [&](ContactBranchOptions o, const std::string& name) {
    try {
      trace_contact_branch(d.model, d.proxy, x, 0.0, Eigen::VectorXd::Zero(x.size()), 1.0,
                           d.pinned, o);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  ContactBranchOptions o = d.options();
  o.stiffness = 0.0;
  expect_message(o, "stiffness");
  o = d.options();
  o.contact_distance = -1.0;
  expect_message(o, "contact_distance");
  o = d.options();
  o.violation_tolerance = GrownDisc::kH;
  expect_message(o, "violation_tolerance");
  o = d.options();
  o.steps_per_segment = 0;
  expect_message(o, "steps_per_segment");
  o = d.options();
  o.repin_above_condition = -1.0;
  expect_message(o, "repin_above_condition");
  o = d.options();
  o.phase_functional = Eigen::VectorXd::Ones(x.size() - 1);
  expect_message(o, "phase_functional");
  o.phase_functional = Eigen::VectorXd::Zero(x.size());
  expect_message(o, "phase_functional");
  o.phase_functional = Eigen::VectorXd::Ones(x.size());
  o.symmetric_subspace =
      std::make_shared<const SymmetricSubspace>(two_mirror_subspace(d.model, 1e-9));
  expect_message(o, "phase_functional");
  o = d.options();
  o.repin_above_condition = 20.0;
  try {
    trace_contact_branch(d.model, d.proxy, x, 0.0, Eigen::VectorXd::Zero(x.size()), 1.0,
                         {d.pinned[0], d.pinned[1], d.pinned[2]}, o);
    ADD_FAILURE() << "no exception for three pins with repin_above_condition";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("six rigid-motion pins"), std::string::npos) << e.what();
  }
}

TEST(EconeBranches, BadSymmetricBranchBeforeTheStartAndCoincidenceRatioAreNamed) {
  GrownDisc& d = disc();
  EconeBranchOptions o;
  o.contact = d.options();
  o.symmetric_before = {{5.0, 1.0, 0.0}, {5.1, 1.0, 0.0}, {5.1, 1.0, 0.0}};
  try {
    // The options are checked before anything is traced: the flat disc serves as the start.
    trace_econe_branches(d.model, d.proxy, d.model.reference_positions(), 0.0, d.pinned, o);
    ADD_FAILURE() << "no exception for a repeated parameter";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "EconeBranchOptions::symmetric_before: join_branch_samples: earlier sample 2"),
              std::string::npos)
        << e.what();
  }
  o.symmetric_before.clear();
  o.coincidence_slope_ratio = 1.5;
  try {
    trace_econe_branches(d.model, d.proxy, d.model.reference_positions(), 0.0, d.pinned, o);
    ADD_FAILURE() << "no exception for coincidence_slope_ratio = 1.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("coincidence_slope_ratio"), std::string::npos) << e.what();
  }
}

// Choosing new rigid-motion pins at every segment (repin_above_condition = 1: every pin set
// exceeds it) changes the gauge, not the branch: the total energy of every sample lies on the
// branch traced with fixed pins (cubic Hermite interpolation between its samples with the
// exact slopes dE/dphi_e, whose own error at these steps is below 1e-9 relative).
TEST(ContactBranch, RepinningChangesTheGaugeNotTheBranch) {
  GrownDisc& d = disc();
  const Eigen::VectorXd& x = d.start();
  ContactBranchOptions o = d.options();
  o.arclength.parameter_max = 5.5;
  o.arclength.max_steps = 40;
  const auto trace = [&](double repin, int* repinnings) {
    ContactBranchOptions r = o;
    r.repin_above_condition = repin;
    std::vector<ContactBranchSample> samples;
    const ContactBranchTrace t = trace_contact_branch(
        d.model, d.proxy, x, GrownDisc::kStart, Eigen::VectorXd::Zero(x.size()), 1.0, d.pinned, r,
        [&](const ContactBranchSample& s) { samples.push_back(s); });
    EXPECT_TRUE(t.reached_bound) << t.message;
    *repinnings = t.cost.repinnings;
    return samples;
  };
  int fixed_repinnings = 0, repinnings = 0;
  const std::vector<ContactBranchSample> fixed = trace(0.0, &fixed_repinnings);
  const std::vector<ContactBranchSample> moved = trace(1.0, &repinnings);
  EXPECT_EQ(fixed_repinnings, 0);
  EXPECT_GE(repinnings, 2);
  ASSERT_GE(fixed.size(), 4u);
  const auto total = [](const ContactBranchSample& s) {
    return s.stretching_energy + s.bending_energy + s.penalty_energy;
  };
  int compared = 0;
  double worst = 0.0;
  for (const ContactBranchSample& m : moved) {
    const double phi = m.sample.parameter;
    for (std::size_t i = 0; i + 1 < fixed.size(); ++i) {
      const ContactBranchSample &a = fixed[i], &b = fixed[i + 1];
      const double pa = a.sample.parameter, pb = b.sample.parameter;
      if (!(phi >= pa && phi <= pb) || pb <= pa) continue;
      const double dp = pb - pa, t = (phi - pa) / dp;
      const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
      const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
      const double interpolated =
          h00 * total(a) + h10 * dp * a.energy_slope + h01 * total(b) + h11 * dp * b.energy_slope;
      worst = std::max(worst, std::abs(total(m) - interpolated) / std::abs(total(m)));
      EXPECT_EQ(m.sample.negative_eigenvalues, a.sample.negative_eigenvalues) << "phi_e " << phi;
      ++compared;
      break;
    }
  }
  EXPECT_GE(compared, 3);
  EXPECT_LT(worst, 1e-7);
  RecordProperty("repinned_energy_relative_error", std::to_string(worst));
  std::printf(
      "repinned trace: %d repinnings, %d samples compared, worst relative energy "
      "difference %.2e\n",
      repinnings, compared, worst);
}

}  // namespace
}  // namespace growshell
