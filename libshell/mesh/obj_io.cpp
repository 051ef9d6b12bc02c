#include "libshell/mesh/obj_io.hpp"

#include <charconv>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "libshell/mesh/mesh_error.hpp"

namespace growshell {

namespace {

class LineError {
 public:
  LineError(const std::string& path, long line)
      : prefix_(path + ", line " + std::to_string(line) + ": ") {}
  [[noreturn]] void raise(const std::string& what) const { throw MeshError(prefix_ + what); }

 private:
  std::string prefix_;
};

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

double parse_double(std::string_view token, const LineError& error) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) {
    error.raise("cannot read the coordinate '" + std::string(token) + "'");
  }
  return value;
}

// Returns the 0-based vertex index of a face entry "i", "i/t", "i//n" or "i/t/n".
int parse_face_index(std::string_view token, long num_vertices, const LineError& error) {
  const std::string_view index_text = token.substr(0, token.find('/'));
  long index = 0;
  const auto [end, ec] =
      std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
  if (ec != std::errc() || end != index_text.data() + index_text.size() || index == 0) {
    error.raise("cannot read the face entry '" + std::string(token) +
                "' (expected a nonzero vertex index)");
  }
  const long zero_based = index > 0 ? index - 1 : num_vertices + index;
  if (zero_based < 0 || zero_based >= num_vertices) {
    error.raise("vertex index " + std::to_string(index) +
                " is out of range: " + std::to_string(num_vertices) + " vertices defined so far");
  }
  return static_cast<int>(zero_based);
}

}  // namespace

TriangleMesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MeshError("cannot open OBJ file '" + path + "'");
  std::vector<double> coordinates;
  std::vector<int> indices;
  std::string line;
  long line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const LineError error(path, line_number);
    const auto tokens = split_whitespace(line);
    if (tokens.empty() || tokens[0].front() == '#') continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "v") {
      // A 4th (w) or colour components (x y z r g b) are tolerated and dropped.
      if (tokens.size() != 4 && tokens.size() != 5 && tokens.size() != 7) {
        error.raise("a vertex line needs 3 coordinates, found " +
                    std::to_string(tokens.size() - 1));
      }
      for (int k = 1; k <= 3; ++k) coordinates.push_back(parse_double(tokens[k], error));
      for (std::size_t k = 4; k < tokens.size(); ++k) parse_double(tokens[k], error);
    } else if (keyword == "f") {
      if (tokens.size() != 4) {
        error.raise("only triangles are supported, but this face has " +
                    std::to_string(tokens.size() - 1) + " vertices");
      }
      const long nv = static_cast<long>(coordinates.size() / 3);
      for (int k = 1; k <= 3; ++k) indices.push_back(parse_face_index(tokens[k], nv, error));
    } else if (keyword == "vn" || keyword == "vt" || keyword == "vp" || keyword == "o" ||
               keyword == "g" || keyword == "s" || keyword == "usemtl" || keyword == "mtllib" ||
               keyword == "l") {
      continue;
    } else {
      error.raise("unknown OBJ statement '" + std::string(keyword) + "'");
    }
  }
  if (in.bad()) throw MeshError("error while reading OBJ file '" + path + "'");

  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(coordinates.size() / 3), 3);
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    for (int k = 0; k < 3; ++k) mesh.vertices(v, k) = coordinates[3 * v + k];
  }
  mesh.faces.resize(static_cast<Eigen::Index>(indices.size() / 3), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) mesh.faces(f, k) = indices[3 * f + k];
  }
  return mesh;
}

void write_obj(const std::string& path, const TriangleMesh& mesh) {
  std::ofstream out(path);
  if (!out) throw MeshError("cannot open OBJ file '" + path + "' for writing");
  out << "# growshell control mesh: " << mesh.vertices.rows() << " vertices, " << mesh.faces.rows()
      << " faces\n";
  char buffer[64];
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
    out << 'v';
    for (int k = 0; k < 3; ++k) {
      // Shortest round-trip representation: from_chars recovers the identical double.
      const auto result = std::to_chars(buffer, buffer + sizeof(buffer), mesh.vertices(v, k));
      out << ' ';
      out.write(buffer, result.ptr - buffer);
    }
    out << '\n';
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    out << "f " << mesh.faces(f, 0) + 1 << ' ' << mesh.faces(f, 1) + 1 << ' '
        << mesh.faces(f, 2) + 1 << '\n';
  }
  out.flush();
  if (!out) throw MeshError("error while writing OBJ file '" + path + "'");
}

}  // namespace growshell
