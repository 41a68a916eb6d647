// Optional parts of shanshui built as modules beside the programs and loaded on first use
// (dlopen), so that a program that never needs a heavy library (OpenImageIO, GDAL) does not
// pay for loading its hundred-odd shared libraries at every start.
#pragma once

#include <string>

namespace shanshui {

//! The entry point `symbol` of the module `file`, looked for in $`env_var` (a file path),
//! next to the running program, then in `build_dir`. Returns nullptr and sets `error` when
//! no candidate loads or has the symbol.
void* loadModuleEntry(const std::string& file, const char* env_var, const std::string& build_dir, const char* symbol,
                      std::string& error);

}  // namespace shanshui
