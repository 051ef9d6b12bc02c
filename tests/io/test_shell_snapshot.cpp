// shell_snapshot: the cell fields are the state's energy densities at the excess angle passed
// (the flat sheet is free of strain at phi_e = 0 and stretched once grown), each element's
// value on each of its sub-cells, and the refined sampling has (r+1)(r+2)/2 points and r^2
// cells per element.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "libshell/mesh/disc_mesh.hpp"

namespace growshell {
namespace {

ShellModel small_disc() {
  DiscMeshOptions o;
  o.rings = 4;
  ShellModelSettings s;
  s.thickness = constant_thickness(0.05);
  return ShellModel(make_disc_mesh(o), s);
}

const Eigen::VectorXd& field(const SurfaceSnapshot& s, const std::string& name) {
  for (const auto& [key, values] : s.cell_data)
    if (key == name) return values;
  throw std::runtime_error("no cell field " + name);
}

TEST(ShellSnapshot, DensitiesAreTheStatesAtTheGivenExcessAngle) {
  const ShellModel model = small_disc();
  const Eigen::VectorXd& X = model.reference_positions();
  const SurfaceSnapshot rest = shell_snapshot(model, X, 0.0, 1);
  EXPECT_LT(field(rest, "stretching_density").cwiseAbs().maxCoeff(), 1e-20);
  EXPECT_LT(field(rest, "bending_density").cwiseAbs().maxCoeff(), 1e-20);
  const double phi = 1.5;
  const SurfaceSnapshot grown = shell_snapshot(model, X, phi, 1);
  const Eigen::VectorXd expected = model.element_stretching_density(X, phi);
  ASSERT_EQ(field(grown, "stretching_density").size(), expected.size());
  EXPECT_GT(expected.maxCoeff(), 1e-4);  // the flat sheet grown by 1.5 rad is strained
  EXPECT_EQ((field(grown, "stretching_density") - expected).cwiseAbs().maxCoeff(), 0.0);
}

TEST(ShellSnapshot, RefinedSamplingHasEveryElementsSubTriangulation) {
  const ShellModel model = small_disc();
  const Eigen::VectorXd& X = model.reference_positions();
  const int r = 3;
  const SurfaceSnapshot s = shell_snapshot(model, X, 0.5, r);
  const Eigen::Index n = model.num_elements();
  EXPECT_EQ(s.points.rows(), n * (r + 1) * (r + 2) / 2);
  EXPECT_EQ(s.triangles.rows(), n * r * r);
  const Eigen::VectorXd per_element = model.element_stretching_density(X, 0.5);
  const Eigen::VectorXd& cells = field(s, "stretching_density");
  const Eigen::VectorXd& ids = field(s, "element");
  for (Eigen::Index c = 0; c < cells.size(); ++c) {
    ASSERT_EQ(ids(c), static_cast<double>(c / (r * r)));
    ASSERT_EQ(cells(c), per_element(c / (r * r)));
  }
  // Every sampled point lies on the flat reference sheet.
  EXPECT_LT(s.points.col(2).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(shell_snapshot(model, X, 0.5, 0), std::invalid_argument);
}

}  // namespace
}  // namespace growshell
