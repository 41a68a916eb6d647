// Placement of trees and moss dots on synthetic terrains whose slope, height and form are
// known analytically, and the brushwork grown for each kind.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include <gtest/gtest.h>

#include "shanshui/core/error.h"
#include "shanshui/elements/brushwork.h"
#include "shanshui/elements/placement.h"
#include "shanshui/mesh/shapes.h"

namespace shanshui::elements {
namespace {

// Mean distance from each point to its nearest neighbour over what a uniform (Poisson)
// scatter of the same count over `area` gives, 0.5 / sqrt(density): Clark and Evans' ratio,
// 1 for an even random scatter, well below 1 for clusters.
double clarkEvans(const std::vector<Instance>& v, double area) {
  double sum = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    double best = std::numeric_limits<double>::max();
    for (std::size_t j = 0; j < v.size(); ++j) {
      if (i == j) continue;
      const double dx = v[i].position.x - v[j].position.x, dy = v[i].position.y - v[j].position.y;
      best = std::min(best, dx * dx + dy * dy);
    }
    sum += std::sqrt(best);
  }
  return sum / static_cast<double>(v.size()) / (0.5 / std::sqrt(static_cast<double>(v.size()) / area));
}

std::size_t treesIn(const std::vector<Instance>& v) {
  return static_cast<std::size_t>(
      std::count_if(v.begin(), v.end(), [](const Instance& i) { return i.kind != Kind::MossDot; }));
}

TreeOptions trees(double density) {
  TreeOptions t;
  t.enabled = true;
  t.density = density;
  return t;
}

// A flat plane, 2 km a side, in metres.
mesh::Mesh flat() {
  return mesh::heightGrid(41, 41, 50.0, [](double, double) { return 0.0; });
}

TEST(Placement, NoTreeAboveTheSlopeLimitOrOutsideTheBand) {
  // z = x² / (2L): the slope atan(x / L) rises from 0 to 45° across the square, the height
  // fraction is (x / side)².
  const double side = 1000.0, L = 1000.0;
  const mesh::Mesh m = mesh::heightGrid(101, 21, side / 100.0, [&](double x, double) { return x * x / (2 * L); });
  TreeOptions t = trees(60.0);
  t.max_slope_deg = 25.0;
  t.band = {0.05, 0.4};
  t.open = 1.0;
  const std::vector<Instance> v = placeElements(m, t, {}, 7);
  ASSERT_GT(v.size(), 50u);
  double steepest = 0.0, lowest = 1.0, highest = 0.0;
  for (const Instance& i : v) {
    const double slope = glm::degrees(std::atan(i.position.x / L));
    const double h = i.position.x * i.position.x / (2 * L) / (side * side / (2 * L));
    steepest = std::max(steepest, slope);
    lowest = std::min(lowest, h);
    highest = std::max(highest, h);
    // On the surface: the mesh is piecewise linear under the parabola by at most cell² / 8L.
    EXPECT_NEAR(i.position.z, i.position.x * i.position.x / (2 * L), 0.02);
  }
  // The mesh's facets are steeper than the parabola at their left end by half a cell.
  EXPECT_LE(steepest, 25.0 + 0.5);
  EXPECT_GT(steepest, 20.0);  // the limit, not something stricter, bounds them
  EXPECT_GE(lowest, 0.05);
  EXPECT_LE(highest, 0.4 + 1e-9);
  // Band x from √0.05 = 224 m up to the slope limit's x = L·tan 25° = 466 m (√0.4 is beyond).
  for (const Instance& i : v) EXPECT_TRUE(i.position.x > 215.0 && i.position.x < 470.0) << i.position.x;
}

TEST(Placement, DensityFollowsTheRuleOnAFullySuitedPlane) {
  // A plain whose open slopes get the full density: density × 400 ha trees, whatever the
  // groves.
  for (double grove : {1.0, 8.0}) {
    SCOPED_TRACE(grove);
    TreeOptions t = trees(2.0);
    t.grove = grove;
    t.open = 1.0;
    double total = 0.0;
    const int runs = 6;
    for (int seed = 1; seed <= runs; ++seed) total += static_cast<double>(placeElements(flat(), t, {}, seed).size());
    const double expected = 2.0 * 400.0;
    // One run's count has a standard deviation of √(800 (1 + grove)) (Thomas process); the
    // mean of six, 4 standard deviations.
    const double sd = std::sqrt(expected * (1.0 + grove) / runs);
    EXPECT_NEAR(total / runs, expected, 4.0 * sd);
    EXPECT_LT(4.0 * sd / expected, 0.2);  // the tolerance stated: within 20 %
  }
}

TEST(Placement, TreesStandInGrovesNotAnEvenScatter) {
  TreeOptions t = trees(2.0);
  t.open = 1.0;
  t.grove = 10.0;
  t.grove_radius = 40.0;
  const std::vector<Instance> groves = placeElements(flat(), t, {}, 3);
  t.grove = 1.0;
  const std::vector<Instance> scatter = placeElements(flat(), t, {}, 3);
  const double area = 2000.0 * 2000.0;
  EXPECT_LT(clarkEvans(groves, area), 0.75);
  EXPECT_NEAR(clarkEvans(scatter, area), 1.0, 0.12);
}

TEST(Placement, RidgesAndHollowsDrawMoreTreesThanOpenSlopes) {
  // Parallel ridges and valleys, 400 m apart, 60 m of relief: crests and troughs near
  // x = 100 + 200 k, open mid-slopes between.
  const mesh::Mesh m = mesh::heightGrid(
      81, 41, 25.0, [](double x, double) { return 30.0 * std::sin(2 * std::numbers::pi * x / 400.0); });
  TreeOptions t = trees(6.0);
  t.open = 0.1;
  t.band = {0.0, 1.0};
  t.max_slope_deg = 60.0;
  const std::vector<Instance> v = placeElements(m, t, {}, 11);
  double formed = 0.0, open = 0.0;
  for (const Instance& i : v) {
    if (i.position.x < 200.0 || i.position.x > 1800.0) continue;  // away from the mesh's edges
    const double phase = std::fmod(i.position.x, 200.0);          // 100: crest or trough
    if (std::abs(phase - 100.0) < 30.0) formed += 1.0;
    if (phase < 30.0 || phase > 170.0) open += 1.0;  // the mid-slopes, same width of land
  }
  EXPECT_GT(formed, 2.5 * open) << formed << " on crests and troughs, " << open << " on open slopes";
}

TEST(Placement, TheSameSeedPlacesTheSameElements) {
  const mesh::Mesh m = mesh::heightGrid(
      61, 61, 20.0, [](double x, double y) { return 80.0 * std::sin(x / 200.0) * std::cos(y / 170.0); });
  DotOptions d;
  d.enabled = true;
  d.density = 4.0;
  const std::vector<Instance> a = placeElements(m, trees(8.0), d, 5), b = placeElements(m, trees(8.0), d, 5);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_EQ(a[i].seed, b[i].seed);
    EXPECT_EQ(a[i].kind, b[i].kind);
  }
  const std::vector<Instance> c = placeElements(m, trees(8.0), d, 6);
  EXPECT_TRUE(c.size() != a.size() || c.front().position != a.front().position);
  // The trees' own seed overrides the scene's.
  TreeOptions own = trees(8.0);
  own.seed = 5;
  EXPECT_EQ(treesIn(placeElements(m, own, {}, 99)), treesIn(placeElements(m, trees(8.0), {}, 5)));
}

// A small change to the ground changes the trees and dots where it changed, not all of
// them: each candidate draws from its own stream, so one the ground no longer takes does not
// move the draws of the next. Raised by 3 %, the hills' slopes and heights shift a little and
// some trees near the rules' limits come and go; nine in ten of the elements stay exactly
// where they stood (before, the first tree that came or went moved every one after it).
TEST(Placement, ASmallChangeToTheGroundMovesFewElements) {
  auto hills = [](double scale) {
    return mesh::heightGrid(61, 61, 20.0, [scale](double x, double y) {
      return scale * (80.0 * std::sin(x / 200.0) * std::cos(y / 170.0) + 15.0 * std::sin(x / 37.0 + y / 53.0));
    });
  };
  DotOptions d;
  d.enabled = true;
  d.density = 4.0;
  TreeOptions t = trees(8.0);
  t.open = 0.3;
  const std::vector<Instance> a = placeElements(hills(1.0), t, d, 5), b = placeElements(hills(1.03), t, d, 5);
  ASSERT_GT(a.size(), 200u);
  std::set<std::pair<float, float>> where;
  for (const Instance& i : a) where.insert({i.position.x, i.position.y});
  std::size_t kept = 0;
  for (const Instance& i : b) kept += where.count({i.position.x, i.position.y});
  EXPECT_NE(a.size(), b.size()) << "the change should take or give some trees";
  EXPECT_GT(static_cast<double>(kept), 0.9 * static_cast<double>(std::min(a.size(), b.size())))
      << kept << " of " << a.size() << " and " << b.size() << " stayed";
}

TEST(Placement, MossDotsGatherOnRidgesAndRockEdgesAndAtTreeFeet) {
  // One ridge along y with steep flanks, flat land either side.
  const mesh::Mesh m = mesh::heightGrid(
      81, 41, 25.0, [](double x, double) { return 200.0 * std::exp(-std::pow((x - 1000.0) / 150.0, 2)); });
  DotOptions d;
  d.enabled = true;
  d.density = 20.0;
  d.at_trees = 0.0;
  const std::vector<Instance> v = placeElements(m, {}, d, 2);
  ASSERT_GT(v.size(), 20u);
  std::size_t near_ridge = 0;
  for (const Instance& i : v) {
    EXPECT_EQ(i.kind, Kind::MossDot);
    near_ridge += std::abs(i.position.x - 1000.0) < 300.0;
  }
  // The ridge and its flanks are 600 m of the 2000 m: an even scatter would put 30 % there.
  EXPECT_GT(static_cast<double>(near_ridge), 0.9 * static_cast<double>(v.size()));
  // At the feet of trees: every tree gets one to three.
  d.density = 0.0;
  d.at_trees = 1.0;
  TreeOptions t = trees(2.0);
  t.open = 1.0;
  const std::vector<Instance> feet = placeElements(flat(), t, d, 4);
  const std::size_t n = treesIn(feet);
  EXPECT_GE(feet.size() - n, n);
  EXPECT_LE(feet.size() - n, 3 * n);
}

// Land wider than 3 km masses its trees and dots: on ridged land 12 km across (f = 3/12)
// the placement is, to the bit, the one asked with massing off and groves of 4 x 18 trees,
// a quarter of the open share and a quarter of the dots' density; its trees stand in
// tighter clumps than the same keys unmassed (Clark and Evans' ratio); on land 2.4 km
// across the keys are used as they are.
TEST(Placement, WideLandMassesItsTreesInFewerDenserGroves) {
  auto ridges = [](double x, double y) { return 300.0 * std::sin(x / 900.0) * std::cos(y / 1300.0); };
  const mesh::Mesh wide = mesh::heightGrid(121, 121, 100.0, ridges);
  TreeOptions t = trees(0.3);
  DotOptions d;
  d.enabled = true;
  EXPECT_DOUBLE_EQ(massing(t.massed_beyond, 12000.0), 0.25);
  TreeOptions by_hand = t;
  by_hand.massed_beyond = 0.0;
  by_hand.grove = 4.0 * t.grove;
  by_hand.open = 0.25 * t.open;
  DotOptions dots_by_hand = d;
  dots_by_hand.massed_beyond = 0.0;
  dots_by_hand.density = 0.25 * d.density;
  const std::vector<Instance> massed = placeElements(wide, t, d, 7);
  const std::vector<Instance> asked = placeElements(wide, by_hand, dots_by_hand, 7);
  ASSERT_EQ(massed.size(), asked.size());
  ASSERT_GT(treesIn(massed), 300u);
  for (std::size_t i = 0; i < massed.size(); ++i) {
    ASSERT_EQ(massed[i].position, asked[i].position) << i;
    ASSERT_EQ(massed[i].seed, asked[i].seed) << i;
  }
  TreeOptions plain = t;
  plain.massed_beyond = 0.0;
  const DotOptions no_dots;
  const std::vector<Instance> massed_trees = placeElements(wide, t, no_dots, 7),
                              plain_trees = placeElements(wide, plain, no_dots, 7);
  const double area = 12000.0 * 12000.0;
  EXPECT_LT(clarkEvans(massed_trees, area), 0.6 * clarkEvans(plain_trees, area));

  const mesh::Mesh narrow = mesh::heightGrid(121, 121, 20.0, ridges);
  TreeOptions dense = trees(20.0), dense_plain = dense;
  dense_plain.massed_beyond = 0.0;
  DotOptions dots_plain = d;
  dots_plain.massed_beyond = 0.0;
  const std::vector<Instance> a = placeElements(narrow, dense, d, 7),
                              b = placeElements(narrow, dense_plain, dots_plain, 7);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i].position, b[i].position) << i;
}

TEST(Placement, TooManyElementsIsAnErrorNamingTheKey) {
  try {
    placeElements(flat(), trees(10000.0), {}, 1, "objects.0");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("objects.0.trees.density"), std::string::npos) << e.what();
  }
}

TEST(Placement, NothingAskedNothingPlaced) {
  EXPECT_TRUE(placeElements(flat(), {}, {}, 1).empty());
  EXPECT_TRUE(placeElements(mesh::Mesh{}, trees(5.0), {}, 1).empty());
  TreeOptions none = trees(5.0);
  none.kinds = {0.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(placeElements(flat(), none, {}, 1).empty()) << "no kind of tree asked for";
}

TEST(Brushwork, LevelWeightsSumToOneAndChangeContinuously) {
  std::array<float, 3> last = levelWeights(0.0);
  EXPECT_EQ(last[0], 1.0f);
  double largest_step = 0.0;
  for (double px = 0.0; px <= 100.0; px += 0.01) {
    const std::array<float, 3> w = levelWeights(px);
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-6);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(w[k], 0.0f);
      largest_step = std::max(largest_step, static_cast<double>(std::abs(w[k] - last[k])));
    }
    last = w;
  }
  EXPECT_LT(largest_step, 0.005);  // 0.01 px moves no weight by more than half a percent
  EXPECT_EQ(levelWeights(100.0)[2], 1.0f);
}

TEST(Brushwork, EveryKindGrowsMoreMarksNearThanFarWithinItsHeight) {
  for (Kind k : {Kind::Pine, Kind::Leafy, Kind::Bare, Kind::Distant}) {
    for (std::uint32_t seed : {1u, 2u, 77u}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(k)) + " seed " + std::to_string(seed));
      const std::vector<Mark> marks = growBrushwork(k, seed);
      std::array<int, 3> at{};
      for (const Mark& m : marks) {
        for (int l = 0; l < 3; ++l) at[l] += (m.levels >> l) & 1;
        for (glm::vec2 p : {m.a, m.b}) {
          EXPECT_GE(p.y, -0.05f);
          EXPECT_LE(p.y, 1.1f);
          EXPECT_LE(std::abs(p.x), 0.6f);
        }
        EXPECT_GT(m.width, 0.0f);
        EXPECT_GT(m.ink, 0.0f);
        EXPECT_LE(m.ink, 1.0f);
      }
      EXPECT_GE(at[0], 1);
      EXPECT_GT(at[1], at[0]);
      EXPECT_GT(at[2], 3 * at[1]);
      // Grown from the seed: the same marks again, others for another seed.
      const std::vector<Mark> again = growBrushwork(k, seed);
      ASSERT_EQ(again.size(), marks.size());
      for (std::size_t i = 0; i < marks.size(); ++i) EXPECT_EQ(again[i].b, marks[i].b);
      const std::vector<Mark> other = growBrushwork(k, seed + 1000);
      bool differs = other.size() != marks.size();
      for (std::size_t i = 0; !differs && i < marks.size(); ++i) differs = other[i].b != marks[i].b;
      EXPECT_TRUE(differs);
    }
  }
}

// In the middle distance (14 to 88 px high) no part of a tree hangs over empty ground: the
// heights its middle-level marks cover, each mark's axis widened by half its width across
// it, run without a gap from the foot to its top. A distant tree's two dabs began at 0.38 of
// its height over nothing, and a leafy tree's clumps at about half over a trunk that ends at
// the fork: on a pale bank they floated.
TEST(Brushwork, NoTreeHangsOverEmptyGroundInTheMiddleDistance) {
  for (Kind k : {Kind::Pine, Kind::Leafy, Kind::Bare, Kind::Distant}) {
    for (std::uint32_t seed = 1; seed <= 40; ++seed) {
      SCOPED_TRACE(std::to_string(static_cast<int>(k)) + " seed " + std::to_string(seed));
      std::vector<std::pair<float, float>> spans;
      for (const Mark& m : growBrushwork(k, seed)) {
        if ((m.levels & kMiddle) == 0) continue;
        const glm::vec2 d = m.b - m.a;
        const float across = glm::length(d) > 0.0f ? 0.5f * m.width * std::abs(d.x) / glm::length(d) : 0.5f * m.width;
        spans.emplace_back(std::min(m.a.y, m.b.y) - across, std::max(m.a.y, m.b.y) + across);
      }
      ASSERT_FALSE(spans.empty());
      std::sort(spans.begin(), spans.end());
      EXPECT_LE(spans.front().first, 0.01f) << "stands on its foot";
      float reached = spans.front().second;
      for (const auto& [lo, hi] : spans) {
        EXPECT_LE(lo, reached + 0.01f) << "a gap from " << reached << " to " << lo;
        reached = std::max(reached, hi);
      }
    }
  }
}

// Drawn near, a distant-kind tree (standing large on a near bank) is a mass of small upright
// dots that fills its crown, not a few large dabs each a fifth of the tree, which read as
// separate grey ovals. Oracle: the crown's ellipse (centre 0.57 up, half-axes 0.13 and 0.21)
// sampled on a grid, each point covered when it lies within half a mark's width of the
// mark's axis.
TEST(Brushwork, ADistantTreeDrawnNearIsAMassOfSmallDots) {
  for (std::uint32_t seed : {1u, 2u, 77u, 1234u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::vector<Mark> dots;
    for (const Mark& m : growBrushwork(Kind::Distant, seed))
      if (m.levels == kNear && m.shape == Shape::Leaf) dots.push_back(m);
    EXPECT_GE(dots.size(), 20u);
    for (const Mark& m : dots) {
      EXPECT_LE(m.width, 0.06f) << "a dot a tenth of the crown's width at most";
      EXPECT_GT(std::abs(m.b.y - m.a.y), std::abs(m.b.x - m.a.x)) << "upright";
    }
    int inside = 0, covered = 0;
    for (float x = -0.13f; x <= 0.13f; x += 0.005f) {
      for (float y = 0.36f; y <= 0.78f; y += 0.005f) {
        const float u = x / 0.13f, v = (y - 0.57f) / 0.21f;
        if (u * u + v * v > 1.0f) continue;
        ++inside;
        const glm::vec2 p(x, y);
        covered += std::any_of(dots.begin(), dots.end(), [&](const Mark& m) {
          const glm::vec2 ab = m.b - m.a;
          const float t = glm::clamp(glm::dot(p - m.a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
          return glm::length(p - (m.a + t * ab)) <= 0.5f * m.width;
        });
      }
    }
    EXPECT_GT(static_cast<double>(covered) / inside, 0.6) << covered << " of " << inside << " crown points";
  }
}

}  // namespace
}  // namespace shanshui::elements
