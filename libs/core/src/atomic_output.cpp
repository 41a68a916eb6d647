#include "shanshui/core/atomic_output.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <system_error>
#include <vector>

#include "shanshui/core/error.h"

namespace shanshui {
namespace fs = std::filesystem;

namespace {

// Live temporaries, where a signal handler can read them without locks or allocation: a
// list that only grows at its head (nodes are never freed, and a node whose temporary is
// gone is reused by a later one that fits), so any number of temporaries of any path length
// are cleaned up.
struct TempNode {
  std::atomic<bool> used{false};  //!< taken by a live registration
  std::atomic<bool> live{false};  //!< `path` names a temporary the handler must remove
  std::size_t capacity = 0;
  char* path = nullptr;
  TempNode* next = nullptr;
};
std::atomic<TempNode*> g_temps{nullptr};

// Registers a temporary for removal on a signal; the handle goes to unregisterTemp.
TempNode* registerTemp(const fs::path& tmp) {
  const std::string s = fs::absolute(tmp).string();
  for (TempNode* n = g_temps.load(std::memory_order_acquire); n; n = n->next) {
    bool expected = false;
    if (n->capacity > s.size() && n->used.compare_exchange_strong(expected, true)) {
      std::memcpy(n->path, s.c_str(), s.size() + 1);
      n->live.store(true, std::memory_order_release);
      return n;
    }
  }
  auto* n = new TempNode;
  n->capacity = std::max<std::size_t>(s.size() + 1, 256);
  n->path = new char[n->capacity];
  std::memcpy(n->path, s.c_str(), s.size() + 1);
  n->used.store(true);
  n->live.store(true);
  n->next = g_temps.load(std::memory_order_relaxed);
  while (!g_temps.compare_exchange_weak(n->next, n, std::memory_order_release, std::memory_order_relaxed)) {
  }
  return n;
}

void unregisterTemp(void* handle) {
  auto* n = static_cast<TempNode*>(handle);
  if (!n) return;
  n->live.store(false, std::memory_order_release);
  n->used.store(false, std::memory_order_release);
}

extern "C" void removeTempsAndReraise(int sig) {
  for (TempNode* n = g_temps.load(std::memory_order_acquire); n; n = n->next) {
    if (n->live.load(std::memory_order_acquire)) ::unlink(n->path);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string reason(int err) {
  return std::strerror(err);
}

fs::path directoryOf(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

fs::path comparable(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(fs::absolute(p, ec), ec);
  return ec ? fs::absolute(p).lexically_normal() : c;
}

// A temporary and its signal-cleanup slot; removes the file unless released.
class TempFile {
 public:
  explicit TempFile(const fs::path& target) {
    sweepStaleTemporaries(target);
    static std::atomic<unsigned> counter{0};
    path_ = temporaryPath(target, ::getpid(), counter++);
    slot_ = registerTemp(path_);
  }
  ~TempFile() {
    if (!released_) {
      std::error_code ec;
      fs::remove(path_, ec);
    }
    unregisterTemp(slot_);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const fs::path& path() const { return path_; }
  void release() { released_ = true; }

 private:
  fs::path path_;
  void* slot_ = nullptr;
  bool released_ = false;
};

void writeBytes(const fs::path& tmp, const fs::path& target, std::string_view bytes) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw makeError(target.string(), ": cannot write: ", reason(errno));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      throw makeError(target.string(), ": cannot write: ", reason(err));
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
    const int err = errno;
    ::close(fd);
    throw makeError(target.string(), ": cannot write: ", reason(err));
  }
  if (::close(fd) != 0) throw makeError(target.string(), ": cannot write: ", reason(errno));
}

void renameOver(const fs::path& tmp, const fs::path& target) {
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    throw makeError(target.string(), ": cannot write: ", reason(errno));
  }
}

}  // namespace

fs::path temporaryPath(const fs::path& target, long pid, unsigned n) {
  return directoryOf(target) / ("." + target.stem().string() + ".tmp" + std::to_string(pid) + "_" + std::to_string(n) +
                                target.extension().string());
}

void sweepStaleTemporaries(const fs::path& target) {
  // One listing per directory and process: a sequence of a thousand frames in one
  // directory must not list it a thousand times.
  static std::mutex mutex;
  static std::map<fs::path, std::vector<fs::path>> stale;  // directory -> dead processes' temporaries
  const std::lock_guard lock(mutex);
  const fs::path dir = comparable(directoryOf(target));
  auto it = stale.find(dir);
  if (it == stale.end()) {
    std::vector<fs::path> found;
    std::error_code ec;
    for (fs::directory_iterator d(dir, ec), end; !ec && d != end; d.increment(ec)) {
      const std::string name = d->path().filename().string();
      if (name.size() < 2 || name[0] != '.') continue;
      const std::size_t at = name.rfind(".tmp");
      if (at == std::string::npos || at == 0) continue;
      std::size_t p = at + 4;
      long pid = 0;
      std::size_t digits = 0;
      while (p < name.size() && std::isdigit(static_cast<unsigned char>(name[p])) && digits < 10) {
        pid = pid * 10 + (name[p++] - '0');
        ++digits;
      }
      if (digits == 0 || p >= name.size() || name[p] != '_') continue;
      if (pid == ::getpid() || pid <= 0) continue;
      if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // still running
      found.push_back(d->path());
    }
    it = stale.emplace(dir, std::move(found)).first;
  }
  // Only the temporaries of this target: ".STEM.tmpPID_N.EXT".
  const std::string prefix = "." + target.stem().string() + ".tmp", ext = target.extension().string();
  auto& list = it->second;
  for (auto f = list.begin(); f != list.end();) {
    const std::string name = f->filename().string();
    const std::size_t tail = name.rfind(".tmp");
    if (name.compare(0, prefix.size(), prefix) == 0 && tail + 4 == prefix.size() && name.size() >= ext.size() &&
        name.compare(name.size() - ext.size(), ext.size(), ext) == 0) {
      std::error_code ec;
      fs::remove(*f, ec);
      f = list.erase(f);
    } else {
      ++f;
    }
  }
}

void installTempFileCleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Every terminating signal a user can send or a closed pipe can cause.
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE}) {
      struct sigaction old {};
      ::sigaction(sig, nullptr, &old);
      if (old.sa_handler == SIG_IGN) continue;  // a shell's `nohup` or background job keeps it
      struct sigaction sa {};
      sa.sa_handler = removeTempsAndReraise;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
    // A file size limit makes write() fail with EFBIG, which is reported and cleaned up,
    // instead of killing the process with SIGXFSZ and leaving the temporary behind.
    std::signal(SIGXFSZ, SIG_IGN);
  });
}

namespace {
char g_crash_message[512];
std::atomic<bool> g_memory_ran_out{false};

// operator new's last resort under a limit: note it, then fail as it would have.
void noteAndThrowBadAlloc() {
  g_memory_ran_out.store(true, std::memory_order_relaxed);
  throw std::bad_alloc();
}

extern "C" void reportCrashUnderLimit(int) {
  for (TempNode* n = g_temps.load(std::memory_order_acquire); n; n = n->next) {
    if (n->live.load(std::memory_order_acquire)) ::unlink(n->path);
  }
  const ssize_t ignored = ::write(2, g_crash_message, std::strlen(g_crash_message));
  (void)ignored;
  ::_exit(1);
}
}  // namespace

void guardCrashesUnderMemoryLimit(std::string_view component) {
  rlimit lim{};
  if (::getrlimit(RLIMIT_AS, &lim) != 0 || lim.rlim_cur == RLIM_INFINITY) return;
  static std::once_flag once;
  std::call_once(once, [&] {
    std::snprintf(g_crash_message, sizeof g_crash_message,
                  "%s: error: %.*s crashed under an address-space limit of %llu MiB (ulimit -v): it ran out of memory "
                  "without saying so; raise the limit\n",
                  program_invocation_short_name, static_cast<int>(component.size()), component.data(),
                  static_cast<unsigned long long>(lim.rlim_cur >> 20));
    // Its own stack: a crash may come from a stack that cannot grow.
    static std::vector<char> stack(std::max<std::size_t>(SIGSTKSZ, 64 * 1024));
    stack_t ss{};
    ss.ss_sp = stack.data();
    ss.ss_size = stack.size();
    ::sigaltstack(&ss, nullptr);
    for (int sig : {SIGSEGV, SIGBUS, SIGABRT}) {  // LLVM (llvmpipe) aborts on a failed mmap
      struct sigaction sa {};
      sa.sa_handler = reportCrashUnderLimit;
      sa.sa_flags = SA_ONSTACK;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
    std::set_new_handler(noteAndThrowBadAlloc);
  });
}

bool memoryRanOut() {
  return g_memory_ran_out.load(std::memory_order_relaxed);
}

void noteMemoryRanOut() {
  rlimit lim{};
  if (::getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY)
    g_memory_ran_out.store(true, std::memory_order_relaxed);
}

void checkOutputPath(const fs::path& target) {
  if (target.empty()) throw makeError("output: empty file name");
  const fs::path dir = directoryOf(target);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw makeError(target.string(), ": output directory does not exist: ", dir.string());
  }
  struct stat st {};
  if (::access(dir.c_str(), W_OK) != 0) {
    throw makeError(target.string(), ": output directory is not writable: ", dir.string(), " (", reason(errno), ")");
  }
  if (::stat(dir.c_str(), &st) == 0 && (st.st_mode & 0222) == 0) {
    throw makeError(target.string(), ": output directory is read-only: ", dir.string());
  }
  if (fs::is_directory(target, ec)) {
    throw makeError(target.string(), ": is a directory, expected a file name");
  }
  if (::lstat(target.c_str(), &st) == 0) {
    if (S_ISLNK(st.st_mode) || !S_ISREG(st.st_mode)) {
      throw makeError(target.string(), ": exists and is not a regular file; refusing to replace it");
    }
    if ((st.st_mode & 0222) == 0) {
      throw makeError(target.string(), ": exists and is read-only; remove it or make it writable");
    }
  }
  if (target.filename().string().size() > 200) {
    throw makeError(target.string().substr(0, 60), "...: file name longer than 200 bytes");
  }
}

void writeFileAtomically(const fs::path& target, std::string_view bytes) {
  checkOutputPath(target);
  TempFile tmp(target);
  writeBytes(tmp.path(), target, bytes);
  renameOver(tmp.path(), target);
  tmp.release();
}

void writeAtomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  checkOutputPath(target);
  TempFile tmp(target);
  write(tmp.path());
  std::error_code ec;
  if (!fs::is_regular_file(tmp.path(), ec)) throw makeError(target.string(), ": cannot write: the writer made no file");
  renameOver(tmp.path(), target);
  tmp.release();
}

// ---- OutputSet ----

OutputSet::OutputSet(std::vector<fs::path> inputs) {
  for (const fs::path& p : inputs) addInput(p);
}

OutputSet::~OutputSet() {
  for (Entry& e : entries_) {
    if (!e.staged.empty()) {
      std::error_code ec;
      fs::remove(e.staged, ec);
    }
    unregisterTemp(e.slot);
  }
}

void OutputSet::addInput(const fs::path& input) {
  if (!input.empty() && input != "-") inputs_.push_back(comparable(input));
}

void OutputSet::declare(const fs::path& target, std::string_view what, const std::vector<std::string>& extensions) {
  if (target.empty()) throw makeError(what, ": empty file name");
  if (!extensions.empty()) {
    const std::string ext = lower(target.extension().string());
    if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
      std::string list;
      for (const std::string& e : extensions) list += (list.empty() ? "" : ", ") + e;
      throw makeError(target.string(), ": ", what, ": unknown extension '", target.extension().string(), "'; expected ",
                      list);
    }
  }
  const fs::path key = comparable(target);
  // Paths compared canonically, and existing files also by device and inode (hard links);
  // indexed, so a sequence of 100 000 frames declares in linear time.
  struct stat st {};
  const bool exists = ::stat(key.c_str(), &st) == 0;
  const std::pair<unsigned long long, unsigned long long> inode{st.st_dev, st.st_ino};
  for (const fs::path& in : inputs_) {
    struct stat is {};
    if (in == key || (exists && ::stat(in.c_str(), &is) == 0 && is.st_dev == st.st_dev && is.st_ino == st.st_ino)) {
      throw makeError(target.string(), ": ", what, " names an input file; refusing to overwrite it");
    }
  }
  std::size_t clash = entries_.size();
  if (const auto it = byKey_.find(key); it != byKey_.end()) {
    clash = it->second;
  } else if (const auto jt = byInode_.find(inode); exists && jt != byInode_.end()) {
    clash = jt->second;
  }
  if (clash < entries_.size()) {
    throw makeError(target.string(), ": ", what, " and ", entries_[clash].what,
                    " name the same file; give each its own");
  }
  checkOutputPath(target);
  byKey_[key] = entries_.size();
  if (exists) byInode_[inode] = entries_.size();
  entries_.push_back({target, key, std::string(what), {}, nullptr});
}

OutputSet::Entry& OutputSet::find(const fs::path& target) {
  for (Entry& e : entries_) {
    if (e.target == target) return e;
  }
  throw makeError(target.string(), ": internal error: output was not declared");
}

void OutputSet::stage(const fs::path& target, std::string_view bytes) {
  Entry& e = find(target);
  checkOutputPath(target);
  TempFile tmp(target);
  writeBytes(tmp.path(), target, bytes);
  if (!e.staged.empty()) {
    std::error_code ec;
    fs::remove(e.staged, ec);
  }
  e.staged = tmp.path();
  tmp.release();
  unregisterTemp(e.slot);
  e.slot = registerTemp(e.staged);  // still removed on a signal until committed
}

namespace {

// Exclusive flock()s on the directories of a set of outputs, released when it goes.
class DirectoryLocks {
 public:
  template <typename Entries>
  explicit DirectoryLocks(const Entries& entries) {
    std::vector<std::string> dirs;
    for (const auto& e : entries) dirs.push_back(comparable(directoryOf(e.target)).string());
    std::sort(dirs.begin(), dirs.end());
    dirs.erase(std::unique(dirs.begin(), dirs.end()), dirs.end());
    for (const std::string& d : dirs) {
      const int fd = ::open(d.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (fd < 0) continue;  // the rename reports what is wrong with it
      while (::flock(fd, LOCK_EX) != 0 && errno == EINTR) {
      }
      fds_.push_back(fd);
    }
  }
  ~DirectoryLocks() {
    for (int fd : fds_) ::close(fd);
  }
  DirectoryLocks(const DirectoryLocks&) = delete;
  DirectoryLocks& operator=(const DirectoryLocks&) = delete;

 private:
  std::vector<int> fds_;
};

}  // namespace

RunLock::RunLock(const fs::path& file, std::string_view who) {
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw makeError(file.string(), ": cannot open the run lock: ", std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  if (errno != EWOULDBLOCK) {
    const int err = errno;
    ::close(fd_);
    throw makeError(file.string(), ": cannot take the run lock: ", std::strerror(err));
  }
  waited_ = true;
  std::fprintf(stderr, "%.*s: another run holds %s; waiting for it to end\n", static_cast<int>(who.size()), who.data(),
               file.c_str());
  std::fflush(stderr);
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const int err = errno;
    ::close(fd_);
    throw makeError(file.string(), ": cannot take the run lock: ", std::strerror(err));
  }
}

RunLock::~RunLock() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputSet::commit() {
  for (const Entry& e : entries_) {
    if (e.staged.empty()) throw makeError(e.target.string(), ": internal error: output was not written");
  }
  // Two runs committing into the same place must not interleave their renames (a sequence
  // of frames half from one run, half from the other): the commit holds an exclusive lock
  // on every directory it writes into, taken in one sorted order so that two runs cannot
  // deadlock, and a second run waits for the first run's commit to end.
  const DirectoryLocks locks(entries_);
  for (Entry& e : entries_) {
    renameOver(e.staged, e.target);
    e.staged.clear();
    unregisterTemp(e.slot);
  }
}

}  // namespace shanshui
