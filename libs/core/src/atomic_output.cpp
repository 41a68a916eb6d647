#include "shanshui/core/atomic_output.h"

#include <unistd.h>

#include <atomic>
#include <system_error>

#include "shanshui/core/error.h"

namespace shanshui {
namespace fs = std::filesystem;

void checkOutputPath(const fs::path& target) {
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw makeError(target.string(), ": output directory does not exist: ", dir.string());
  }
  if (fs::is_directory(target, ec)) {
    throw makeError(target.string(), ": is a directory, expected a file name");
  }
}

void writeAtomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  checkOutputPath(target);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = dir / ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) +
                              "_" + std::to_string(counter++) + target.extension().string());
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw makeError(target.string(), ": cannot write: ", ec.message());
  }
}

}  // namespace shanshui
