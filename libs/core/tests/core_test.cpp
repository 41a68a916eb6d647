#include <fstream>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/parse.h"
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

}  // namespace
}  // namespace shanshui
