// JSON reports of the tools as text: never fails on a file name that is not UTF-8, and never
// carries a NaN or an infinity (which JSON cannot hold: nlohmann writes them as null).
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "shanshui/core/error.h"

namespace shanshui::tools {

//! The JSON pointer of the first non-finite number in `j` ("/stats/ink_share"), or nothing.
inline std::optional<std::string> firstNonFinite(const nlohmann::json& j, const std::string& at = "") {
  if (j.is_number_float() && !std::isfinite(j.get<double>())) return at.empty() ? "/" : at;
  if (j.is_object()) {
    for (const auto& [key, value] : j.items())
      if (auto found = firstNonFinite(value, at + "/" + key)) return found;
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      if (auto found = firstNonFinite(j[i], at + "/" + std::to_string(i))) return found;
  }
  return std::nullopt;
}

//! Pretty-printed with a final newline; invalid UTF-8 in strings (a file name in another
//! encoding) becomes U+FFFD instead of an exception after the main output was made. A
//! non-finite value is an error naming `target` and the value's key, raised before
//! anything is written.
inline std::string jsonText(const nlohmann::json& j, const std::string& target = "the report") {
  if (const auto key = firstNonFinite(j)) {
    throw makeError(target, ": the value at ", *key, " is not finite (",
                    j.at(nlohmann::json::json_pointer(*key)).get<double>(), "); refusing to write it");
  }
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace shanshui::tools
