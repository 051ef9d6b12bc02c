#pragma once
/// \file
/// Reading Gmsh .msh files (ASCII formats 4.1 and 2.2) into a sheet triangulation.

#include <istream>
#include <string>

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Reads the 3-node triangles (element type 2) of the Gmsh mesh file at `path`, ASCII format
/// 4.1 or 2.2 (2.0 and 2.1 read as 2.2). Returns the sheet: the nodes used by triangles, in
/// increasing node tag (coordinates as written, metres), and the triangles in file order, each
/// made counter-clockwise seen from +z (nodes 2 and 3 swapped where the signed area in the
/// xy-plane is negative). Other element types (points, lines, quadrangles, ...) and other
/// sections ($PhysicalNames, $Entities, $NodeData, ...) are skipped. Throws MeshError naming
/// the file and line for a missing file, a binary or other-version file, a malformed or
/// truncated section, a non-finite coordinate, a repeated node tag, a triangle naming an
/// unknown node or repeating one, and for a file without $MeshFormat, $Nodes, $Elements or
/// triangles.
TriangleMesh read_msh(const std::string& path);

/// As read_msh, from a stream; `source` names it in error messages (e.g. the file name).
TriangleMesh read_msh(std::istream& in, const std::string& source);

}  // namespace growshell
