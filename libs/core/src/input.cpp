#include "shanshui/core/input.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <system_error>

#include "shanshui/core/error.h"

namespace shanshui {
namespace fs = std::filesystem;

namespace {
std::mutex g_last_mutex;
std::string g_last_input;
}  // namespace

std::string lastInputFile() {
  std::lock_guard lock(g_last_mutex);
  return g_last_input;
}

std::uintmax_t checkInputFile(const fs::path& path, std::string_view what, std::uintmax_t max_bytes) {
  std::error_code ec;
  const fs::file_status s = fs::status(path, ec);
  if (!fs::exists(s)) throw makeError(path.string(), ": no such file; expected ", what);
  if (fs::is_directory(s)) throw makeError(path.string(), ": is a directory, expected ", what);
  if (!fs::is_regular_file(s)) {
    throw makeError(path.string(), ": not a regular file (a device, FIFO or socket); expected ", what);
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw makeError(path.string(), ": cannot read its size: ", ec.message());
  if (size == 0) throw makeError(path.string(), ": empty file; expected ", what);
  if (size > max_bytes) {
    throw makeError(path.string(), ": ", size, " bytes is larger than the limit of ", max_bytes, " bytes for ", what);
  }
  if (::access(path.c_str(), R_OK) != 0) throw makeError(path.string(), ": cannot read: ", std::strerror(errno));
  {
    std::lock_guard lock(g_last_mutex);
    g_last_input = path.string();
  }
  return size;
}

std::string readInputFile(const fs::path& path, std::string_view what, std::uintmax_t max_bytes) {
  const std::uintmax_t size = checkInputFile(path, what, max_bytes);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw makeError(path.string(), ": cannot read: ", std::strerror(errno));
  // Read at most one byte past the size checked above: a file swapped for something endless
  // between the check and the open is still bounded.
  std::string data(static_cast<std::size_t>(size) + 1, '\0');
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::read(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw makeError(path.string(), ": cannot read: ", std::strerror(err));
    }
    if (n == 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (done > size) throw makeError(path.string(), ": grew while it was read; expected ", what);
  data.resize(done);
  return data;
}

std::string readInputStream(std::FILE* stream, std::string_view name, std::string_view what, std::uintmax_t max_bytes) {
  std::string data;
  char buf[1 << 16];
  for (;;) {
    const std::size_t n = std::fread(buf, 1, sizeof buf, stream);
    if (n > 0) {
      if (data.size() + n > max_bytes) {
        throw makeError(name, ": more than ", max_bytes, " bytes; larger than the limit for ", what);
      }
      data.append(buf, n);
    }
    if (n < sizeof buf) {
      if (std::ferror(stream)) throw makeError(name, ": cannot read: ", std::strerror(errno));
      break;
    }
  }
  return data;
}

// ---- memory budget --------------------------------------------------------------------

namespace {

std::mutex g_budget_mutex;
std::uintmax_t g_budget = 0;  // 0: not set

std::uintmax_t defaultBudget() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGESIZE);
  std::uintmax_t budget =
      pages > 0 && page > 0 ? static_cast<std::uintmax_t>(pages) * page / 2 : std::uintmax_t{4} << 30;
  rlimit lim{};
  if (::getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) {
    // What the address-space limit leaves beyond what the process already maps, with a
    // quarter kept for the decoder's own buffers and libraries loaded later.
    std::uintmax_t mapped = 0;
    if (std::ifstream statm("/proc/self/statm"); statm) {
      unsigned long long vm_pages = 0;
      statm >> vm_pages;
      mapped = static_cast<std::uintmax_t>(vm_pages) * (page > 0 ? page : 4096);
    }
    const std::uintmax_t limit = lim.rlim_cur;
    budget = std::min(budget, limit > mapped ? (limit - mapped) / 4 * 3 : 0);
  }
  return budget;
}

}  // namespace

std::uintmax_t parseByteSize(std::string_view text, std::string_view source) {
  unsigned long long v = 0;
  const char* b = text.data();
  const char* e = b + text.size();
  const auto [p, ec] = std::from_chars(b, e, v);
  // A unit letter after the number: K, M, G or T (any case), powers of 1024; 0: not a unit.
  std::uintmax_t scale = 1;
  if (ec == std::errc() && p + 1 == e) {
    constexpr std::string_view kUnits = "kmgt";
    const std::size_t unit = kUnits.find(static_cast<char>(std::tolower(static_cast<unsigned char>(*p))));
    scale = unit == std::string_view::npos ? 0 : std::uintmax_t{1} << (10 * (unit + 1));
  }
  if (ec != std::errc() || (p != e && scale <= 1) || v == 0 || v > (~std::uintmax_t{0}) / scale) {
    throw makeError(source, ": '", text,
                    "' is not a memory size; expected bytes, or a number with K, M, G or T (e.g. 512M)");
  }
  return v * scale;
}

std::uintmax_t memoryBudget() {
  std::lock_guard lock(g_budget_mutex);
  if (g_budget == 0) {
    if (const char* env = std::getenv("SHANSHUI_MAX_MEMORY"); env && *env) {
      g_budget = parseByteSize(env, "SHANSHUI_MAX_MEMORY");
    } else {
      g_budget = defaultBudget();
    }
  }
  return g_budget;
}

void setMemoryBudget(std::uintmax_t bytes) {
  std::lock_guard lock(g_budget_mutex);
  g_budget = bytes;
}

std::string addressSpaceLimitNote() {
  rlimit lim{};
  if (::getrlimit(RLIMIT_AS, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return {};
  return " under an address-space limit of " + std::to_string(lim.rlim_cur >> 20) + " MiB (ulimit -v)";
}

void checkMemoryNeed(std::string_view name, std::string_view what, std::uintmax_t bytes) {
  const std::uintmax_t budget = memoryBudget();
  if (bytes <= budget) return;
  throw makeError(name, ": ", what, " needs ", byteCount(bytes), ", more than the memory budget of ", byteCount(budget),
                  " (--max-memory or SHANSHUI_MAX_MEMORY sets it)");
}

}  // namespace shanshui
