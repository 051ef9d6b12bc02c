#include "libshell/io/vtk_writer.hpp"

#include <fstream>
#include <iomanip>
#include <limits>
#include <stdexcept>

namespace growshell {
namespace {

std::ofstream open_for_writing(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot open '" + path + "' for writing");
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  return out;
}

void write_fields(std::ofstream& out, const char* tag,
                  const std::vector<std::pair<std::string, Eigen::VectorXd>>& fields,
                  Eigen::Index expected, const char* what) {
  out << "      <" << tag << ">\n";
  for (const auto& [name, values] : fields) {
    if (values.size() != expected)
      throw std::invalid_argument(std::string(what) + " field '" + name + "' has " +
                                  std::to_string(values.size()) + " values, expected " +
                                  std::to_string(expected));
    out << "        <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
    for (Eigen::Index i = 0; i < values.size(); ++i) out << values(i) << '\n';
    out << "        </DataArray>\n";
  }
  out << "      </" << tag << ">\n";
}

}  // namespace

void write_vtu(const std::string& path, const SurfaceSnapshot& s) {
  std::ofstream out = open_for_writing(path);
  const Eigen::Index np = s.points.rows(), nc = s.triangles.rows();
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << np << "\" NumberOfCells=\"" << nc << "\">\n";
  write_fields(out, "PointData", s.point_data, np, "point");
  write_fields(out, "CellData", s.cell_data, nc, "cell");
  out << "      <Points>\n"
      << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < np; ++i)
    out << s.points(i, 0) << ' ' << s.points(i, 1) << ' ' << s.points(i, 2) << '\n';
  out << "        </DataArray>\n      </Points>\n      <Cells>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < nc; ++i)
    out << s.triangles(i, 0) << ' ' << s.triangles(i, 1) << ' ' << s.triangles(i, 2) << '\n';
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < nc; ++i) out << 3 * (i + 1) << '\n';
  out << "        </DataArray>\n"
      << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (Eigen::Index i = 0; i < nc; ++i) out << "5\n";  // VTK_TRIANGLE
  out << "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
      << "</VTKFile>\n";
  if (!out) throw std::runtime_error("writing '" + path + "' failed");
}

void write_pvd(const std::string& path, const std::vector<CollectionEntry>& entries) {
  std::ofstream out = open_for_writing(path);
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
