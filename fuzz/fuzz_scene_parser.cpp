// libFuzzer target: the scene reader (parse_scene, which read_scene uses on a file's text).
// Any input must either be refused with std::invalid_argument or read into a scene whose JSON
// reads back to the same scene (scene_to_json and parse_scene are inverse on valid scenes).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "libshell/io/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  growshell::Scene scene;
  try {
    scene = growshell::parse_scene(text, "fuzz input");
  } catch (const std::invalid_argument&) {
    return 0;  // refused by name: what bad input must get
  }
  const std::string json = growshell::scene_to_json(scene);
  if (growshell::scene_to_json(growshell::parse_scene(json, "round trip")) != json) std::abort();
  return 0;
}
