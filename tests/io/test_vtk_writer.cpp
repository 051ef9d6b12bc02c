// write_vtu: both encodings hold every array exactly. The appended raw file is read back here
// as a VTK reader does (the offset of each DataArray into the <AppendedData> block, a UInt64
// byte count, the little-endian bytes) and the ASCII file by parsing its numbers; a field of
// the wrong length is refused, naming it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "libshell/io/vtk_writer.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;

SurfaceSnapshot two_triangles() {
  SurfaceSnapshot s;
  s.points.resize(4, 3);
  s.points << 0.0, 0.0, 0.0,  //
      1.0, 0.0, 1.0 / 3.0,    // not exact in decimal: the round trip must still be exact
      0.0, 1.0, -2.5e-300,    //
      1.0, 1.0, 6.02214076e23;
  s.triangles.resize(2, 3);
  s.triangles << 0, 1, 2,  //
      1, 3, 2;
  s.cell_data.emplace_back("U_b", Eigen::Vector2d(0.1, -7.0 / 9.0));
  Eigen::VectorXd p(4);
  p << 1.0, 2.0, std::nextafter(3.0, 4.0), -0.0;
  s.point_data.emplace_back("flag", p);
  return s;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The DataArray tag that holds `key` (a Name="..." or NumberOfComponents="3").
std::string tag_with(const std::string& xml, const std::string& key) {
  const std::size_t at = xml.find(key);
  EXPECT_NE(at, std::string::npos) << key;
  const std::size_t begin = xml.rfind("<DataArray", at);
  return xml.substr(begin, xml.find('>', at) - begin + 1);
}

/// The bytes of an appended array, from its offset="N".
template <class T>
std::vector<T> appended_array(const std::string& file, const std::string& key) {
  const std::string tag = tag_with(file, key);
  std::smatch m;
  EXPECT_TRUE(std::regex_search(tag, m, std::regex("offset=\"([0-9]+)\""))) << tag;
  const std::size_t start = file.find('_', file.find("<AppendedData encoding=\"raw\">")) + 1;
  const std::size_t at = start + std::stoull(m[1]);
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, file.data() + at, sizeof bytes);
  std::vector<T> out(bytes / sizeof(T));
  std::memcpy(out.data(), file.data() + at + sizeof bytes, bytes);
  return out;
}

/// The numbers inside an ASCII array.
std::vector<double> ascii_array(const std::string& file, const std::string& key) {
  const std::size_t open = file.find('>', file.find(key)) + 1;
  std::istringstream text(file.substr(open, file.find("</DataArray>", open) - open));
  std::vector<double> out;
  for (double v; text >> v;) out.push_back(v);
  return out;
}

class VtkWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("growshell_vtk_" + std::to_string(::getpid()) + "_" + info->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(VtkWriterTest, AppendedRawHoldsEveryArrayExactly) {
  const SurfaceSnapshot s = two_triangles();
  write_vtu((dir_ / "s.vtu").string(), s);  // the default encoding
  const std::string file = read_file(dir_ / "s.vtu");
  EXPECT_NE(file.find("version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\""),
            std::string::npos);
  EXPECT_NE(file.find("NumberOfPoints=\"4\" NumberOfCells=\"2\""), std::string::npos);
  const std::vector<double> points = appended_array<double>(file, "NumberOfComponents=\"3\"");
  ASSERT_EQ(points.size(), 12u);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(points[3 * i + c], s.points(i, c));
  EXPECT_EQ(appended_array<std::int64_t>(file, "Name=\"connectivity\""),
            (std::vector<std::int64_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(appended_array<std::int64_t>(file, "Name=\"offsets\""), (std::vector<std::int64_t>{3, 6}));
  EXPECT_EQ(appended_array<std::uint8_t>(file, "Name=\"types\""), (std::vector<std::uint8_t>{5, 5}));
  const std::vector<double> ub = appended_array<double>(file, "Name=\"U_b\"");
  ASSERT_EQ(ub.size(), 2u);
  EXPECT_EQ(ub[1], -7.0 / 9.0);
  const std::vector<double> flag = appended_array<double>(file, "Name=\"flag\"");
  ASSERT_EQ(flag.size(), 4u);
  EXPECT_EQ(flag[2], std::nextafter(3.0, 4.0));
  EXPECT_TRUE(std::signbit(flag[3]));
  EXPECT_EQ(file.substr(file.size() - 30), "\n  </AppendedData>\n</VTKFile>\n");
}

TEST_F(VtkWriterTest, AsciiHoldsEveryArrayExactlyAndIsLarger) {
  const SurfaceSnapshot s = two_triangles();
  write_vtu((dir_ / "a.vtu").string(), s, VtuEncoding::Ascii);
  const std::string file = read_file(dir_ / "a.vtu");
  EXPECT_EQ(file.find("AppendedData"), std::string::npos);
  const std::vector<double> points = ascii_array(file, "NumberOfComponents=\"3\"");
  ASSERT_EQ(points.size(), 12u);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(points[3 * i + c], s.points(i, c));
  EXPECT_EQ(ascii_array(file, "Name=\"connectivity\""), (std::vector<double>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(ascii_array(file, "Name=\"types\""), (std::vector<double>{5, 5}));
  EXPECT_EQ(ascii_array(file, "Name=\"U_b\"")[1], -7.0 / 9.0);
  EXPECT_EQ(ascii_array(file, "Name=\"flag\"")[2], std::nextafter(3.0, 4.0));
  // A strip of 400 triangles: ASCII is larger (1.28 times here: each double takes about 20
  // characters for 8 bytes, while the small integers of the connectivity print short).
  SurfaceSnapshot strip;
  strip.points.resize(402, 3);
  strip.triangles.resize(400, 3);
  for (int i = 0; i < 402; ++i) strip.points.row(i) << i / 7.0, (i % 2) / 3.0, std::sqrt(i + 0.5);
  for (int i = 0; i < 400; ++i) strip.triangles.row(i) << i, i + 1, i + 2;
  strip.cell_data.emplace_back("U_b", Eigen::VectorXd::LinSpaced(400, 1.0 / 3.0, 2.0 / 3.0));
  write_vtu((dir_ / "strip_ascii.vtu").string(), strip, VtuEncoding::Ascii);
  write_vtu((dir_ / "strip_raw.vtu").string(), strip, VtuEncoding::AppendedRaw);
  EXPECT_GT(fs::file_size(dir_ / "strip_ascii.vtu"), fs::file_size(dir_ / "strip_raw.vtu"));
}

TEST_F(VtkWriterTest, AFieldOfTheWrongLengthIsRefusedByName) {
  SurfaceSnapshot s = two_triangles();
  s.cell_data.emplace_back("short", Eigen::VectorXd::Zero(1));
  try {
    write_vtu((dir_ / "bad.vtu").string(), s);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "cell field 'short' has 1 values, expected 2");
  }
  EXPECT_FALSE(fs::exists(dir_ / "bad.vtu"));  // refused before the file was opened
  EXPECT_THROW(write_vtu((dir_ / "no_such_dir" / "x.vtu").string(), two_triangles()),
               std::runtime_error);
}

}  // namespace
}  // namespace growshell
