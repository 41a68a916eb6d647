// Batch use (issue 8): every asset tool and the headless renderer take --manifest; one
// failing item is reported by line with its error, writes nothing, and the others finish.
#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "json_text.h"
#include "shanshui/image/image_io.h"
#include "shanshui/mesh/mesh_io.h"
#include "test_support.h"

namespace shanshui {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::run;

std::string bin(const char* name) {
  return quote(test::binDir() / name);
}

void writeText(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

struct ToolCase {
  const char* tool;
  std::string input;   // quoted
  std::string rest;    // the other arguments, before -o
  std::string output;  // the file the good item writes
};

TEST(Batch, EveryToolRunsAManifestAndReportsTheFailedItemByLine) {
  const test::TempDir dir;
  const fs::path dem = test::sourceDir() / "samples/terrain/mount_st_helens.dem";
  const fs::path scan = test::sourceDir() / "samples/textures/rain_strokes_scan.png";
  auto r = run(bin("shanshui-terrain") + " " + quote(dem) + " -o " + quote(dir / "small.obj") + " --max-vertices 1500");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string mesh = "'" + (dir / "small.obj").string() + "'";
  const std::vector<ToolCase> cases = {
      {"shanshui-terrain", "'" + dem.string() + "'", "--max-vertices 1500", "out terrain.obj"},
      {"shanshui-repair", mesh, "", "repaired.obj"},
      {"shanshui-enhance", "'" + scan.string() + "'", "", "enhanced.png"},
      {"shanshui-quilt", "'" + scan.string() + "'", "--size 64x64", "quilted.png"},
      {"shanshui-param", mesh, "", "param.obj"},
      {"shanshui-render", mesh, "--size 64x48", "render.png"},
  };
  for (const ToolCase& c : cases) {
    SCOPED_TRACE(c.tool);
    const fs::path work = dir / c.tool;
    fs::create_directories(work);
    // Line 1: a comment; line 3: a missing input (its output must not appear); line 4: good.
    const std::string bad = "bad" + fs::path(c.output).extension().string();
    writeText(work / "items.txt", "# two items\n\nno_such_input.xyz " + c.rest + " -o " + bad + "\n" + c.input + " " +
                                      c.rest + " -o '" + c.output + "'\n");
    r = run("cd " + quote(work) + " && " + bin(c.tool) + " --manifest items.txt");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("batch of 2: 1 done, 1 failed"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("line 3: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("no_such_input.xyz"), std::string::npos) << "the error names the file: " << r.output;
    EXPECT_NE(r.output.find("[2/2]"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(work / c.output)) << "the good item still ran";
    EXPECT_FALSE(fs::exists(work / bad));
  }
}

TEST(Batch, SharedArgumentsStdinAndSyntaxErrors) {
  const test::TempDir dir;
  const fs::path dem = test::sourceDir() / "samples/terrain/mount_st_helens.dem";
  // Shared --size for every render item, the manifest from stdin.
  const std::string items = "'" + dem.string() + "' -o a.png\n'" + dem.string() + "' -o \"b b.png\" # spaces quoted\n";
  writeText(dir / "items.txt", items);
  auto r = run("cd " + quote(dir.path()) + " && " + bin("shanshui-render") + " --size 48x32 --manifest - < items.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("batch of 2: 2 done, 0 failed"), std::string::npos) << r.output;
  for (const char* f : {"a.png", "b b.png"}) {
    const image::Image img = image::loadImage(dir / f);
    EXPECT_EQ(img.width, 48);
    EXPECT_EQ(img.height, 32);
  }
  // An unterminated quote and a nested manifest fail their own lines only.
  writeText(dir / "bad.txt",
            "'" + dem.string() + "' -o 'c.png\n--manifest other.txt\n'" + dem.string() + "' -o d.png\n");
  r = run("cd " + quote(dir.path()) + " && " + bin("shanshui-render") + " --size 48x32 --manifest bad.txt");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("line 1: unterminated ' quote"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("line 2: an item cannot name another manifest"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "d.png"));
  EXPECT_FALSE(fs::exists(dir / "c.png"));
  // Two manifests in one call are refused (an item run would otherwise start a batch).
  r = run("cd " + quote(dir.path()) + " && " + bin("shanshui-render") + " --manifest items.txt --manifest=bad.txt");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--manifest given 2 times"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  // A manifest that cannot be read, or has no items: one line naming it, nothing run.
  for (const std::string& m : {std::string("missing.txt"), std::string("empty.txt")}) {
    writeText(dir / "empty.txt", "# nothing\n\n");
    r = run("cd " + quote(dir.path()) + " && " + bin("shanshui-enhance") + " --manifest " + m);
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find(m), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

// The manifest passes the input gate: a FIFO, a link to /dev/zero or /dev/zero on stdin is
// one line naming it, at once, instead of a hang or a gigabyte read.
TEST(Batch, AManifestThatCouldNeverEndIsRefusedByName) {
  const test::TempDir dir;
  ASSERT_EQ(::mkfifo((dir / "fifo.txt").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", dir / "zero.txt");
  for (const char* m : {"fifo.txt", "zero.txt"}) {
    const auto r = run("cd " + quote(dir.path()) + " && timeout 20 " + bin("shanshui-enhance") + " --manifest " + m);
    EXPECT_EQ(r.exit_code, 1) << m << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(m) + ": not a regular file"), std::string::npos) << r.output;
  }
  const auto r = run("timeout 20 " + bin("shanshui-enhance") + " --manifest - < /dev/zero");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("stdin: more than"), std::string::npos) << r.output;
}

// Every report goes through jsonText: a NaN or an infinity (which JSON writes as null) is an
// error naming the report and the value's key, before anything is written.
TEST(Reports, ANonFiniteValueIsRefusedByItsKey) {
  nlohmann::json j = {{"faces", 12}, {"stats", {{"ink", 0.5}, {"per_frame", {1.0, std::nan("")}}}}};
  test::expectErrorNaming([&] { tools::jsonText(j, "r.json"); }, "r.json", "/stats/per_frame/1");
  j["stats"]["per_frame"][1] = -std::numeric_limits<double>::infinity();
  test::expectErrorNaming([&] { tools::jsonText(j, "r.json"); }, "r.json", "not finite (-inf)");
  j["stats"]["per_frame"][1] = 2.0;
  EXPECT_EQ(nlohmann::json::parse(tools::jsonText(j, "r.json")), j);
}

}  // namespace
}  // namespace shanshui
