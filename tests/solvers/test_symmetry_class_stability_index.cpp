// The stability index class by class on a small disc with both mirrors (x -> -x, y -> -y):
//  - the groups and their classes: orthonormal bases that split the space, each class mapped
//    onto itself with its character's sign, and a Hessian block-diagonal over them at a state
//    with the mirrors;
//  - on the flat disc grown past the n = 2 and n = 3 buckling thresholds, the count is the full
//    Hessian's (six pins) and each unstable mode sits in the class its pattern's symmetry gives
//    (cos 2t keeps both mirrors, sin 2t breaks both, cos 3t and sin 3t one each);
//  - the count orthogonal to a direction drops by one for a direction along an unstable mode
//    and not for one along a stable mode; a direction spread over two classes is refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "solvers/stability/hessian_negative_count.hpp"
#include "solvers/stability/subspace_rigid_motions.hpp"
#include "solvers/stability/symmetry_class_stability_index.hpp"
#include "solvers/stability/vertex_symmetry_group.hpp"
#include "support/vertex_symmetry_action.hpp"
#include "tests/support/two_mirrors.hpp"

namespace growshell {
namespace {

using test_support::apply;

constexpr double kThickness = 0.05;

ShellModel disc() {
  DiscMeshOptions o;
  o.rings = 6;
  ShellModelSettings s;
  s.thickness = constant_thickness(kThickness);
  return ShellModel(make_disc_mesh(o), s);
}

Eigen::MatrixX3d as_rows(const Eigen::VectorXd& x) {
  return Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
}

/// The two mirrors of the model's reference.
VertexSymmetryGroup reference_two_mirrors(const ShellModel& model) {
  return test_support::two_mirrors(as_rows(model.reference_positions()));
}

std::vector<Eigen::Index> six_pins(const ShellModel& model) {
  return mirror_axis_pinned_dofs(as_rows(model.reference_positions()), model.sheet_vertices(),
                                 Eigen::Vector3d::Zero());
}

/// The flat disc at excess angle phi_e, relaxed in its plane: Newton from the reference, whose
/// steps stay in the plane (the gradient has no out-of-plane part there, and the Hessian does
/// not couple the two), so it reaches the flat equilibrium however unstable it is.
Eigen::VectorXd flat_equilibrium(const ShellModel& model, double phi_e) {
  ObjectiveAtParameter at(model, phi_e);
  NewtonOptions o;
  o.gradient_tolerance = 1e-10 * model.natural_force_scale();
  const NewtonResult r = NewtonSolver(o).minimize(at, model.reference_positions(), six_pins(model));
  EXPECT_EQ(r.status, NewtonStatus::Converged);
  double lift = 0.0;
  for (Eigen::Index v = 0; v < r.x.size() / 3; ++v) lift = std::max(lift, std::abs(r.x(3 * v + 2)));
  EXPECT_LT(lift, 1e-12);
  return r.x;
}

TEST(VertexSymmetryGroup, ClassesOfTwoMirrorsSplitTheSpaceWithTheirSigns) {
  const ShellModel model = disc();
  const VertexSymmetryGroup group = reference_two_mirrors(model);
  EXPECT_EQ(group.order(), 4);
  const std::vector<std::vector<int>> characters = group.splitting_characters();
  ASSERT_EQ(characters.size(), 4u);
  EXPECT_EQ(characters.front(), (std::vector<int>{1, 1}));
  Eigen::MatrixXd all(model.dimension(), 0);
  for (const std::vector<int>& chi : characters) {
    const Eigen::MatrixXd Q(group.class_basis(chi));
    for (std::size_t s = 0; s < 2; ++s)
      for (Eigen::Index j = 0; j < Q.cols(); ++j)
        EXPECT_LT((apply(group.generators()[s], Q.col(j)) - chi[s] * Q.col(j)).cwiseAbs().maxCoeff(),
                  1e-15);
    all.conservativeResize(Eigen::NoChange, all.cols() + Q.cols());
    all.rightCols(Q.cols()) = Q;
  }
  // Together the classes are an orthonormal basis of the whole space.
  ASSERT_EQ(all.cols(), model.dimension());
  EXPECT_LT((all.transpose() * all - Eigen::MatrixXd::Identity(all.cols(), all.cols()))
                .cwiseAbs()
                .maxCoeff(),
            1e-14);
}

TEST(VertexSymmetryGroup, SignsThatAreNoCharacterAndGroupsThatDoNotSplitAreRefused) {
  const ShellModel model = disc();
  const Eigen::MatrixX3d P = as_rows(model.reference_positions());
  const VertexSymmetry mx = mirror_symmetry(P, 0, 1e-9), my = mirror_symmetry(P, 1, 1e-9);
  const VertexSymmetry turn = half_turn_symmetry(P, 2, 1e-9);
  // The half turn is the product of the mirrors: its sign must be theirs.
  const VertexSymmetryGroup dependent(P.rows(), {mx, my, turn});
  EXPECT_EQ(dependent.order(), 4);
  EXPECT_TRUE(dependent.is_character({-1, -1, 1}));
  EXPECT_FALSE(dependent.is_character({-1, -1, -1}));
  EXPECT_THROW(dependent.class_basis({-1, -1, -1}), std::invalid_argument);
  EXPECT_THROW(dependent.splitting_characters(), std::invalid_argument);
  // A three-cycle of vertices is no involution.
  VertexSymmetry cycle;
  for (int v = 0; v < P.rows(); ++v) cycle.image.push_back(v);
  cycle.image[0] = 1;
  cycle.image[1] = 2;
  cycle.image[2] = 0;
  const VertexSymmetryGroup three(P.rows(), {cycle});
  EXPECT_EQ(three.order(), 3);
  try {
    three.splitting_characters();
    ADD_FAILURE() << "a three-cycle was taken for an involution";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("generator 0 is not an involution"), std::string::npos)
        << e.what();
  }
  VertexSymmetry short_map = mx;
  short_map.image.pop_back();
  EXPECT_THROW(VertexSymmetryGroup(P.rows(), {short_map}), std::invalid_argument);
}

TEST(SymmetryClassStabilityIndex, TheHessianOfAStateWithTheMirrorsIsBlockDiagonalOverTheClasses) {
  const ShellModel model = disc();
  const VertexSymmetryGroup group = reference_two_mirrors(model);
  Eigen::VectorXd x = model.reference_positions();
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
    const double px = x(3 * v), py = x(3 * v + 1);
    x(3 * v) *= 1.0 - 0.05 * py * py;
    x(3 * v + 2) = 0.2 * (px * px - py * py) + 0.3 * (px * px + py * py);
  }
  Eigen::SparseMatrix<double> H = model.hessian_pattern();
  model.evaluate(x, 1.5, nullptr, &H);
  const Eigen::MatrixXd dense(Eigen::SparseMatrix<double>(H.selfadjointView<Eigen::Upper>()));
  const double scale = dense.cwiseAbs().maxCoeff();
  const std::vector<std::vector<int>> characters = group.splitting_characters();
  for (std::size_t c = 0; c < characters.size(); ++c)
    for (std::size_t d = 0; d < c; ++d) {
      const Eigen::MatrixXd Qc(group.class_basis(characters[c]));
      const Eigen::MatrixXd Qd(group.class_basis(characters[d]));
      EXPECT_LT((Qc.transpose() * dense * Qd).cwiseAbs().maxCoeff(), 1e-11 * scale)
          << "classes " << c << " and " << d;
    }
  // The rigid motions of such a state split over the classes: the translation along z keeps
  // both mirrors, those along x and y (with the turns about y and x) break one each, and the
  // turn about z breaks both.
  std::vector<std::size_t> rigid;
  for (const std::vector<int>& chi : characters)
    rigid.push_back(subspace_rigid_motions(group.class_basis(chi), x).pins.size());
  EXPECT_EQ(rigid, (std::vector<std::size_t>{1, 2, 2, 1}));
}

class GrownFlatDisc : public ::testing::Test {
 protected:
  GrownFlatDisc() : model_(disc()), group_(reference_two_mirrors(model_)) {}
  ShellModel model_;
  VertexSymmetryGroup group_;
};

TEST_F(GrownFlatDisc, CountIsTheFullHessiansWithEachModeInTheClassOfItsPattern) {
  SymmetryClassStabilityIndex index(model_, group_);
  HessianNegativeCount full(model_, six_pins(model_));
  // Below the n = 2 threshold (c2 h^2 = 0.0265 for a free rim), between it and n = 3's
  // (c3 h^2 = 0.0528), between n = 3's and n = 4's (c4 h^2 = 0.0862), and past n = 4's, whose
  // cos 4t keeps both mirrors and sin 4t breaks both. This mesh's thresholds lie within 0.005
  // of the free rim's (scanned in steps of 0.005: 0.025-0.03, 0.05-0.055, 0.08-0.085).
  struct Case {
    double phi_e;
    std::vector<int> classes;  // (+,+), (-,+), (+,-), (-,-): signs under x -> -x, y -> -y
  };
  for (const Case& c : {Case{0.015, {0, 0, 0, 0}}, Case{0.04, {1, 0, 0, 1}},
                        Case{0.07, {1, 1, 1, 1}}, Case{0.1, {2, 1, 1, 2}}}) {
    const Eigen::VectorXd x = flat_equilibrium(model_, c.phi_e);
    EXPECT_EQ(index.at(x, c.phi_e), full.at(x, c.phi_e)) << "phi_e " << c.phi_e;
    EXPECT_EQ(index.class_negatives(), c.classes) << "phi_e " << c.phi_e;
  }
}

/// The eigenvector of the `which`-th eigenvalue (ascending) of class c's block, pins removed,
/// as a full state.
Eigen::VectorXd class_mode(const ShellModel& model, const VertexSymmetryGroup& group,
                           const std::vector<int>& chi, const Eigen::VectorXd& x, double phi_e,
                           Eigen::Index which, double* eigenvalue) {
  const Eigen::SparseMatrix<double> q = group.class_basis(chi);
  const std::vector<Eigen::Index> pins = subspace_rigid_motions(q, x).pins;
  Eigen::SparseMatrix<double> H = model.hessian_pattern();
  model.evaluate(x, phi_e, nullptr, &H);
  const Eigen::MatrixXd Q(q);
  Eigen::MatrixXd block =
      Q.transpose() *
      Eigen::MatrixXd(Eigen::SparseMatrix<double>(H.selfadjointView<Eigen::Upper>())) * Q;
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < block.rows(); ++i)
    if (std::find(pins.begin(), pins.end(), i) == pins.end()) free.push_back(i);
  Eigen::MatrixXd reduced(free.size(), free.size());
  for (std::size_t i = 0; i < free.size(); ++i)
    for (std::size_t j = 0; j < free.size(); ++j) reduced(i, j) = block(free[i], free[j]);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(reduced);
  *eigenvalue = eig.eigenvalues()(which);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(block.rows());
  for (std::size_t i = 0; i < free.size(); ++i) y(free[i]) = eig.eigenvectors()(i, which);
  return Q * y;
}

TEST_F(GrownFlatDisc, CountOrthogonalToADirectionDropsForAnUnstableModeOnly) {
  const double phi_e = 0.04;
  const Eigen::VectorXd x = flat_equilibrium(model_, phi_e);
  SymmetryClassStabilityIndex index(model_, group_);
  EXPECT_THROW(index.negative_orthogonal_to(x), std::logic_error);
  const int total = index.at(x, phi_e);
  ASSERT_EQ(total, 2);
  const std::vector<int> both_odd{-1, -1};
  double lowest = 0.0, highest = 0.0;
  const Eigen::VectorXd unstable = class_mode(model_, group_, both_odd, x, phi_e, 0, &lowest);
  ASSERT_LT(lowest, 0.0);
  EXPECT_EQ(index.negative_orthogonal_to(unstable), total - 1);
  const Eigen::VectorXd stable = class_mode(model_, group_, both_odd, x, phi_e, 5, &highest);
  ASSERT_GT(highest, 0.0);
  EXPECT_EQ(index.negative_orthogonal_to(stable), total);
  // Spread over two classes: which class's count should lose the mode is not defined.
  const std::vector<int> symmetric{1, 1};
  const Eigen::VectorXd other = class_mode(model_, group_, symmetric, x, phi_e, 0, &lowest);
  EXPECT_THROW(index.negative_orthogonal_to(unstable + other), std::invalid_argument);
  EXPECT_THROW(index.negative_orthogonal_to(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}

TEST_F(GrownFlatDisc, AStateWithoutTheMirrorsIsRefused) {
  SymmetryClassStabilityIndex index(model_, group_);
  Eigen::VectorXd x = model_.reference_positions();
  x(3 * 7 + 2) += 1e-3;  // one vertex lifted alone
  try {
    index.at(x, 0.02);
    ADD_FAILURE() << "an asymmetric state was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("off the group's symmetric subspace"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace growshell
