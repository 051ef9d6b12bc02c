// The elements around each element: on a regular strip an interior element touches twelve
// others at its corners, and the relation is symmetric.
#include <gtest/gtest.h>

#include <algorithm>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_topology.hpp"
#include "libshell/subdivision/element_neighbourhood.hpp"

namespace growshell {
namespace {

TEST(ElementNeighbourhood, AnInteriorElementOfARegularStripTouchesTwelveOthersAndTheRelationIsSymmetric) {
  StripMeshOptions o;
  o.cells_x = 8;
  o.cells_y = 6;
  const TriangleMesh mesh = make_strip_mesh(o);
  const MeshTopology topology(mesh);
  const ElementPatches patches = build_element_patches(topology);
  const auto around = element_neighbourhoods(topology, patches);
  ASSERT_EQ(around.size(), patches.patch.size());
  int interior = 0;
  for (std::size_t e = 0; e < around.size(); ++e) {
    const auto& set = around[e];
    EXPECT_TRUE(std::is_sorted(set.begin(), set.end()));
    EXPECT_TRUE(std::binary_search(set.begin(), set.end(), static_cast<int>(e)));
    EXPECT_LE(set.size(), 13U);
    if (set.size() == 13U) ++interior;
    for (int f : set) {
      const auto& back = around[static_cast<std::size_t>(f)];
      EXPECT_TRUE(std::binary_search(back.begin(), back.end(), static_cast<int>(e)));
    }
  }
  // Elements with no corner on the strip's edge: (cells_x - 2) (cells_y - 2) squares, two each.
  EXPECT_EQ(interior, 2 * (o.cells_x - 2) * (o.cells_y - 2));
}

}  // namespace
}  // namespace growshell
