#pragma once
/// \file
/// The exception thrown for invalid control meshes and mesh files.

#include <stdexcept>
#include <string>

namespace growshell {

/// Thrown when a mesh (or a mesh file, or mesh-generator options) is not usable by growshell.
/// what() names the offending item (vertex, face, edge, file and line, or option) and, where
/// one exists, the allowed range.
class MeshError : public std::invalid_argument {
 public:
  /// Creates the error with the full, human-readable message.
  explicit MeshError(const std::string& message) : std::invalid_argument(message) {}
};

}  // namespace growshell
