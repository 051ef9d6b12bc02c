#pragma once
// The command line of the branch-tracing programs: an optional scene file first (any first
// argument not starting with '-'; default_scene() without one), then `--name value` options.

#include <stdexcept>
#include <string>
#include <vector>

#include "examples/support/command_line.hpp"
#include "libshell/io/scene.hpp"

namespace growshell::examples {

struct SceneCommandLine {
  Scene scene;          ///< read from the file, or default_scene()
  CommandLine options;  ///< the options after the scene file
};

/// Throws as read_scene (a bad file, naming the key) and CommandLine (a malformed option).
inline SceneCommandLine read_scene_command_line(int argc, char** argv) {
  int first_option = 1;
  Scene scene = default_scene();
  if (argc > 1 && argv[1][0] != '-') {
    scene = read_scene(argv[1]);
    first_option = 2;
  }
  std::vector<char*> rest(argv + first_option, argv + argc);
  rest.insert(rest.begin(), argv[0]);
  return {std::move(scene), CommandLine(static_cast<int>(rest.size()), rest.data())};
}

/// Applies the mesh options that are given, in this order: `--mesh FAMILY` (mesh.family),
/// `--size-slope C` (mesh.size_slope) and `--rings N` (the lattice family's resolution:
/// mesh.rings for a disc, mesh.radial_layers for a ring). Throws std::invalid_argument for a
/// resolution option that the scene's family does not read (a silently ignored option would run
/// another mesh than asked): --rings with a family other than lattice, --size-slope with the
/// lattice or file family.
inline void apply_mesh_options(Scene& scene, CommandLine& cl) {
  const std::string family = cl.text("--mesh", "");
  if (!family.empty()) apply_override(scene, "mesh.family", family);
  const std::string slope = cl.text("--size-slope", "");
  if (!slope.empty()) {
    if (scene.mesh.family != MeshFamily::Rings && scene.mesh.family != MeshFamily::Gmsh)
      throw std::invalid_argument("--size-slope " + slope + " sets the resolution of mesh.family = "
                                  "rings or gmsh; this scene's family does not read it");
    apply_override(scene, "mesh.size_slope", slope);
  }
  const std::string rings = cl.text("--rings", "");
  if (!rings.empty()) {
    if (scene.mesh.family != MeshFamily::Lattice)
      throw std::invalid_argument("--rings " + rings + " sets the resolution of mesh.family = "
                                  "lattice (--mesh lattice); this scene's family sets it with "
                                  "mesh.size_slope (--size-slope)");
    apply_override(scene,
                   scene.geometry.shape == SceneShape::Ring ? "mesh.radial_layers" : "mesh.rings",
                   rings);
  }
}

}  // namespace growshell::examples
