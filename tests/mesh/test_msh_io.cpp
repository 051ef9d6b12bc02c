// read_msh: hand-written Gmsh 4.1 and 2.2 ASCII files (triangles kept, other elements and
// sections skipped, orientation made counter-clockwise), errors naming the line for malformed
// input, and a deterministic mutation fuzz that must only ever produce MeshError.
#include "libshell/mesh/msh_io.hpp"

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "libshell/mesh/mesh_error.hpp"
#include "tests/support/expect_contains.hpp"

namespace growshell {
namespace {

// Unit square split into two triangles, the second written clockwise; plus a point, a line
// and a quadrangle element, physical names and entities. Node 7 is used by no triangle.
const char* const kMsh41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "sheet"
$EndPhysicalNames
$Entities
1 0 1 0
1 0 0 0 0
1 0 0 0 1 1 0 0
1 0 0 0 1 1 0 0 0
$EndEntities
$Nodes
3 6 3 20
0 1 0 1
7
5 5 0
1 1 1 2
3
20
0 0 0 0.0
1 0 0 1.0
2 1 0 3
10
4
11
0 1 0
1 1 0
0.5 2 0
$EndNodes
$Elements
4 5 1 9
0 1 15 1
1 7
1 1 1 1
2 3 20
2 1 2 2
3 3 20 11
4 3 11 4
2 1 3 1
5 3 20 4 10
$EndElements
)";

const char* const kMsh22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Comments
anything at all $Nodes
$EndComments
$Nodes
6
3 0 0 0
20 1 0 0
10 0 1 0
4 1 1 0
11 0.5 2 0
7 5 5 0
$EndNodes
$Elements
5
1 15 2 0 1 7
2 1 2 0 1 3 20
3 2 2 0 1 3 20 11
4 2 2 0 1 3 11 4
5 3 2 0 1 3 20 4 10
$EndElements
)";

TriangleMesh read_text(const std::string& text) {
  std::istringstream in(text);
  return read_msh(in, "test.msh");
}

std::string error_of(const std::string& text) {
  try {
    read_text(text);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "<no MeshError thrown>";
}

void expect_square(const TriangleMesh& m) {
  // Used nodes in increasing tag: 3, 4, 11, 20 -> vertices 0..3.
  Eigen::MatrixX3d v(4, 3);
  v << 0, 0, 0, 1, 1, 0, 0.5, 2, 0, 1, 0, 0;
  EXPECT_EQ(m.vertices, v);
  Eigen::MatrixX3i f(2, 3);
  f << 0, 3, 2,  // (3, 20, 11): counter-clockwise as written
      0, 1, 2;   // (3, 11, 4) is clockwise: nodes 2 and 3 swapped to (3, 4, 11)
  EXPECT_EQ(m.faces, f);
}

TEST(MshIo, ReadsFormat41) { expect_square(read_text(kMsh41)); }

TEST(MshIo, ReadsFormat22) { expect_square(read_text(kMsh22)); }

TEST(MshIo, MissingFileIsNamed) {
  try {
    read_msh("/nonexistent/dir/x.msh");
    FAIL() << "no error";
  } catch (const MeshError& e) {
    EXPECT_CONTAINS(e.what(), "cannot open .msh file '/nonexistent/dir/x.msh'");
  }
}

TEST(MshIo, MalformedInputNamesTheLine) {
  const std::string good = kMsh41;
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const std::size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  EXPECT_CONTAINS(error_of(""), "no $MeshFormat section");
  EXPECT_CONTAINS(error_of("hello\n"), "test.msh, line 1: expected a section");
  EXPECT_CONTAINS(error_of(replaced("4.1 0 8", "4.1 1 8")), "line 2: binary .msh files");
  EXPECT_CONTAINS(error_of(replaced("4.1 0 8", "4.0 0 8")), "line 2: unsupported .msh format");
  EXPECT_CONTAINS(error_of(replaced("0 1 0\n1 1 0", "0 1 x\n1 1 0")),
                  "line 28: cannot read coordinate z from 'x'");
  EXPECT_CONTAINS(error_of(replaced("0 1 0\n1 1 0", "0 1 nan\n1 1 0")),
                  "line 28: coordinate z is not finite");
  EXPECT_CONTAINS(error_of(replaced("3 6 3 20", "3 7 3 20")),
                  "the node blocks hold 6 nodes, the header says 7");
  EXPECT_CONTAINS(error_of(replaced("3 6 3 20", "3 5 3 20")), "more nodes than the header");
  EXPECT_CONTAINS(error_of(replaced("4 5 1 9", "4 4 1 9")), "more elements than numElements");
  EXPECT_CONTAINS(error_of(replaced("\n10\n4\n11", "\n10\n3\n11")), "node tag 3 repeated");
  EXPECT_CONTAINS(error_of(replaced("3 3 20 11", "3 3 20 99")),
                  "line 39: the triangle refers to node 99, which is not in $Nodes");
  EXPECT_CONTAINS(error_of(replaced("3 3 20 11", "3 3 20 20")), "line 39: triangle repeats a node");
  EXPECT_CONTAINS(error_of(replaced("3 3 20 11", "3 3 20")), "line 39: expected a triangle");
  EXPECT_CONTAINS(error_of(replaced("3 3 20 11", "3 3 20 -11")), "node tag -11 is out of range");
  EXPECT_CONTAINS(error_of(replaced("3 3 20 11", "3 3 20 99999999999999999999")),
                  "cannot read node tag");
  EXPECT_CONTAINS(error_of(replaced("$EndElements\n", "")), "unexpected end of file");
  EXPECT_CONTAINS(error_of(replaced("$EndNodes", "$EndNode")), "expected $EndNodes");
  EXPECT_CONTAINS(error_of(replaced("$EndPhysicalNames\n", "")), "expected $EndPhysicalNames");
  EXPECT_CONTAINS(error_of(replaced("2 1 2 2", "2 1 15 2")), "no triangles");
  EXPECT_CONTAINS(error_of(good + good), "second $MeshFormat section");
  const std::string v22 = kMsh22;
  EXPECT_CONTAINS(error_of(v22.substr(0, v22.find("10 0 1 0"))),
                  "unexpected end of file after line 10, expected a node");
  EXPECT_CONTAINS(error_of(v22.substr(0, v22.find("1 0 0\n10 0 1 0"))),
                  "line 10: expected a node: tag x y z (4 fields), found 1 fields");
  EXPECT_CONTAINS(error_of("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n0\n$EndElements\n"),
                  "no $Nodes section");
  EXPECT_CONTAINS(error_of("$Nodes\n0\n$EndNodes\n"), "$Nodes before $MeshFormat");
}

// Random mutations of both files (characters replaced by ones that matter to the parser,
// lines dropped or duplicated, truncation): every outcome is a mesh or a MeshError.
TEST(MshIo, MutatedFilesGiveMeshErrorOrAMeshNeverAnythingElse) {
  std::mt19937 rng(12345);
  const std::string alphabet = "0123456789 -+.eE$\n\t\rxNodesElementsEnd";
  int errors = 0;
  int meshes = 0;
  for (const std::string& base : {std::string(kMsh41), std::string(kMsh22)}) {
    for (int trial = 0; trial < 3000; ++trial) {
      std::string s = base;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !s.empty(); ++e) {
        const std::size_t at = rng() % s.size();
        switch (rng() % 4) {
          case 0: s[at] = alphabet[rng() % alphabet.size()]; break;
          case 1: s.erase(at, 1 + rng() % 12); break;
          case 2: s.insert(at, s.substr(rng() % s.size(), 1 + rng() % 30)); break;
          default: s.resize(at); break;
        }
      }
      try {
        read_text(s);
        ++meshes;
      } catch (const MeshError&) {
        ++errors;
      } catch (const std::exception& ex) {
        ADD_FAILURE() << "not a MeshError: " << ex.what() << "\ninput:\n" << s;
      }
    }
  }
  EXPECT_GT(errors, 3000);  // most mutations break the file
  EXPECT_GT(meshes, 10);    // some only touch coordinates or skipped parts
}

}  // namespace
}  // namespace growshell
