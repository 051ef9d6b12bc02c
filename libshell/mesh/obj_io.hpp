#pragma once
/// \file
/// Reading and writing triangle meshes in Wavefront OBJ format.

#include <string>

#include "libshell/mesh/triangle_mesh.hpp"

namespace growshell {

/// Reads the `v` and `f` lines of the OBJ file at `path` (coordinates as written, in metres
/// by growshell's convention; faces converted to 0-based indices). Face entries may be
/// "i", "i/t", "i//n" or "i/t/n"; negative indices count back from the last vertex read so
/// far. Lines starting with vn, vt, vp, o, g, s, usemtl, mtllib, l or # and blank lines are
/// ignored. Throws MeshError naming the file and line for a missing or unreadable file,
/// a malformed line, a polygon that is not a triangle, or an index out of range.
TriangleMesh read_obj(const std::string& path);

/// Writes `mesh` to `path` as OBJ (1-based `v`/`f` lines) with the shortest decimal form
/// that reads back to the identical double, so read_obj(write_obj(m)) == m bit for bit.
/// Throws MeshError if the file cannot be written.
void write_obj(const std::string& path, const TriangleMesh& mesh);

}  // namespace growshell
