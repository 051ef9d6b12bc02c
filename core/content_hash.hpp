#pragma once
/// \file
/// A 64-bit FNV-1a hash of bytes: a fingerprint that tells two contents apart (not a
/// cryptographic hash). Used to name damaged files and to tie saved states to their scene.

#include <cstdint>
#include <string_view>

namespace growshell {

/// FNV-1a (offset basis 14695981039346656037, prime 1099511628211) of `bytes`.
inline std::uint64_t fnv1a_64(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

}  // namespace growshell
