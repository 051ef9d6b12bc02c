// The symmetric subspace of the disc's two mirrors and the energy restricted to it:
//  - the basis is orthonormal, spans exactly the states with both mirrors, and has a quarter
//    of the unknowns (up to the dofs on the mirror axes);
//  - rigid-motion pins: one for two mirrors (the translation along z), three for one mirror;
//  - aligning_motion brings a turned and moved symmetric state back into the subspace;
//  - the half turn about z: the subspace of the skewed cone's states, its two rigid pins and
//    its alignment;
//  - the restricted family's gradient and Hessian are the derivatives of its energy (finite
//    differences), and Q^T of the full ones;
//  - bad generators and meshes without the symmetry are named.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/continuation/symmetric_subspace_family.hpp"

namespace growshell {
namespace {

ShellModel small_disc() {
  DiscMeshOptions o;
  o.rings = 5;
  o.grading_exponent = 3.0;
  o.min_spacing = 0.05;
  ShellModelSettings s;
  s.thickness = constant_thickness(0.05);
  return ShellModel(make_disc_mesh(o), s);
}

Eigen::MatrixX3d as_rows(const Eigen::VectorXd& x) {
  return Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
}

/// A state with both mirrors: the reference lifted by z = a (x^2 - y^2) + b r^2 (an n = 2
/// saddle on a cone-like bowl), in-plane squeezed along x.
Eigen::VectorXd symmetric_state(const ShellModel& model, double a, double b) {
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double px = x(3 * v), py = x(3 * v + 1);
    x(3 * v) *= 1.0 - 0.05 * py * py;
    x(3 * v + 2) = a * (px * px - py * py) + b * (px * px + py * py);
  }
  return x;
}

/// x turned by 0.7 rad about a tilted axis and moved.
Eigen::VectorXd turned_and_moved(const Eigen::VectorXd& x) {
  RigidMotion turn;
  turn.rotation =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized())).toRotationMatrix();
  turn.translation = Eigen::Vector3d(0.3, -0.1, 0.2);
  return turn.apply(x);
}

TEST(SymmetricSubspace, TwoMirrorBasisIsOrthonormalAndSpansTheSymmetricStates) {
  ShellModel model = small_disc();
  const SymmetricSubspace sub = two_mirror_subspace(model, 1e-9);
  EXPECT_EQ(sub.group_order(), 4);
  EXPECT_EQ(sub.full_dimension(), model.dimension());
  const Eigen::MatrixXd Q = Eigen::MatrixXd(sub.basis());
  EXPECT_LT(
      (Q.transpose() * Q - Eigen::MatrixXd::Identity(Q.cols(), Q.cols())).cwiseAbs().maxCoeff(),
      1e-14);
  // Count: a generic vertex has an orbit of 4 (3 reduced dofs per orbit); one on a mirror
  // axis an orbit of 2 with its normal component odd (2 dofs); the centre keeps only z.
  const Eigen::VectorXd& X = model.reference_positions();
  int generic = 0, on_axis = 0, centre = 0;
  for (Eigen::Index v = 0; v < X.size() / 3; ++v) {
    const bool on_x = std::abs(X(3 * v + 1)) < 1e-12, on_y = std::abs(X(3 * v)) < 1e-12;
    if (on_x && on_y)
      ++centre;
    else if (on_x || on_y)
      ++on_axis;
    else
      ++generic;
  }
  EXPECT_EQ(centre, 1);
  EXPECT_EQ(sub.dimension(), 3 * generic / 4 + 2 * on_axis / 2 + 1);
  // A symmetric state is its own projection; breaking one mirror is measured.
  const Eigen::VectorXd x = symmetric_state(model, 0.2, 0.1);
  EXPECT_LT(sub.asymmetry(x), 1e-14);
  EXPECT_LT((sub.expand(sub.restrict_to(x)) - x).cwiseAbs().maxCoeff(), 1e-14);
  Eigen::VectorXd y = x;
  for (Eigen::Index v = 0; v < y.size() / 3; ++v) y(3 * v + 2) += 0.01 * y(3 * v + 1);  // tilt
  EXPECT_GT(sub.asymmetry(y), 1e-3);
  // Every state of the subspace has both mirrors.
  const Eigen::VectorXd random = sub.expand(Eigen::VectorXd::Random(sub.dimension()));
  const Eigen::MatrixX3d P = as_rows(X);
  EXPECT_LT(symmetry_defect(as_rows(random), mirror_symmetry(P, 0, 1e-9)), 1e-14);
  EXPECT_LT(symmetry_defect(as_rows(random), mirror_symmetry(P, 1, 1e-9)), 1e-14);
}

TEST(SymmetricSubspace, RigidMotionPinsAreThoseOfTheSymmetricRigidMotions) {
  ShellModel model = small_disc();
  const Eigen::VectorXd x = symmetric_state(model, 0.2, 0.1);
  const SymmetricSubspace both = two_mirror_subspace(model, 1e-9);
  ASSERT_EQ(both.rigid_motion_pins(x).size(), 1u);  // translation along z
  // The pinned reduced dof moves every vertex's z: its basis column has only z entries.
  const Eigen::Index pin = both.rigid_motion_pins(x)[0];
  for (Eigen::SparseMatrix<double>::InnerIterator it(both.basis(), pin); it; ++it)
    EXPECT_EQ(it.row() % 3, 2);
  const Eigen::MatrixX3d P = as_rows(model.reference_positions());
  const SymmetricSubspace one(P.rows(), {mirror_symmetry(P, 1, 1e-9)});
  EXPECT_EQ(one.group_order(), 2);
  // y -> -y keeps the translations along x and z and the rotation about y.
  EXPECT_EQ(one.rigid_motion_pins(x).size(), 3u);
  const SymmetricSubspace none(P.rows(), {});
  EXPECT_EQ(none.dimension(), model.dimension());
  EXPECT_EQ(none.rigid_motion_pins(x).size(), 6u);
}

TEST(SymmetricSubspace, RigidMotionPinsAreTheSameDofsAtEveryStateOfABranch) {
  // The translation along z gives every orbit of the same size the same component: the pin is
  // the lowest-index reduced dof among the largest orbits' z-dofs, whichever symmetric state
  // it is chosen at (a trace resumed from a later state pins what the trace that wrote it did).
  ShellModel model = small_disc();
  const SymmetricSubspace sub = two_mirror_subspace(model, 1e-9);
  Eigen::Index expected = -1, largest_orbit = 0;
  for (Eigen::Index j = 0; j < sub.dimension(); ++j) {
    Eigen::Index entries = 0;
    bool only_z = true;
    for (Eigen::SparseMatrix<double>::InnerIterator it(sub.basis(), j); it; ++it) {
      ++entries;
      only_z = only_z && it.row() % 3 == 2;
    }
    if (only_z && entries > largest_orbit) {
      largest_orbit = entries;
      expected = j;
    }
  }
  ASSERT_GE(expected, 0);
  for (const Eigen::VectorXd& x :
       {Eigen::VectorXd(model.reference_positions()), symmetric_state(model, 0.2, 0.1),
        symmetric_state(model, 0.5, -0.3), symmetric_state(model, 1e-6, 0.0),
        symmetric_state(model, -0.05, 0.4)}) {
    const std::vector<Eigen::Index> pins = sub.rigid_motion_pins(x);
    ASSERT_EQ(pins.size(), 1u);
    EXPECT_EQ(pins[0], expected);
  }
  // One mirror (the subspace of an odd number of folds): translations along x and z and the
  // rotation about y stay in it, three pins. The rotation's field depends on the state, and so
  // do the dofs rigid_motion_pins chooses at each; a trace's pins (trace_pins) are chosen on
  // the reference positions, the same at every state, and still hold all three motions there.
  const SymmetricSubspace one = mirror_subspace(model, {1}, 1e-9);
  const std::vector<Eigen::Index> at_flat = one.rigid_motion_pins(model.reference_positions());
  ASSERT_EQ(at_flat.size(), 3u);
  bool chosen_elsewhere = false;
  for (const Eigen::VectorXd& x :
       {symmetric_state(model, 0.2, 0.1), symmetric_state(model, 0.5, -0.3),
        symmetric_state(model, 1e-6, 0.0), symmetric_state(model, -0.05, 0.4)}) {
    chosen_elsewhere = chosen_elsewhere || one.rigid_motion_pins(x) != at_flat;
    const std::vector<Eigen::Index> pins = one.trace_pins(x);
    EXPECT_EQ(pins, at_flat);
    // The pinned rows of the symmetric rigid fields at x have full rank, well conditioned.
    Eigen::MatrixXd fields = rigid_velocity_fields(x);
    for (int k = 0; k < 6; ++k) fields.col(k).normalize();
    const Eigen::MatrixXd reduced = one.basis().transpose() * fields;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(reduced, Eigen::ComputeThinU);
    const Eigen::MatrixXd modes = svd.matrixU().leftCols(3);
    Eigen::MatrixXd pinned(3, 3);
    for (int r = 0; r < 3; ++r) pinned.row(r) = modes.row(pins[static_cast<std::size_t>(r)]);
    const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(pinned).singularValues();
    EXPECT_GT(sigma(2) / sigma(0), 0.05) << sigma.transpose();
  }
  EXPECT_TRUE(chosen_elsewhere);  // what the pin configuration is for
  // Without one, a trace pins what the state's own fields give; a configuration off the
  // subspace is refused.
  const Eigen::MatrixX3d P = as_rows(model.reference_positions());
  SymmetricSubspace bare(P.rows(), {mirror_symmetry(P, 1, 1e-9)});
  const Eigen::VectorXd x = symmetric_state(model, 0.5, -0.3);
  EXPECT_EQ(bare.trace_pins(x), bare.rigid_motion_pins(x));
  Eigen::VectorXd off = model.reference_positions();
  off(4) += 0.01;
  EXPECT_THROW(bare.set_pin_configuration(off), std::invalid_argument);
}

TEST(SymmetricSubspace, AligningMotionBringsATurnedSymmetricStateBack) {
  ShellModel model = small_disc();
  const SymmetricSubspace sub = two_mirror_subspace(model, 1e-9);
  const Eigen::VectorXd x = symmetric_state(model, 0.3, 0.2);
  const Eigen::VectorXd turned = turned_and_moved(x);
  ASSERT_GT(sub.asymmetry(turned), 0.1);
  const RigidMotion back = sub.aligning_motion(turned);
  const Eigen::VectorXd aligned = back.apply(turned);
  EXPECT_LT(sub.asymmetry(aligned), 1e-12);
  EXPECT_LT((back.apply_inverse(aligned) - turned).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(back.rotation.determinant(), 1.0, 1e-12);
  // The shape is unchanged: the aligned state is x up to a motion that keeps the mirrors
  // (here at most a translation along z and half turns), so pairwise distances agree.
  EXPECT_NEAR((aligned.segment<3>(0) - aligned.segment<3>(30)).norm(),
              (x.segment<3>(0) - x.segment<3>(30)).norm(), 1e-12);
  // Generators that are neither mirrors nor a single half turn are not aligned.
  const Eigen::MatrixX3d P = as_rows(model.reference_positions());
  const SymmetricSubspace mixed(P.rows(),
                                {half_turn_symmetry(P, 2, 1e-9), mirror_symmetry(P, 1, 1e-9)});
  EXPECT_THROW(mixed.aligning_motion(x), std::invalid_argument);
}

/// A state with the half turn about z and neither mirror, as a skewed cone: the saddle and
/// bowl of symmetric_state plus an xy term, and an in-plane twist growing with r^2.
Eigen::VectorXd skewed_state(const ShellModel& model) {
  Eigen::VectorXd x = symmetric_state(model, 0.3, 0.2);
  const Eigen::VectorXd& X = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double px = X(3 * v), py = X(3 * v + 1), r2 = px * px + py * py;
    x(3 * v) -= 0.1 * py * r2;
    x(3 * v + 1) += 0.1 * px * r2;
    x(3 * v + 2) += 0.15 * px * py;
  }
  return x;
}

TEST(SymmetricSubspace, HalfTurnSubspaceHoldsTheSkewedStatesAndAlignsThem) {
  ShellModel model = small_disc();
  const SymmetricSubspace sub = half_turn_subspace(model, 1e-9);
  EXPECT_EQ(sub.group_order(), 2);
  // Every vertex but the centre has an orbit of 2 (3 reduced dofs per orbit); the centre keeps
  // only z.
  const Eigen::Index nv = model.dimension() / 3;
  EXPECT_EQ(sub.dimension(), 3 * (nv - 1) / 2 + 1);
  const Eigen::VectorXd x = skewed_state(model);
  EXPECT_LT(sub.asymmetry(x), 1e-14);
  EXPECT_GT(two_mirror_subspace(model, 1e-9).asymmetry(x), 1e-3);  // it breaks the mirrors
  // The translation along z and the rotation about z stay in it: two pins, chosen on the
  // trace's start (no pin configuration).
  EXPECT_EQ(sub.rigid_motion_pins(x).size(), 2u);
  EXPECT_EQ(sub.trace_pins(x), sub.rigid_motion_pins(x));
  // Turned about a tilted axis and moved, it is brought back onto the half turn about z.
  const Eigen::VectorXd turned = turned_and_moved(x);
  ASSERT_GT(sub.asymmetry(turned), 0.1);
  const RigidMotion back = sub.aligning_motion(turned);
  EXPECT_LT(sub.asymmetry(back.apply(turned)), 1e-12);
  EXPECT_LT(sub.aligned_asymmetry(turned), 1e-12);
  EXPECT_NEAR(back.rotation.determinant(), 1.0, 1e-12);
  // A state without the half turn stays off it in every frame.
  Eigen::VectorXd odd = x;  // z odd in x: not a rigid tilt, and the half turn flips it
  const Eigen::VectorXd& X = model.reference_positions();
  for (Eigen::Index v = 0; v < nv; ++v) odd(3 * v + 2) += 0.05 * X(3 * v) * X(3 * v) * X(3 * v);
  EXPECT_GT(sub.aligned_asymmetry(odd), 1e-3);
  // As a start of a trace: the turned state may start one in the subspace, the odd one not,
  // and the note names the branch and both distances.
  EXPECT_EQ(subspace_start_mismatch(sub, turned, 1e-6, "the skewed branch"), "");
  const std::string note = subspace_start_mismatch(sub, odd, 1e-6, "the skewed branch");
  EXPECT_EQ(note.rfind("the skewed branch is traced in the full space: its start is ", 0), 0u)
      << note;
  EXPECT_NE(note.find("(more than 1e-06 m)"), std::string::npos) << note;
}

TEST(SymmetricSubspace, RestrictedFamilyHasTheDerivativesOfItsEnergy) {
  ShellModel model = small_disc();
  const SymmetricSubspace sub = two_mirror_subspace(model, 1e-9);
  const ShellModel& full = model;
  SymmetricSubspaceFamily family(full, sub);
  const double phi_e = 1.5;
  const Eigen::VectorXd y = sub.restrict_to(symmetric_state(model, 0.2, 0.3));
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H = family.hessian_pattern();
  const double e = family.evaluate(y, phi_e, &g, &H);
  Eigen::VectorXd gf;
  Eigen::SparseMatrix<double> Hf = full.hessian_pattern();
  EXPECT_DOUBLE_EQ(e, full.evaluate(sub.expand(y), phi_e, &gf, &Hf));
  EXPECT_LT((g - Eigen::VectorXd(sub.basis().transpose() * gf)).cwiseAbs().maxCoeff(),
            1e-12 * gf.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd Hd =
      Eigen::MatrixXd(Eigen::SparseMatrix<double>(H.selfadjointView<Eigen::Upper>()));
  const Eigen::MatrixXd Hfd =
      Eigen::MatrixXd(Eigen::SparseMatrix<double>(Hf.selfadjointView<Eigen::Upper>()));
  const Eigen::MatrixXd Q = Eigen::MatrixXd(sub.basis());
  EXPECT_LT((Hd - Q.transpose() * Hfd * Q).cwiseAbs().maxCoeff(),
            1e-12 * Hfd.cwiseAbs().maxCoeff());
  // Central differences along a random direction: O(eps^2) error, eps = 1e-5.
  Eigen::VectorXd d = Eigen::VectorXd::Random(y.size());
  d /= d.norm();
  const double eps = 1e-5;
  Eigen::VectorXd gp, gm;
  const double ep = family.evaluate(y + eps * d, phi_e, &gp, nullptr);
  const double em = family.evaluate(y - eps * d, phi_e, &gm, nullptr);
  EXPECT_NEAR((ep - em) / (2 * eps), g.dot(d), 1e-7 * g.norm());
  EXPECT_LT(((gp - gm) / (2 * eps) - Hd * d).norm(), 1e-6 * (Hd * d).norm());
  // d(gradient)/d(phi_e): central difference in the parameter.
  const Eigen::VectorXd dg = family.gradient_parameter_derivative(y, phi_e);
  family.evaluate(y, phi_e + eps, &gp, nullptr);
  family.evaluate(y, phi_e - eps, &gm, nullptr);
  EXPECT_LT(((gp - gm) / (2 * eps) - dg).norm(), 1e-6 * dg.norm());
}

TEST(SymmetricSubspace, BadGeneratorsAndMeshesWithoutTheMirrorsAreNamed) {
  ShellModel model = small_disc();
  const Eigen::MatrixX3d P = as_rows(model.reference_positions());
  VertexSymmetry bad = mirror_symmetry(P, 0, 1e-9);
  bad.image[0] = bad.image[1];
  EXPECT_THROW(SymmetricSubspace(P.rows(), {bad}), std::invalid_argument);
  EXPECT_THROW(SymmetricSubspace(P.rows() + 1, {mirror_symmetry(P, 0, 1e-9)}),
               std::invalid_argument);
  const SymmetricSubspace other(P.rows() - 1, {});
  EXPECT_THROW(SymmetricSubspaceFamily(model, other), std::invalid_argument);
  // A disc centred off the origin has its mirrors elsewhere.
  DiscMeshOptions o;
  o.rings = 5;
  o.center = {0.1, 0.0};
  ShellModelSettings s;
  s.thickness = constant_thickness(0.05);
  s.growth.center = Eigen::Vector3d(0.1, 0.0, 0.0);
  const ShellModel moved(make_disc_mesh(o), s);
  try {
    two_mirror_subspace(moved, 1e-9);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("does not have this symmetry"), std::string::npos)
        << e.what();
  }
  // The annulus grid splits every cell along the same diagonal: its vertices have the mirrors,
  // its triangulation does not.
  AnnulusMeshOptions a;
  a.radial_layers = 4;
  const ShellModel ring(make_annulus_mesh(a), s);
  try {
    two_mirror_subspace(ring, 1e-9);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("triangulation"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace growshell
