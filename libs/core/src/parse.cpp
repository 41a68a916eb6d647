#include "shanshui/core/parse.h"

#include <charconv>
#include <cmath>
#include <string>

#include "shanshui/core/error.h"

namespace shanshui {

namespace {
bool parseInt(std::string_view s, int& out) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}
}  // namespace

Size2 parseSize(std::string_view text, std::string_view what) {
  const auto x = text.find_first_of("xX");
  Size2 size;
  if (x == std::string_view::npos || !parseInt(text.substr(0, x), size.width) ||
      !parseInt(text.substr(x + 1), size.height) || size.width <= 0 || size.height <= 0) {
    throw makeError(what, ": '", text, "' is not a size; expected WxH with positive integers, e.g. 1024x768");
  }
  return size;
}

double parseDouble(std::string_view text, std::string_view what) {
  double v = 0;
  const std::string s(text);
  std::size_t used = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v)) {
    throw makeError(what, ": '", text, "' is not a finite number");
  }
  return v;
}

std::pair<double, double> parsePair(std::string_view text, std::string_view what) {
  const auto colon = text.find(':');
  try {
    if (colon != std::string_view::npos) {
      return {parseDouble(text.substr(0, colon), what), parseDouble(text.substr(colon + 1), what)};
    }
  } catch (const Error&) {
  }
  throw makeError(what, ": '", text, "' is not a pair; expected A:B with two finite numbers, e.g. 0.1:0.9");
}

}  // namespace shanshui
