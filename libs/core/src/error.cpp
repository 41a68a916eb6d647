#include "shanshui/core/error.h"

#include <cstdio>
#include <cstdlib>

namespace shanshui::detail {

void checkFailed(const char* file, int line, const std::string& what) {
  std::fprintf(stderr, "internal error: %s:%d: %s\n", file, line, what.c_str());
  std::abort();
}

}  // namespace shanshui::detail
