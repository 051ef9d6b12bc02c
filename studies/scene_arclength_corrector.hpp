#pragma once
/// \file
/// The scene's continuation.corrector as the continuation's corrector.

#include "libshell/io/scene.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// ArclengthOptions::Corrector for the scene's continuation.corrector.
inline ArclengthOptions::Corrector scene_arclength_corrector(const Scene& scene) {
  return scene.continuation.corrector == SceneCorrector::Chord ? ArclengthOptions::Corrector::Chord
                                                               : ArclengthOptions::Corrector::Newton;
}

}  // namespace growshell
