#include "libshell/mesh/msh_io.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "libshell/mesh/mesh_error.hpp"

namespace growshell {

namespace {

// Reads lines, keeps the line number and splits lines into whitespace-separated tokens.
class LineReader {
 public:
  LineReader(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {}

  // Next line (without '\r'); false at the end of the input.
  bool next() {
    if (!std::getline(in_, line_)) {
      if (in_.bad()) throw MeshError(source_ + ": read error after line " + std::to_string(number_));
      return false;
    }
    ++number_;
    if (!line_.empty() && line_.back() == '\r') line_.pop_back();
    tokens_.clear();
    std::size_t i = 0;
    const std::string_view s(line_);
    while (i < s.size()) {
      while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
      std::size_t j = i;
      while (j < s.size() && s[j] != ' ' && s[j] != '\t' && s[j] != '\r') ++j;
      if (j > i) tokens_.push_back(s.substr(i, j - i));
      i = j;
    }
    return true;
  }

  // Next line, which must exist; `what` says what was expected.
  void require(const std::string& what) {
    if (!next())
      throw MeshError(source_ + ": unexpected end of file after line " + std::to_string(number_) +
                      ", expected " + what);
  }

  const std::vector<std::string_view>& tokens() const { return tokens_; }
  const std::string& line() const { return line_; }
  long number() const { return number_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw MeshError(source_ + ", line " + std::to_string(number_) + ": " + what);
  }

  void expect_tokens(std::size_t n, const std::string& what) const {
    if (tokens_.size() != n)
      fail("expected " + what + " (" + std::to_string(n) + " fields), found " +
           std::to_string(tokens_.size()) + " fields");
  }

  long long integer(std::size_t k, long long lo, long long hi, const std::string& what) const {
    if (k >= tokens_.size()) fail("missing " + what);
    const std::string_view t = tokens_[k];
    long long value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || end != t.data() + t.size())
      fail("cannot read " + what + " from '" + std::string(t) + "'");
    if (value < lo || value > hi)
      fail(what + " " + std::to_string(value) + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    return value;
  }

  double real(std::size_t k, const std::string& what) const {
    if (k >= tokens_.size()) fail("missing " + what);
    const std::string_view t = tokens_[k];
    double value = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || end != t.data() + t.size())
      fail("cannot read " + what + " from '" + std::string(t) + "'");
    if (!std::isfinite(value)) fail(what + " is not finite");
    return value;
  }

  // Reads lines up to "$End<name>"; the current line is the section's opening line.
  void skip_section(const std::string& name) {
    const std::string end = "$End" + name;
    for (;;) {
      require(end);
      if (!tokens_.empty() && tokens_[0] == end) return;
    }
  }

  // The current line must be exactly "$End<name>".
  void expect_end(const std::string& name) {
    require("$End" + name);
    if (tokens_.size() != 1 || tokens_[0] != "$End" + name)
      fail("expected $End" + name + ", found '" + line_ + "'");
  }

 private:
  std::istream& in_;
  std::string source_;
  std::string line_;
  std::vector<std::string_view> tokens_;
  long number_ = 0;
};

constexpr long long kMaxCount = 1'000'000'000'000LL;  // counts are only compared, never allocated
constexpr long long kMaxTag = 0x7fffffffffffffffLL;

struct Contents {
  std::map<long long, Eigen::Vector3d> nodes;
  std::vector<std::array<long long, 3>> triangles;
  std::vector<long> triangle_lines;
};

void add_node(LineReader& r, Contents& c, long long tag, const Eigen::Vector3d& x) {
  if (!c.nodes.emplace(tag, x).second) r.fail("node tag " + std::to_string(tag) + " repeated");
}

void add_triangle(LineReader& r, Contents& c, long long a, long long b, long long d) {
  if (a == b || b == d || a == d) r.fail("triangle repeats a node");
  c.triangles.push_back({a, b, d});
  c.triangle_lines.push_back(r.number());
}

void read_nodes_41(LineReader& r, Contents& c) {
  r.require("the $Nodes header");
  r.expect_tokens(4, "numEntityBlocks numNodes minNodeTag maxNodeTag");
  const long long blocks = r.integer(0, 0, kMaxCount, "numEntityBlocks");
  const long long total = r.integer(1, 0, kMaxCount, "numNodes");
  long long read = 0;
  for (long long b = 0; b < blocks; ++b) {
    r.require("a node block header");
    r.expect_tokens(4, "a node block header entityDim entityTag parametric numNodesInBlock");
    const int dim = static_cast<int>(r.integer(0, 0, 3, "entityDim"));
    const bool parametric = r.integer(2, 0, 1, "parametric flag") == 1;
    const long long count = r.integer(3, 0, kMaxCount, "numNodesInBlock");
    if (count > total - read) r.fail("the node blocks hold more nodes than the header's numNodes");
    std::vector<long long> tags;
    for (long long k = 0; k < count; ++k) {
      r.require("a node tag");
      r.expect_tokens(1, "a node tag");
      tags.push_back(r.integer(0, 1, kMaxTag, "node tag"));
    }
    const std::size_t fields = 3 + (parametric ? static_cast<std::size_t>(dim) : 0);
    for (long long k = 0; k < count; ++k) {
      r.require("node coordinates");
      r.expect_tokens(fields, "node coordinates");
      add_node(r, c, tags[static_cast<std::size_t>(k)],
               {r.real(0, "coordinate x"), r.real(1, "coordinate y"), r.real(2, "coordinate z")});
    }
    read += count;
  }
  if (read != total)
    r.fail("the node blocks hold " + std::to_string(read) + " nodes, the header says " +
           std::to_string(total));
  r.expect_end("Nodes");
}

void read_elements_41(LineReader& r, Contents& c) {
  r.require("the $Elements header");
  r.expect_tokens(4, "numEntityBlocks numElements minElementTag maxElementTag");
  const long long blocks = r.integer(0, 0, kMaxCount, "numEntityBlocks");
  const long long total = r.integer(1, 0, kMaxCount, "numElements");
  long long read = 0;
  for (long long b = 0; b < blocks; ++b) {
    r.require("an element block header");
    r.expect_tokens(4, "an element block header entityDim entityTag elementType numElementsInBlock");
    r.integer(0, 0, 3, "entityDim");
    const long long type = r.integer(2, 1, 1000, "elementType");
    const long long count = r.integer(3, 0, kMaxCount, "numElementsInBlock");
    if (count > total - read) r.fail("the element blocks hold more elements than numElements");
    for (long long k = 0; k < count; ++k) {
      r.require("an element");
      if (r.tokens().size() < 2) r.fail("expected an element: its tag and its nodes");
      r.integer(0, 1, kMaxTag, "element tag");
      if (type != 2) continue;  // not a 3-node triangle: ignored
      r.expect_tokens(4, "a triangle: elementTag and 3 node tags");
      add_triangle(r, c, r.integer(1, 1, kMaxTag, "node tag"), r.integer(2, 1, kMaxTag, "node tag"),
                   r.integer(3, 1, kMaxTag, "node tag"));
    }
    read += count;
  }
  if (read != total)
    r.fail("the element blocks hold " + std::to_string(read) + " elements, the header says " +
           std::to_string(total));
  r.expect_end("Elements");
}

void read_nodes_22(LineReader& r, Contents& c) {
  r.require("the number of nodes");
  r.expect_tokens(1, "the number of nodes");
  const long long count = r.integer(0, 0, kMaxCount, "number of nodes");
  for (long long k = 0; k < count; ++k) {
    r.require("a node");
    r.expect_tokens(4, "a node: tag x y z");
    add_node(r, c, r.integer(0, 1, kMaxTag, "node tag"),
             {r.real(1, "coordinate x"), r.real(2, "coordinate y"), r.real(3, "coordinate z")});
  }
  r.expect_end("Nodes");
}

void read_elements_22(LineReader& r, Contents& c) {
  r.require("the number of elements");
  r.expect_tokens(1, "the number of elements");
  const long long count = r.integer(0, 0, kMaxCount, "number of elements");
  for (long long k = 0; k < count; ++k) {
    r.require("an element");
    if (r.tokens().size() < 3) r.fail("expected an element: tag type number-of-tags ...");
    r.integer(0, 1, kMaxTag, "element tag");
    const long long type = r.integer(1, 1, 1000, "element type");
    const long long ntags = r.integer(2, 0, 1000, "number of tags");
    if (type != 2) continue;
    const std::size_t first = 3 + static_cast<std::size_t>(ntags);
    r.expect_tokens(first + 3, "a triangle: tag type number-of-tags, its tags and 3 nodes");
    for (std::size_t t = 3; t < first; ++t) r.integer(t, -kMaxTag, kMaxTag, "element tag value");
    add_triangle(r, c, r.integer(first, 1, kMaxTag, "node tag"),
                 r.integer(first + 1, 1, kMaxTag, "node tag"),
                 r.integer(first + 2, 1, kMaxTag, "node tag"));
  }
  r.expect_end("Elements");
}

}  // namespace

TriangleMesh read_msh(std::istream& in, const std::string& source) {
  LineReader r(in, source);
  Contents c;
  int version = 0;  // 41 or 22
  bool have_nodes = false;
  bool have_elements = false;
  while (r.next()) {
    if (r.tokens().empty()) continue;
    const std::string_view head = r.tokens()[0];
    if (head.empty() || head[0] != '$') r.fail("expected a section ($Name), found '" + r.line() + "'");
    const std::string name(head.substr(1));
    if (name == "MeshFormat") {
      if (version != 0) r.fail("second $MeshFormat section");
      r.require("the format line 'version file-type data-size'");
      r.expect_tokens(3, "the format line 'version file-type data-size'");
      const std::string_view v = r.tokens()[0];
      if (v == "4.1") {
        version = 41;
      } else if (v == "2.2" || v == "2.1" || v == "2" || v == "2.0") {
        version = 22;
      } else {
        r.fail("unsupported .msh format version '" + std::string(v) + "' (4.1 and 2.2 are read)");
      }
      if (r.integer(1, 0, 1, "file-type") != 0) r.fail("binary .msh files are not supported");
      r.integer(2, 1, 64, "data-size");
      r.expect_end("MeshFormat");
    } else if (name == "Nodes" || name == "Elements") {
      if (version == 0) r.fail("$" + name + " before $MeshFormat");
      bool& seen = name == "Nodes" ? have_nodes : have_elements;
      if (seen) r.fail("second $" + name + " section");
      seen = true;
      if (name == "Nodes") {
        version == 41 ? read_nodes_41(r, c) : read_nodes_22(r, c);
      } else {
        version == 41 ? read_elements_41(r, c) : read_elements_22(r, c);
      }
    } else if (name.rfind("End", 0) == 0) {
      r.fail("'" + r.line() + "' without its opening section");
    } else {
      r.skip_section(name);
    }
  }
  if (version == 0) throw MeshError(source + ": no $MeshFormat section (not a .msh file)");
  if (!have_nodes) throw MeshError(source + ": no $Nodes section");
  if (!have_elements) throw MeshError(source + ": no $Elements section");
  if (c.triangles.empty()) throw MeshError(source + ": no triangles (element type 2)");

  std::map<long long, int> index;
  for (std::size_t f = 0; f < c.triangles.size(); ++f)
    for (const long long t : c.triangles[f]) {
      if (!c.nodes.count(t))
        throw MeshError(source + ", line " + std::to_string(c.triangle_lines[f]) +
                        ": the triangle refers to node " + std::to_string(t) +
                        ", which is not in $Nodes");
      index[t] = 0;
    }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(index.size()), 3);
  int next = 0;
  for (auto& [tag, v] : index) {
    v = next++;
    mesh.vertices.row(v) = c.nodes.at(tag).transpose();
  }
  mesh.faces.resize(static_cast<Eigen::Index>(c.triangles.size()), 3);
  for (std::size_t f = 0; f < c.triangles.size(); ++f) {
    int t[3];
    for (int k = 0; k < 3; ++k) t[k] = index.at(c.triangles[f][static_cast<std::size_t>(k)]);
    const Eigen::Vector2d a = mesh.vertices.row(t[0]).head<2>();
    const Eigen::Vector2d b = mesh.vertices.row(t[1]).head<2>();
    const Eigen::Vector2d d = mesh.vertices.row(t[2]).head<2>();
    if ((b - a).x() * (d - a).y() - (b - a).y() * (d - a).x() < 0.0) std::swap(t[1], t[2]);
    mesh.faces.row(static_cast<Eigen::Index>(f)) << t[0], t[1], t[2];
  }
  return mesh;
}

TriangleMesh read_msh(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw MeshError("cannot open .msh file '" + path + "'");
  return read_msh(in, path);
}

}  // namespace growshell
