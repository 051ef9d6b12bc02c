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

/// Applies `--rings N` (if given): the lattice family's resolution, mesh.rings for a disc and
/// mesh.radial_layers for a ring. Throws std::invalid_argument for another mesh family, whose
/// resolution is mesh.size_slope (a silently ignored --rings would run another mesh than asked).
inline void apply_rings_option(Scene& scene, const std::string& rings) {
  if (rings.empty()) return;
  if (scene.mesh.family != MeshFamily::Lattice)
    throw std::invalid_argument("--rings " + rings + " sets the resolution of mesh.family = "
                                "lattice; this scene's family sets it with mesh.size_slope");
  apply_override(scene, scene.geometry.shape == SceneShape::Ring ? "mesh.radial_layers" : "mesh.rings",
                 rings);
}

}  // namespace growshell::examples
