#pragma once
/// \file
/// Writing triangle surfaces with per-cell and per-point data as VTK XML files for ParaView.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace growshell {

/// A triangulated surface with named scalar fields.
struct SurfaceSnapshot {
  Eigen::MatrixX3d points;     ///< one row per point (metres)
  Eigen::MatrixX3i triangles;  ///< point indices, counter-clockwise
  std::vector<std::pair<std::string, Eigen::VectorXd>> cell_data;   ///< one value per triangle
  std::vector<std::pair<std::string, Eigen::VectorXd>> point_data;  ///< one value per point
};

/// How write_vtu stores the arrays.
enum class VtuEncoding {
  /// Raw little-endian bytes in one <AppendedData encoding="raw"> block after the XML (VTK
  /// XML format 1.0, UInt64 size headers): exact doubles at 8 bytes each, about a third of
  /// the ASCII size; read by ParaView, VTK and meshio, and by scripts/render_surface.py.
  AppendedRaw,
  /// Inline ASCII with full double precision (17 significant digits): readable as text.
  Ascii,
};

/// Writes `snapshot` as a VTK XML unstructured grid (.vtu): points (Float64 x 3), triangles
/// (Int64 connectivity and offsets, UInt8 types), and the named Float64 point and cell fields,
/// every value exact. Throws std::invalid_argument for a field of the wrong length and
/// std::runtime_error if the file cannot be written (naming the path).
void write_vtu(const std::string& path, const SurfaceSnapshot& snapshot,
               VtuEncoding encoding = VtuEncoding::AppendedRaw);

/// One entry of a ParaView collection: a time value and a file name relative to the .pvd.
struct CollectionEntry {
  double time;
  std::string file;
};

/// Writes a ParaView .pvd collection listing `entries` (e.g. one VTU per continuation step,
/// with phi_e as the time value). Throws std::runtime_error if the file cannot be written.
void write_pvd(const std::string& path, const std::vector<CollectionEntry>& entries);

}  // namespace growshell
