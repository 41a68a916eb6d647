// Errors and internal checks shared by every shanshui library.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace shanshui {

//! Bad input or a failed operation that the user can act on. The message is one line
//! and names what was wrong and where ("dem.asc: line 7: expected 120 values, found 95").
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Builds an Error message from streamable parts: throw makeError(path, ": ", what).
template <typename... Parts>
Error makeError(const Parts&... parts) {
  std::ostringstream s;
  (s << ... << parts);
  return Error(s.str());
}

namespace detail {
[[noreturn]] void checkFailed(const char* file, int line, const std::string& what);
}  // namespace detail

}  // namespace shanshui

//! Internal invariant, always on. Not for user input: that gets an Error.
#define SHANSHUI_CHECK(cond)                                                              \
  do {                                                                                    \
    if (!(cond)) ::shanshui::detail::checkFailed(__FILE__, __LINE__, "CHECK(" #cond ")"); \
  } while (false)

//! Compares two values and prints both on failure.
#define SHANSHUI_CHECK_OP(a, op, b)                                                       \
  do {                                                                                    \
    const auto& check_a_ = (a);                                                           \
    const auto& check_b_ = (b);                                                           \
    if (!(check_a_ op check_b_)) {                                                        \
      std::ostringstream check_s_;                                                        \
      check_s_ << "CHECK(" #a " " #op " " #b ") with " << check_a_ << " vs " << check_b_; \
      ::shanshui::detail::checkFailed(__FILE__, __LINE__, check_s_.str());                \
    }                                                                                     \
  } while (false)

#define SHANSHUI_CHECK_EQ(a, b) SHANSHUI_CHECK_OP(a, ==, b)
#define SHANSHUI_CHECK_LT(a, b) SHANSHUI_CHECK_OP(a, <, b)
#define SHANSHUI_CHECK_LE(a, b) SHANSHUI_CHECK_OP(a, <=, b)
#define SHANSHUI_CHECK_NE(a, b) SHANSHUI_CHECK_OP(a, !=, b)
#define SHANSHUI_CHECK_GT(a, b) SHANSHUI_CHECK_OP(a, >, b)
#define SHANSHUI_CHECK_GE(a, b) SHANSHUI_CHECK_OP(a, >=, b)

#ifdef NDEBUG
#define SHANSHUI_DCHECK(cond) \
  do {                        \
  } while (false)
#else
#define SHANSHUI_DCHECK(cond) SHANSHUI_CHECK(cond)
#endif
