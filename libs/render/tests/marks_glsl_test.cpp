// The wet strokes' shortcut (shaders/ink/ink_marks.glsl's washGroup: of a group's strokes,
// only the two nearest a point are drawn, the second laid over the first) against the brute
// force, every stroke of the group layered, evaluated at the same points by a compute shader
// (shaders/ink/wash_probe.comp).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gl_probe.h"
#include "gl_test.h"
#include "shanshui/render/shader_program.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using MarksGlsl = test::HeadlessGl;

struct GroupInk {
  float shortcut, all_layered, darkest, strokes;
};

// Groups 0 .. groups − 1 of breadth `breadth`, each probed on a grid of offsets from its
// centre across the reach a group has (0.42 of a cell).
std::vector<GroupInk> probeGroups(float breadth, int groups, int grid) {
  std::vector<glm::vec4> points;
  for (int g = 0; g < groups; ++g)
    for (int y = 0; y < grid; ++y)
      for (int x = 0; x < grid; ++x)
        points.push_back(
            {-0.42f + 0.84f * x / (grid - 1), -0.42f + 0.84f * y / (grid - 1), breadth, static_cast<float>(g)});
  return test::runProbe<GroupInk>(Program({"wash_probe.comp"}), points);
}

TEST_F(MarksGlsl, TwoNearestStrokesLayeredAreTheWholeGroupLayeredAtEveryBreadth) {
  for (const float breadth : {0.5f, 1.0f, 1.2f, 1.5f, 2.0f, 2.5f}) {
    SCOPED_TRACE("wash_width " + std::to_string(breadth));
    const std::vector<GroupInk> v = probeGroups(breadth, 120, 41);
    double worst = 0.0;
    int inked = 0, overlapped = 0;
    for (const GroupInk& g : v) {
      worst = std::max(worst, static_cast<double>(std::abs(g.shortcut - g.all_layered)));
      if (g.all_layered > 0.05f) ++inked;
      // Where two strokes lie, layering is darker than either alone.
      if (g.all_layered > g.darkest + 0.05f) ++overlapped;
    }
    ASSERT_GT(inked, static_cast<int>(v.size() / 50)) << "the groups draw strokes";
    // Float rounding of the same terms taken in another order: the third-nearest stroke lies a
    // gap away, farther than any stroke's half-width, and adds nothing.
    EXPECT_LT(worst, 1e-5);
    if (breadth > 1.0f) {
      // A broad group's strokes lie closer than their width: some of its ink is two strokes
      // over each other (about 1-3 % of the inked points, at the strokes' edges and between
      // their heads), which drawing the nearest one alone would lose.
      EXPECT_GT(overlapped, inked / 200) << overlapped << " of " << inked;
      EXPECT_GT(v.front().strokes, 3.5f);
    } else {
      // Thin strokes stand apart: no point lies under two.
      EXPECT_EQ(overlapped, 0);
    }
  }
}

// washOctave looks at a point's own cell alone, and only within 0.42 of its group's centre:
// a stroke reaching farther would be cut off there along a circle. Every stroke of every
// group, at every breadth, is probed on rings just beyond that reach.
TEST_F(MarksGlsl, NoGroupReachesBeyondItsCellsReach) {
  for (const float breadth : {0.5f, 1.0f, 1.5f, 2.0f, 2.5f}) {
    SCOPED_TRACE("wash_width " + std::to_string(breadth));
    std::vector<glm::vec4> points;
    for (int g = 0; g < 400; ++g)
      for (const float r : {0.421f, 0.45f, 0.5f, 0.6f})
        for (int k = 0; k < 360; ++k) {
          const float angle = static_cast<float>(k) * 0.0174533f;
          points.push_back({r * std::cos(angle), r * std::sin(angle), breadth, static_cast<float>(g)});
        }
    const std::vector<GroupInk> v = test::runProbe<GroupInk>(Program({"wash_probe.comp"}), points);
    float darkest = 0.0f;
    for (const GroupInk& g : v) darkest = std::max(darkest, g.all_layered);
    EXPECT_EQ(darkest, 0.0f);
  }
}

}  // namespace
}  // namespace shanshui::render
