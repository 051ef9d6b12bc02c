// libFuzzer target: the mesh readers (Gmsh .msh from a stream, OBJ from a file). Any input
// must either be refused with MeshError or read into a mesh whose faces index its vertices.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "libshell/mesh/mesh_error.hpp"
#include "libshell/mesh/msh_io.hpp"
#include "libshell/mesh/obj_io.hpp"

namespace {

void check(const growshell::TriangleMesh& mesh) {
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.faces(f, c) < 0 || mesh.faces(f, c) >= mesh.vertices.rows()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::istringstream in(text);
    check(growshell::read_msh(in, "fuzz input"));
  } catch (const growshell::MeshError&) {
  }
  static const std::string obj = "/tmp/growshell_fuzz_mesh_" + std::to_string(getpid()) + ".obj";
  std::ofstream(obj, std::ios::binary) << text;
  try {
    check(growshell::read_obj(obj));
  } catch (const growshell::MeshError&) {
  }
  return 0;
}
