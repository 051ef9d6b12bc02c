#pragma once
/// A value of results.json that may be missing: a finite number, or null.

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

namespace growshell {

/// `v` as a JSON number, or null where it is unset or not finite (JSON has no NaN or infinity).
inline nlohmann::ordered_json json_number_or_null(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

}  // namespace growshell
