// cone_mirror_subspace: the two-fold cone is traced among the states with its mirrors on the
// meshes that have them (rings, and Gmsh's sector reflected: gmsh_d4), and in the full space,
// with a note naming why, on the unsymmetric Gmsh mesh. On gmsh_d4 the energy has the mesh's
// symmetry group: a state and its image under each generator of D4 have the same energy, to
// rounding, so the subspace traced there is one the discrete physics keeps.
#include "studies/cone_mirror_subspace.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/mesh/gmsh_disc_mesh.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "libshell/mesh/vertex_symmetry.hpp"

namespace growshell {
namespace {

ShellModelSettings settings() {
  ShellModelSettings s;
  s.thickness = constant_thickness(0.04);
  return s;
}

ShellModel coarse_gmsh_model(bool dihedral) {
  GmshDiscMeshOptions o;
  o.size_slope = 0.2;
  o.size_floor = 0.04;
  o.dihedral_symmetry = dihedral;
  return ShellModel(make_gmsh_disc_mesh(o), settings());
}

TEST(ConeMirrorSubspace, FoundOnMeshesWithTheMirrorsAndNotWithout) {
  RingDiscMeshOptions rings;
  rings.size_slope = 0.2;
  rings.size_floor = 0.04;
  const ShellModel rings_model(make_ring_disc_mesh(rings), settings());
  const ConeSubspaceChoice on_rings = cone_mirror_subspace(rings_model, 1.0, 2);
  EXPECT_NE(on_rings.subspace, nullptr);
  EXPECT_EQ(on_rings.note, "");

  const ConeSubspaceChoice on_d4 = cone_mirror_subspace(coarse_gmsh_model(true), 1.0, 2);
  EXPECT_NE(on_d4.subspace, nullptr);
  EXPECT_EQ(on_d4.note, "");

  const ConeSubspaceChoice on_gmsh = cone_mirror_subspace(coarse_gmsh_model(false), 1.0, 2);
  EXPECT_EQ(on_gmsh.subspace, nullptr);
  EXPECT_NE(on_gmsh.note.find("full space"), std::string::npos) << on_gmsh.note;
}

// A state with no symmetry at all (a tilted, twisted, stretched disc), its images under the
// mirror y -> -y and the quarter turn about z (the generators of D4), vertices permuted by the
// mesh's vertex maps: the energies at phi_e = 3 agree to 1e-12 relative, though the state's
// own energy is far from any symmetric state's.
TEST(ConeMirrorSubspace, TheEnergyOnGmshD4HasTheMeshSymmetry) {
  const ShellModel model = coarse_gmsh_model(true);
  const Eigen::VectorXd X = model.reference_positions();
  const Eigen::Index n = X.size() / 3;
  Eigen::VectorXd x(X.size());
  for (Eigen::Index v = 0; v < n; ++v) {
    const double a = X(3 * v), b = X(3 * v + 1);
    x(3 * v) = 1.1 * a + 0.2 * b * b;
    x(3 * v + 1) = 0.9 * b + 0.1 * a * b;
    x(3 * v + 2) = 0.3 * a * a - 0.1 * b + 0.2 * a * b * b;
  }
  Eigen::MatrixX3d points(n, 3);
  for (Eigen::Index v = 0; v < n; ++v) points.row(v) = X.segment<3>(3 * v).transpose();
  const double phi = 3.0;
  const double e = model.evaluate(x, phi, nullptr, nullptr);
  ASSERT_GT(e, 0.0);

  const VertexSymmetry mirror = mirror_symmetry(points, 1, 1e-12);
  const LinearVertexSymmetry turn = quarter_turn_symmetry(points, 1e-12);
  const Eigen::Matrix3d mirror_matrix = mirror.signs.asDiagonal();
  for (const auto& [matrix, image] :
       {std::pair{mirror_matrix, mirror.image}, std::pair{turn.matrix, turn.image}}) {
    Eigen::VectorXd y(x.size());
    for (Eigen::Index v = 0; v < n; ++v)
      y.segment<3>(3 * image[static_cast<std::size_t>(v)]) = matrix * x.segment<3>(3 * v);
    EXPECT_NEAR(model.evaluate(y, phi, nullptr, nullptr), e, 1e-12 * e);
  }
}

}  // namespace
}  // namespace growshell
