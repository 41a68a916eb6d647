// Writing outputs so that a failure never leaves a half-finished file over a good one.
#pragma once

#include <filesystem>
#include <functional>

namespace shanshui {

//! Calls write(tmp) with a temporary path next to `target` (same directory, same
//! extension so format-sniffing writers still work), then renames it over `target`.
//! If write throws, the temporary file is removed and `target` is left untouched.
//! The directory of `target` must exist; an Error names it otherwise.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

//! Throws the Error writeAtomically() would throw for `target` (missing directory, target is
//! a directory), so a tool can refuse before a long computation rather than after it.
void checkOutputPath(const std::filesystem::path& target);

}  // namespace shanshui
