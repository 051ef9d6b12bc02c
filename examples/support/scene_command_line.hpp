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

/// Sets scene key `key` from the text of `option`, if the option is given (apply_override).
inline void apply_option(Scene& scene, CommandLine& cl, const char* option, const char* key) {
  const std::string value = cl.text(option, "");
  if (!value.empty()) apply_override(scene, key, value);
}

/// Throws std::invalid_argument unless the scene's mesh family reads the mesh option `option`,
/// given as `value` (a silently ignored option would run another mesh than asked): --rings and
/// --grading belong to the lattice family, --size-slope to the rings and gmsh families.
inline void require_family_reads(const Scene& scene, const std::string& option,
                                 const std::string& value) {
  const MeshFamily family = scene.mesh.family;
  if (option == "--size-slope") {
    if (graded_by_size(family)) return;
    throw std::invalid_argument("--size-slope " + value + " sets the resolution of mesh.family = "
                                "rings, gmsh or gmsh_d4; this scene's family does not read it");
  }
  if (family == MeshFamily::Lattice) return;
  const bool rings = option == "--rings";
  throw std::invalid_argument(option + " " + value + " sets the " +
                              (rings ? "resolution" : "grading") +
                              " of mesh.family = lattice (--mesh lattice); this scene's family " +
                              (rings ? "sets it" : "grades its mesh") +
                              " with mesh.size_slope (--size-slope)");
}

/// Applies the mesh options that are given, in this order: `--mesh FAMILY` (mesh.family),
/// `--size-slope C` (mesh.size_slope) and `--rings N` (the lattice family's resolution:
/// mesh.rings for a disc, mesh.radial_layers for a ring). Throws as require_family_reads for a
/// resolution option that the scene's family does not read.
inline void apply_mesh_options(Scene& scene, CommandLine& cl) {
  apply_option(scene, cl, "--mesh", "mesh.family");
  const std::string slope = cl.text("--size-slope", "");
  if (!slope.empty()) {
    require_family_reads(scene, "--size-slope", slope);
    apply_override(scene, "mesh.size_slope", slope);
  }
  const std::string rings = cl.text("--rings", "");
  if (!rings.empty()) {
    require_family_reads(scene, "--rings", rings);
    apply_override(scene,
                   scene.geometry.shape == SceneShape::Ring ? "mesh.radial_layers" : "mesh.rings",
                   rings);
  }
}

}  // namespace growshell::examples
