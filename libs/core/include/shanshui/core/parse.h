// Parsing of small command-line values shared by the tools ("1024x768", "0.2:0.8").
#pragma once

#include <string_view>
#include <utility>

namespace shanshui {

struct Size2 {
  int width = 0;
  int height = 0;
};

//! Parses "WxH" with positive integers; `what` names the parameter in the error.
Size2 parseSize(std::string_view text, std::string_view what);

//! Parses a finite double; the whole string must be consumed.
double parseDouble(std::string_view text, std::string_view what);

//! Parses "A:B" with two finite numbers (no order implied).
std::pair<double, double> parsePair(std::string_view text, std::string_view what);

}  // namespace shanshui
