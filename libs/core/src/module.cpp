#include "shanshui/core/module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace shanshui {
namespace fs = std::filesystem;

void* loadModuleEntry(const std::string& file, const char* env_var, const std::string& build_dir, const char* symbol,
                      std::string& error) {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv(env_var); env != nullptr && *env != '\0') candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path() / file);
  if (!build_dir.empty()) candidates.push_back(fs::path(build_dir) / file);
  error.clear();
  for (const fs::path& candidate : candidates) {
    if (!fs::exists(candidate, ec)) continue;
    void* handle = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      error = ::dlerror();
      continue;
    }
    if (void* entry = ::dlsym(handle, symbol)) return entry;
    error = candidate.string() + " has no entry point " + symbol;
  }
  if (error.empty()) error = "not found next to the program";
  return nullptr;
}

}  // namespace shanshui
