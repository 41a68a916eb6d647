// JSON reports of the tools as text: never fails on a file name that is not UTF-8.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace shanshui::tools {

//! Pretty-printed with a final newline; invalid UTF-8 in strings (a file name in another
//! encoding) becomes U+FFFD instead of an exception after the main output was made.
inline std::string jsonText(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace shanshui::tools
