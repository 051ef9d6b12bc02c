// ElementLatticeSampling: the cached lattice map gives the limit positions of
// evaluate_limit_surface at every lattice point of every element, regular and irregular (rings
// disc: valence-8 centre, 5s and 7s at the doublings; ghost layer), for a random state; rows are
// ordered element by element, i-major; bad input is refused by name.
#include "libshell/subdivision/element_lattice_sampling.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <string>

#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/mesh/ring_disc_mesh.hpp"
#include "libshell/subdivision/limit_surface.hpp"

namespace growshell {
namespace {

TEST(ElementLatticeSampling, EqualsTheLimitSurfaceAtEveryLatticePoint) {
  RingDiscMeshOptions o;
  o.size_slope = 0.25;
  o.size_floor = 0.05;
  const TriangleMesh mesh = make_ring_disc_mesh(o);
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  ASSERT_GT(patches.num_irregular(), 0);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 0.1);
  Eigen::MatrixX3d x = mesh.vertices;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int c = 0; c < 3; ++c) x(i, c) += normal(rng);
  for (const int n : {1, 3}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const ElementLatticeSampling lattice(patches, mesh.vertices, n);
    EXPECT_EQ(lattice.points_per_element(), (n + 1) * (n + 2) / 2);
    const Eigen::MatrixX3d p = lattice.positions(x);
    // The flat, vertex-major form of the same state, and the reference computed once.
    Eigen::VectorXd flat(3 * x.rows());
    for (Eigen::Index v = 0; v < x.rows(); ++v) flat.segment<3>(3 * v) = x.row(v).transpose();
    EXPECT_EQ(lattice.state_positions(flat), p);
    EXPECT_EQ(lattice.reference_positions(), lattice.positions(mesh.vertices));
    ASSERT_EQ(p.rows(), static_cast<Eigen::Index>(patches.patch.size()) * lattice.points_per_element());
    Eigen::Index expected_row = 0;
    double worst = 0.0;
    for (std::size_t e = 0; e < patches.patch.size(); ++e) {
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n - i; ++j) {
          const auto E = static_cast<Eigen::Index>(e);
          EXPECT_EQ(lattice.row(E, i, j), expected_row++);
          const Eigen::Vector3d direct =
              evaluate_limit_surface(x, patches.patch[e], static_cast<double>(i) / n,
                                     static_cast<double>(j) / n)
                  .position;
          worst = std::max(worst, (p.row(lattice.row(E, i, j)).transpose() - direct).norm());
        }
      }
    }
    // Positions of O(1) m summed in another order: a few ulps.
    EXPECT_LT(worst, 1e-14);
  }
}

TEST(ElementLatticeSampling, RejectsBadInputByName) {
  RingDiscMeshOptions o;
  o.size_floor = 0.2;
  const TriangleMesh mesh = make_ring_disc_mesh(o);
  const ElementPatches patches = build_element_patches(MeshTopology(mesh));
  try {
    ElementLatticeSampling(patches, mesh.vertices, 0);
    FAIL() << "n = 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("n = 0 subdivisions per edge must be >= 1"), std::string::npos);
  }
  const ElementLatticeSampling lattice(patches, mesh.vertices, 2);
  try {
    lattice.positions(Eigen::MatrixX3d::Zero(mesh.vertices.rows() - 1, 3));
    FAIL() << "a state of the wrong size accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("control points for a mesh of"), std::string::npos);
  }
  try {
    lattice.state_positions(Eigen::VectorXd::Zero(3 * mesh.vertices.rows() + 1));
    FAIL() << "a flat state of the wrong size accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("entries for a mesh of"), std::string::npos);
  }
}

}  // namespace
}  // namespace growshell
