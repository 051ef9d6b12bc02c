#include "libshell/mesh/obj_io.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "libshell/mesh/disc_mesh.hpp"
#include "libshell/mesh/mesh_error.hpp"
#include "tests/support/expect_contains.hpp"

namespace growshell {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(testing::TempDir()) / ("growshell_test_obj_io_" + name)).string();
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string read_error(const std::string& path) {
  try {
    read_obj(path);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "<no MeshError thrown>";
}

TEST(ObjIo, RoundTripIsBitExact) {
  TriangleMesh mesh = make_disc_mesh({.radius = 1.0 / 3.0,
                                      .rings = 6,
                                      .grading_exponent = 2.7,
                                      .min_spacing = 0.01,
                                      .center = {0.1, -std::numbers::pi}});
  // Awkward values: signed zero, subnormal, extremes, and values with 17 significant digits.
  mesh.vertices(0, 2) = -0.0;
  mesh.vertices(1, 2) = std::numeric_limits<double>::denorm_min();
  mesh.vertices(2, 2) = std::numeric_limits<double>::max();
  mesh.vertices(3, 2) = -std::numeric_limits<double>::min();
  mesh.vertices(4, 2) = 0.1 + 0.2;
  mesh.vertices(5, 2) = std::nextafter(1.0, 2.0);
  const std::string path = temp_path("round_trip.obj");
  write_obj(path, mesh);
  const TriangleMesh back = read_obj(path);
  ASSERT_EQ(back.vertices.rows(), mesh.vertices.rows());
  ASSERT_EQ(back.faces.rows(), mesh.faces.rows());
  EXPECT_EQ(std::memcmp(back.vertices.data(), mesh.vertices.data(),
                        sizeof(double) * static_cast<std::size_t>(mesh.vertices.size())),
            0);
  EXPECT_TRUE(back.faces == mesh.faces);
  EXPECT_TRUE(std::signbit(back.vertices(0, 2)));
}

TEST(ObjIo, ReadsFaceEntryFormsAndIgnoresOtherStatements) {
  const std::string path = write_text("forms.obj",
                                      "# comment\n"
                                      "mtllib x.mtl\n"
                                      "o thing\n"
                                      "g group\n"
                                      "s off\n"
                                      "v 0 0 0\n"
                                      "v 1 0 0\n"
                                      "v 0 1 0\n"
                                      "v 1 1 0.5\r\n"
                                      "vt 0 0\n"
                                      "vn 0 0 1\n"
                                      "\n"
                                      "   \t\n"
                                      "f 1 2 3\n"
                                      "f 2/1 4/1 3/1\n"
                                      "f 1//1 2//1 3//1\n"
                                      "f 1/1/1 2/1/1 3/1/1\n"
                                      "f -3 -1 -2\n");
  const TriangleMesh mesh = read_obj(path);
  ASSERT_EQ(mesh.vertices.rows(), 4);
  ASSERT_EQ(mesh.faces.rows(), 5);
  EXPECT_EQ(mesh.vertices(3, 2), 0.5);
  EXPECT_EQ(mesh.faces.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.faces.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(mesh.faces.row(2), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.faces.row(3), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.faces.row(4), Eigen::RowVector3i(1, 3, 2));
}

TEST(ObjIo, MalformedFilesNameFileAndLine) {
  const std::string header = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  struct Case {
    const char* name;
    std::string body;
    const char* expected;
  };
  const Case cases[] = {
      {"quad.obj", header + "f 1 2 4 3\n", "line 5: only triangles are supported"},
      {"two_coords.obj", "v 0 0 0\nv 1 2\n", "line 2: a vertex line needs 3 coordinates"},
      {"bad_number.obj", "v 0 0 0\nv 1 x 2\n", "line 2: cannot read the coordinate 'x'"},
      {"out_of_range.obj", header + "\nf 1 2 9\n", "line 6: vertex index 9 is out of range"},
      {"negative_out_of_range.obj", header + "f -5 1 2\n", "line 5: vertex index -5"},
      {"zero_index.obj", header + "f 0 1 2\n", "line 5: cannot read the face entry '0'"},
      {"garbage_index.obj", header + "f 1 2a 3\n", "line 5: cannot read the face entry '2a'"},
      {"forward_reference.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n",
       "line 2: vertex index 2 is out of range"},
      {"unknown.obj", header + "curv 1 2\n", "line 5: unknown OBJ statement 'curv'"},
  };
  for (const Case& c : cases) {
    const std::string path = write_text(c.name, c.body);
    const std::string message = read_error(path);
    EXPECT_CONTAINS(message, path + ", " + c.expected);
  }
  EXPECT_CONTAINS(read_error(temp_path("does_not_exist.obj")),
                  "cannot open OBJ file '" + temp_path("does_not_exist.obj") + "'");
}

}  // namespace
}  // namespace growshell
