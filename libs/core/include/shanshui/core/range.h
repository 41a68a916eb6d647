// A parameter's allowed values, named once and read by every place that checks it: the
// scene's parameter description (libs/scene), the CPU references' validate() functions
// and the viewer's widgets.
#pragma once

#include <sstream>
#include <string>

namespace shanshui {

template <typename T>
struct Range {
  T lo, hi;
  bool lo_open = false;  //!< (lo, hi] instead of [lo, hi]

  constexpr bool contains(T v) const { return (lo_open ? v > lo : v >= lo) && v <= hi; }

  //! "[0, 1]" or "(0, 1000]".
  std::string text() const {
    std::ostringstream s;
    s << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
    return s.str();
  }
};

}  // namespace shanshui
