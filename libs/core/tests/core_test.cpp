#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <set>
#include <thread>
#include <vector>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/core/parallel_for.h"
#include "shanshui/core/parse.h"
#include "shanshui/core/random.h"
#include "test_support.h"

namespace shanshui {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(AtomicOutput, FailedWriteLeavesTheOldFileAndNoTemporaries) {
  test::TempDir dir;
  const auto target = dir / "result.txt";
  std::ofstream(target) << "good";
  EXPECT_THROW(writeAtomically(target,
                               [](const std::filesystem::path& tmp) {
                                 std::ofstream(tmp) << "half";
                                 throw Error("disk on fire");
                               }),
               Error);
  EXPECT_EQ(slurp(target), "good");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(AtomicOutput, SuccessfulWriteReplacesTheFile) {
  test::TempDir dir;
  const auto target = dir / "result.txt";
  std::ofstream(target) << "old";
  writeAtomically(target, [](const std::filesystem::path& tmp) {
    EXPECT_EQ(tmp.extension(), ".txt");  // format-sniffing writers see the real extension
    std::ofstream(tmp) << "new";
  });
  EXPECT_EQ(slurp(target), "new");
}

TEST(AtomicOutput, MissingDirectoryIsNamed) {
  try {
    writeAtomically("no/such/dir/x.png", [](const std::filesystem::path&) {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/dir"), std::string::npos) << e.what();
  }
}

TEST(OutputSet, NothingIsWrittenUntilCommitAndAllTogetherThen) {
  test::TempDir dir;
  std::ofstream(dir / "a.png") << "old a";
  {
    OutputSet out;
    out.declare(dir / "a.png", "-o", {".png"});
    out.declare(dir / "r.json", "--report", {".json"});
    out.stage(dir / "a.png", "new a");
    EXPECT_EQ(slurp(dir / "a.png"), "old a");  // staged, not yet visible
    out.stage(dir / "r.json", "{}");
    EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
    out.commit();
  }
  EXPECT_EQ(slurp(dir / "a.png"), "new a");
  EXPECT_EQ(slurp(dir / "r.json"), "{}");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 2);
}

TEST(OutputSet, AFailureBeforeCommitLeavesEveryTargetAndNoTemporary) {
  test::TempDir dir;
  std::ofstream(dir / "a.png") << "old a";
  try {
    OutputSet out;
    out.declare(dir / "a.png", "-o");
    out.declare(dir / "b.json", "--report");
    out.stage(dir / "a.png", "new a");
    throw Error("the report failed");
  } catch (const Error&) {
  }
  EXPECT_EQ(slurp(dir / "a.png"), "old a");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(OutputSet, RefusesSamePathsInputsUnknownExtensionsAndReadOnlyTargets) {
  test::TempDir dir;
  std::ofstream(dir / "in.png") << "input";
  std::filesystem::create_directories(dir / "sub");
  OutputSet out({dir / "in.png"});
  out.declare(dir / "x.obj", "-o");
  test::expectErrorNaming([&] { out.declare(dir / "sub/../x.obj", "--report"); }, "x.obj", "name the same file");
  test::expectErrorNaming([&] { out.declare(dir / "in.png", "-o"); }, "in.png", "names an input file");
  std::filesystem::create_symlink(dir / "in.png", dir / "link.png");
  test::expectErrorNaming([&] { out.declare(dir / "link.png", "-o"); }, "link.png", "input");
  test::expectErrorNaming(
      [&] {
        out.declare(dir / "c.xyz", "--checker", {".png", ".jpg"});
      },
      "c.xyz", "unknown extension '.xyz'; expected .png, .jpg");
  std::ofstream(dir / "ro.json") << "keep";
  std::filesystem::permissions(dir / "ro.json", std::filesystem::perms::owner_read);
  test::expectErrorNaming([&] { out.declare(dir / "ro.json", "--report"); }, "ro.json", "read-only");
  test::expectErrorNaming([&] { out.declare(dir / "none/r.json", "--report"); }, "r.json", "does not exist");
}

TEST(AtomicOutput, AFileSizeLimitIsAnErrorNamingTheTargetAndItsCause) {
  test::TempDir dir;
  const auto target = dir / "big.bin";
  std::ofstream(target) << "good";
  installTempFileCleanup();  // SIGXFSZ ignored: the write fails with EFBIG instead of killing us
  struct rlimit old {};
  ::getrlimit(RLIMIT_FSIZE, &old);
  struct rlimit lim = old;
  lim.rlim_cur = 1000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &lim), 0);
  std::string message;
  try {
    writeFileAtomically(target, std::string(5000, 'x'));
  } catch (const Error& e) {
    message = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  EXPECT_NE(message.find("big.bin: cannot write: File too large"), std::string::npos) << message;
  EXPECT_EQ(message.find(".tmp"), std::string::npos) << "names the temporary: " << message;
  EXPECT_EQ(slurp(target), "good");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(AtomicOutput, ASignalRemovesEveryStagedTemporaryHoweverManyAndHoweverLongTheirPaths) {
  // More staged outputs than the old 4096-slot table held (with SIGTERM; a few with the
  // others), some under a path longer than its 1024 bytes; a child stages them all, then
  // is terminated by the signal.
  for (int sig : {SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGPIPE}) {
    test::TempDir dir;
    std::filesystem::path deep = dir.path();
    while (deep.string().size() < 1200) deep /= std::string(200, 'd');
    std::filesystem::create_directories(deep);
    const pid_t child = ::fork();
    if (child == 0) {
      installTempFileCleanup();
      OutputSet out;
      std::vector<std::filesystem::path> targets;
      for (int i = 0; i < (sig == SIGTERM ? 4200 : 16); ++i)
        targets.push_back(dir / ("f" + std::to_string(i) + ".txt"));
      for (int i = 0; i < 8; ++i) targets.push_back(deep / ("g" + std::to_string(i) + ".txt"));
      for (const auto& t : targets) out.declare(t, "-o", {".txt"});
      for (const auto& t : targets) out.stage(t, "x");
      ::raise(sig);
      ::_exit(0);  // not reached
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << sig;
    EXPECT_EQ(WTERMSIG(status), sig);
    std::size_t left = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path())) left += e.is_regular_file();
    EXPECT_EQ(left, 0u) << "signal " << sig << ": temporaries left";
  }
}

TEST(AtomicOutput, TemporariesOfDeadProcessesAreSweptOthersKept) {
  test::TempDir dir;
  const auto target = dir / "frame.png";
  // A process id that is not running: a child that has exited and been reaped.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const auto stale = temporaryPath(target, dead, 3);
  const auto live = temporaryPath(target, ::getppid(), 4);       // our parent is running
  const auto other = temporaryPath(dir / "other.png", dead, 5);  // another output's
  for (const auto& p : {stale, live, other}) std::ofstream(p) << "x";
  writeFileAtomically(target, "new");
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(live));
  EXPECT_TRUE(std::filesystem::exists(other));
  EXPECT_EQ(slurp(target), "new");
}

// Two runs writing the same outputs must not leave a mix: a commit holds a lock on its
// directories, so while another process holds it the commit waits with everything staged.
TEST(AtomicOutput, ACommitWaitsWhileAnotherRunCommitsIntoTheSameDirectory) {
  test::TempDir dir;
  const int lock = ::open(dir.path().c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(lock, 0);
  ASSERT_EQ(::flock(lock, LOCK_EX), 0);
  const pid_t child = ::fork();
  if (child == 0) {
    OutputSet out;
    out.declare(dir / "a.txt", "-o");
    out.declare(dir / "b.txt", "--report");
    out.stage(dir / "a.txt", "A");
    out.stage(dir / "b.txt", "B");
    out.commit();
    ::_exit(0);
  }
  auto staged = [&] {
    int n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) n += e.path().filename().string()[0] == '.';
    return n;
  };
  for (int i = 0; i < 500 && staged() < 2; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(staged(), 2) << "the child staged both outputs";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(std::filesystem::exists(dir / "a.txt")) << "committed while another run held the directory";
  EXPECT_FALSE(std::filesystem::exists(dir / "b.txt"));
  ::flock(lock, LOCK_UN);
  ::close(lock);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(slurp(dir / "a.txt"), "A");
  EXPECT_EQ(slurp(dir / "b.txt"), "B");
  EXPECT_EQ(staged(), 0);
}

TEST(AtomicOutput, NonRegularInputsAreRefusedWithoutReading) {
  test::TempDir dir;
  std::filesystem::create_symlink("/dev/zero", dir / "zero.png");
  ASSERT_EQ(::mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
  test::expectErrorNaming([&] { checkInputFile(dir / "zero.png", "an image"); }, "zero.png", "not a regular file");
  test::expectErrorNaming([&] { checkInputFile(dir / "fifo.obj", "a mesh"); }, "fifo.obj", "not a regular file");
  test::expectErrorNaming([&] { readInputFile(dir / "fifo.obj", "a mesh", 10); }, "fifo.obj", "not a regular file");
  std::ofstream(dir / "big.json") << std::string(100, ' ');
  test::expectErrorNaming([&] { readInputFile(dir / "big.json", "a scene", 10); }, "big.json", "larger than the limit");
}

TEST(InputGate, StandardInputIsBoundedWhileItIsRead) {
  std::FILE* zero = std::fopen("/dev/zero", "rb");
  ASSERT_NE(zero, nullptr);
  test::expectErrorNaming([&] { readInputStream(zero, "stdin", "a --manifest", 1 << 20); }, "stdin",
                          "larger than the limit");
  std::fclose(zero);
  std::FILE* text = std::tmpfile();
  std::fputs("a b\n", text);
  std::rewind(text);
  EXPECT_EQ(readInputStream(text, "stdin", "a --manifest", 1 << 20), "a b\n");
  std::fclose(text);
}

TEST(InputGate, DirectoriesAndEmptyFilesAreRefusedByName) {
  test::TempDir dir;
  std::filesystem::create_directory(dir / "scene.json");
  std::ofstream(dir / "empty.obj").flush();
  test::expectErrorNaming([&] { readInputFile(dir / "scene.json", "a scene", 100); }, "scene.json", "is a directory");
  test::expectErrorNaming([&] { checkInputFile(dir / "empty.obj", "a mesh"); }, "empty.obj", "empty file");
  test::expectErrorNaming([&] { checkInputFile(dir / "gone.obj", "a mesh"); }, "gone.obj", "no such file");
}

TEST(MemoryBudget, SizesParseAndANeedAboveTheBudgetIsRefused) {
  EXPECT_EQ(parseByteSize("512M", "--max-memory"), std::uintmax_t{512} << 20);
  EXPECT_EQ(parseByteSize("2g", "--max-memory"), std::uintmax_t{2} << 30);
  EXPECT_EQ(parseByteSize("4096", "--max-memory"), 4096u);
  for (const char* bad : {"", "0", "-1", "12Q", "1.5G", "G", "99999999999999999999"}) {
    test::expectErrorNaming([&] { parseByteSize(bad, "--max-memory"); }, "--max-memory", "not a memory size");
  }
  setMemoryBudget(1 << 20);
  EXPECT_NO_THROW(checkMemoryNeed("dem.tif", "the grid", 1 << 20));
  test::expectErrorNaming([&] { checkMemoryNeed("dem.tif", "the grid", (1 << 20) + 1); }, "dem.tif",
                          "more than the memory budget of 1.0 MiB");
  setMemoryBudget(0);
  EXPECT_GT(memoryBudget(), std::uintmax_t{1} << 20) << "the default: half this machine's memory";
}

TEST(Parse, SizeAcceptsWxHAndRejectsEverythingElse) {
  EXPECT_EQ(parseSize("1024x768", "--size").width, 1024);
  EXPECT_EQ(parseSize("3X5", "--size").height, 5);
  for (const char* bad : {"", "1024", "0x5", "-3x4", "4x", "x4", "4x4x4", "1e3x2", "abc"}) {
    EXPECT_THROW(parseSize(bad, "--size"), Error) << bad;
  }
  try {
    parseSize("12y", "--size");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--size: '12y'"), std::string::npos) << e.what();
  }
}

TEST(Parse, DoubleRejectsTrailingJunkAndNonFinite) {
  EXPECT_DOUBLE_EQ(parseDouble("2.5", "x"), 2.5);
  for (const char* bad : {"", "2.5m", "nan", "inf", "--"}) EXPECT_THROW(parseDouble(bad, "x"), Error) << bad;
}

TEST(Parse, PairNeedsTwoNumbersAroundAColon) {
  EXPECT_EQ(parsePair("0.1:0.9", "--range"), std::make_pair(0.1, 0.9));
  EXPECT_EQ(parsePair("-1:2e3", "--range"), std::make_pair(-1.0, 2000.0));
  for (const char* bad : {"0.5", "0.1:", ":0.9", "a:b", "0.1:0.2:0.3", "nan:1"}) {
    test::expectErrorNaming([&] { parsePair(bad, "--range"); }, "--range", bad);
  }
}

// Under an address-space limit a failed operator new is noted (memoryRanOut), so the GL
// wrappers stop calling a driver that may hang after running out; without a limit neither a
// failed allocation nor a driver's report is noted. In a child process, which sets the limit.
TEST(AtomicOutput, RunningOutOfMemoryIsNotedOnlyUnderAnAddressSpaceLimit) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no limit leaves it room";
#endif
  rlimit own{};
  ASSERT_EQ(::getrlimit(RLIMIT_AS, &own), 0);
  if (own.rlim_cur != RLIM_INFINITY) GTEST_SKIP() << "this test process already runs under a limit";
  auto child = [](bool limit) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (limit) {
        const rlimit lim{rlim_t{2} << 30, rlim_t{2} << 30};
        ::setrlimit(RLIMIT_AS, &lim);
      }
      guardCrashesUnderMemoryLimit("the test");
      int code = memoryRanOut() ? 10 : 0;
      try {
        std::vector<char> big(std::size_t{64} << 40);  // 64 TiB: fails with or without a limit
        code = 11;
      } catch (const std::bad_alloc&) {
        if (memoryRanOut() != limit) code = 12;
      }
      ::_exit(code);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
  };
  EXPECT_EQ(child(true), 0) << "under a limit the failure is noted";
  EXPECT_EQ(child(false), 0) << "without one it is not";
  noteMemoryRanOut();  // this process has no limit: a driver's report changes nothing
  EXPECT_FALSE(memoryRanOut());
}

TEST(AtomicOutput, CheckOutputPathRefusesBeforeAnyWork) {
  test::TempDir dir;
  EXPECT_NO_THROW(checkOutputPath(dir / "fine.png"));
  test::expectErrorNaming([&] { checkOutputPath(dir / "missing/out.png"); }, "out.png", "directory does not exist");
  test::expectErrorNaming([&] { checkOutputPath(dir.path()); }, dir.path().string(), "is a directory");
}

TEST(ParallelFor, VisitsEveryIndexOnceForAnyThreadCount) {
  for (int threads : {1, 2, 5, 64}) {
    for (int count : {0, 1, 7, 1000}) {
      std::vector<std::atomic<int>> visits(static_cast<std::size_t>(count));
      parallelFor(count, threads, [&](int i) { ++visits[static_cast<std::size_t>(i)]; });
      for (int i = 0; i < count; ++i)
        ASSERT_EQ(visits[static_cast<std::size_t>(i)], 1) << threads << " threads, index " << i;
    }
  }
  EXPECT_GE(resolveThreads(0), 1);
  EXPECT_EQ(resolveThreads(3), 3);
}

TEST(ParallelFor, RethrowsTheWorkersException) {
  for (int threads : {1, 3}) {
    std::atomic<int> done{0};
    EXPECT_THROW(parallelFor(100, threads,
                             [&](int i) {
                               if (i == 10) throw Error("item 10 failed");
                               ++done;
                             }),
                 Error);
    EXPECT_LT(done, 100);
  }
}

TEST(Random, StreamsAreDistinctAndReproducible) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t seed : {0ull, 1ull, 2ull}) {
    for (std::uint64_t i = 0; i < 1000; ++i) seen.insert(streamValue(seed, i));
  }
  EXPECT_EQ(seen.size(), 3000u);
  EXPECT_EQ(streamValue(7, 3), streamValue(7, 3));
  // SplitMix64's published first output for seed 0 (state advanced once by the golden gamma).
  EXPECT_EQ(splitMix64(0), 0xe220a8397b1dcdafull);
}

}  // namespace
}  // namespace shanshui

namespace shanshui {
namespace {

// A failed check aborts and prints the condition with both values.
TEST(CheckDeathTest, ComparisonsPrintBothValues) {
  const int three = 3, four = 4;
  EXPECT_DEATH(SHANSHUI_CHECK_EQ(three, four), "CHECK\\(three == four\\) with 3 vs 4");
  EXPECT_DEATH(SHANSHUI_CHECK_NE(three, three), "CHECK\\(three != three\\) with 3 vs 3");
  EXPECT_DEATH(SHANSHUI_CHECK_GT(three, four), "CHECK\\(three > four\\) with 3 vs 4");
  EXPECT_DEATH(SHANSHUI_CHECK_GE(three, four), "CHECK\\(three >= four\\) with 3 vs 4");
  EXPECT_DEATH(SHANSHUI_CHECK_LT(four, three), "CHECK\\(four < three\\) with 4 vs 3");
  EXPECT_DEATH(SHANSHUI_CHECK_LE(four, three), "CHECK\\(four <= three\\) with 4 vs 3");
  SHANSHUI_CHECK_NE(three, four);
  SHANSHUI_CHECK_GT(four, three);
  SHANSHUI_CHECK_GE(three, three);
}

}  // namespace
}  // namespace shanshui
