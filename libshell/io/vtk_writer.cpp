#include "libshell/io/vtk_writer.hpp"

#include <bit>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <stdexcept>

namespace growshell {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the appended VTU data are written in the host's byte order, declared little-endian");

std::ofstream open_for_writing(const std::string& path, bool binary) {
  std::ofstream out(path, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if (!out) throw std::runtime_error("cannot open '" + path + "' for writing");
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  return out;
}

/// The arrays of one file in the order they are declared, as raw little-endian bytes, and the
/// XML that declares them: inline ASCII, or appended (format="appended" with its offset into
/// the <AppendedData> block, each array there a UInt64 byte count and the bytes).
class VtuArrays {
 public:
  explicit VtuArrays(VtuEncoding encoding) : encoding_(encoding) {}

  template <class T>
  void declare(std::ostream& xml, const char* type, const std::string& attributes,
               const std::vector<T>& values, int per_line) {
    xml << "        <DataArray type=\"" << type << "\"" << attributes;
    if (encoding_ == VtuEncoding::Ascii) {
      xml << " format=\"ascii\">\n";
      for (std::size_t i = 0; i < values.size(); ++i)
        xml << +values[i] << ((i + 1) % static_cast<std::size_t>(per_line) == 0 ? '\n' : ' ');
      xml << "        </DataArray>\n";
      return;
    }
    xml << " format=\"appended\" offset=\"" << appended_.size() << "\"/>\n";
    const std::uint64_t bytes = values.size() * sizeof(T);
    const char* begin = reinterpret_cast<const char*>(&bytes);
    appended_.insert(appended_.end(), begin, begin + sizeof bytes);
    const char* data = reinterpret_cast<const char*>(values.data());
    appended_.insert(appended_.end(), data, data + bytes);
  }

  void write_appended(std::ostream& out) const {
    if (encoding_ == VtuEncoding::Ascii) return;
    out << "  <AppendedData encoding=\"raw\">\n   _";
    out.write(appended_.data(), static_cast<std::streamsize>(appended_.size()));
    out << "\n  </AppendedData>\n";
  }

 private:
  VtuEncoding encoding_;
  std::vector<char> appended_;
};

void check_fields(const std::vector<std::pair<std::string, Eigen::VectorXd>>& fields,
                  Eigen::Index expected, const char* what) {
  for (const auto& [name, values] : fields)
    if (values.size() != expected)
      throw std::invalid_argument(std::string(what) + " field '" + name + "' has " +
                                  std::to_string(values.size()) + " values, expected " +
                                  std::to_string(expected));
}

void declare_fields(std::ostream& xml, VtuArrays& arrays, const char* tag,
                    const std::vector<std::pair<std::string, Eigen::VectorXd>>& fields) {
  xml << "      <" << tag << ">\n";
  for (const auto& [name, values] : fields) {
    arrays.declare(xml, "Float64", " Name=\"" + name + "\"",
                   std::vector<double>(values.data(), values.data() + values.size()), 1);
  }
  xml << "      </" << tag << ">\n";
}

}  // namespace

void write_vtu(const std::string& path, const SurfaceSnapshot& s, VtuEncoding encoding) {
  const Eigen::Index np = s.points.rows(), nc = s.triangles.rows();
  check_fields(s.point_data, np, "point");  // before the file is opened
  check_fields(s.cell_data, nc, "cell");
  std::vector<double> points(static_cast<std::size_t>(3 * np));
  for (Eigen::Index i = 0; i < np; ++i)
    for (int c = 0; c < 3; ++c) points[static_cast<std::size_t>(3 * i + c)] = s.points(i, c);
  std::vector<std::int64_t> connectivity(static_cast<std::size_t>(3 * nc)), offsets;
  for (Eigen::Index i = 0; i < nc; ++i) {
    for (int c = 0; c < 3; ++c)
      connectivity[static_cast<std::size_t>(3 * i + c)] = s.triangles(i, c);
    offsets.push_back(3 * (i + 1));
  }
  const std::vector<std::uint8_t> types(static_cast<std::size_t>(nc), 5);  // VTK_TRIANGLE

  std::ofstream out = open_for_writing(path, encoding == VtuEncoding::AppendedRaw);
  VtuArrays arrays(encoding);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
      << " header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n";
  declare_fields(out, arrays, "PointData", s.point_data);
  declare_fields(out, arrays, "CellData", s.cell_data);
  out << "      <Points>\n";
  arrays.declare(out, "Float64", " NumberOfComponents=\"3\"", points, 3);
  out << "      </Points>\n      <Cells>\n";
  arrays.declare(out, "Int64", " Name=\"connectivity\"", connectivity, 3);
  arrays.declare(out, "Int64", " Name=\"offsets\"", offsets, 1);
  arrays.declare(out, "UInt8", " Name=\"types\"", types, 1);
  out << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
  arrays.write_appended(out);
  out << "</VTKFile>\n";
  if (!out) throw std::runtime_error("writing '" + path + "' failed");
}

void write_pvd(const std::string& path, const std::vector<CollectionEntry>& entries) {
  std::ofstream out = open_for_writing(path, false);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const auto& e : entries)
    out << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\"" << e.file
        << "\"/>\n";
  out << "  </Collection>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("writing '" + path + "' failed");
}

}  // namespace growshell
