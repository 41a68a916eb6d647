// Trees grown as brush marks. The kinds follow the painters' manuals (Mustard Seed Garden):
// a pine is a trunk with tiers of needle clusters, short strokes radiating from a point; a
// leafy tree a forked trunk under clumps of dot leaves (点叶); a bare tree recursive branches
// ending in twigs (crab-claw); a distant tree a few vertical dots over a thin stem.
#include "shanshui/elements/brushwork.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shanshui/core/random.h"

namespace shanshui::elements {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

class Grower {
 public:
  explicit Grower(std::uint32_t seed) : seed_(seed) {}
  float uniform() { return static_cast<float>(streamValue(seed_, n_++) >> 40) * 0x1.0p-24f; }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  int count(int lo, int hi) { return lo + static_cast<int>(uniform() * static_cast<float>(hi - lo + 1) * 0.9999f); }

  std::vector<Mark> marks;
  void add(glm::vec2 a, glm::vec2 b, float width, float ink, Shape shape, std::uint8_t levels) {
    marks.push_back({a, b, width, ink, shape, levels});
  }

 private:
  std::uint64_t seed_, n_ = 0;
};

// A trunk from the foot to `top`, bowed sideways by `bow`, in `segments` tapering pieces.
glm::vec2 trunk(Grower& g, glm::vec2 top, float bow, float width, int segments, std::uint8_t levels) {
  glm::vec2 prev(0.0f);
  for (int i = 1; i <= segments; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(segments);
    const glm::vec2 p(top.x * t + bow * std::sin(kPi * t), top.y * t);
    g.add(prev, p, width * (1.0f - 0.45f * (t - 1.0f / static_cast<float>(segments))), 0.95f, Shape::Branch, levels);
    prev = p;
  }
  return prev;
}

// A cluster of needles: short strokes radiating from `centre`, spread into a flat fan that
// opens upwards, as the manuals draw a pine's needle wheel.
void needleFan(Grower& g, glm::vec2 centre, float size) {
  const int needles = g.count(9, 13);
  for (int k = 0; k < needles; ++k) {
    const float a =
        kPi * (-0.15f + 1.3f * (static_cast<float>(k) + g.uniform(0.0f, 0.7f)) / static_cast<float>(needles));
    const float len = size * g.uniform(0.8f, 1.15f);
    const glm::vec2 tip = centre + len * glm::vec2(std::cos(a), 0.55f * std::sin(a));
    g.add(centre, tip, 0.18f * size, g.uniform(0.82f, 1.0f), Shape::Leaf, kNear);
  }
}

void pine(Grower& g) {
  const float bow = g.uniform(-0.07f, 0.07f);
  const glm::vec2 top(g.uniform(-0.06f, 0.06f), 0.93f);
  trunk(g, top, bow, 0.045f, 4, kMiddle | kNear);
  const int tiers = g.count(5, 7);
  float side = g.uniform() < 0.5f ? -1.0f : 1.0f;
  for (int i = 0; i < tiers; ++i) {
    const float f = (static_cast<float>(i) + g.uniform(0.0f, 0.35f)) / static_cast<float>(tiers);
    const float y = 0.42f + 0.5f * f;
    const float t = y / top.y;
    const glm::vec2 on_trunk(top.x * t + bow * std::sin(kPi * t), y);
    const float reach = (0.3f - 0.2f * f) * g.uniform(0.8f, 1.15f);
    const glm::vec2 tip = on_trunk + glm::vec2(side * reach, g.uniform(-0.01f, 0.04f));
    g.add(on_trunk, tip, 0.018f, 0.9f, Shape::Branch, kNear);
    // Two needle fans along the branch, the larger at its tip.
    const int fans = 2;
    for (int k = 0; k < fans; ++k) {
      const float along = 1.0f - 0.45f * static_cast<float>(k);
      needleFan(g, on_trunk + along * (tip - on_trunk) + glm::vec2(0.0f, 0.01f),
                (0.11f - 0.02f * static_cast<float>(k)) * (1.0f - 0.3f * f));
    }
    // In the middle distance a tier is one flat stroke.
    const glm::vec2 mid = on_trunk + 0.7f * (tip - on_trunk) + glm::vec2(0.0f, 0.02f);
    g.add(mid - glm::vec2(0.13f, 0.0f), mid + glm::vec2(0.13f, 0.015f), 0.07f, 0.85f, Shape::Leaf, kMiddle);
    side = -side;
  }
  needleFan(g, top + glm::vec2(0.0f, 0.0f), 0.09f);
  g.add({0.0f, 0.38f}, {top.x * 0.6f, 0.9f}, 0.34f, 0.8f, Shape::Dab, kFar);
}

void leafy(Grower& g) {
  const float fork = g.uniform(0.28f, 0.36f);
  const glm::vec2 split =
      trunk(g, {g.uniform(-0.04f, 0.04f), fork}, g.uniform(-0.04f, 0.04f), 0.05f, 2, kMiddle | kNear);
  // Clumps over a dome: a ring of four to six and one or two inside it.
  const int ring = g.count(4, 6), inner = g.count(1, 2);
  const glm::vec2 crown(split.x, 0.64f);
  for (int c = 0; c < ring + inner; ++c) {
    const float a =
        kPi * (-0.05f + 1.1f * (static_cast<float>(c % ring) + g.uniform(0.2f, 0.8f)) / static_cast<float>(ring));
    const float r = c < ring ? g.uniform(0.8f, 1.05f) : g.uniform(0.1f, 0.4f);
    const glm::vec2 centre = crown + r * glm::vec2(-0.24f * std::cos(a), 0.24f * std::sin(a));
    // The limbs to the clumps inside the ring are drawn in the middle distance too: without
    // them its dabs (from about half the height) hung over a trunk that ends at the fork.
    g.add(split, centre, 0.02f, 0.9f, Shape::Branch, c < ring ? kNear : (kMiddle | kNear));
    // Dot leaves (点叶): small horizontal dabs, dense at the clump's heart, of one ink.
    const float ink = g.uniform(0.6f, 0.95f);
    const int leaves = g.count(12, 18);
    for (int k = 0; k < leaves; ++k) {
      const float rr = 0.11f * std::sqrt(g.uniform()), b = 2.0f * kPi * g.uniform();
      const glm::vec2 p = centre + rr * glm::vec2(std::cos(b), 0.75f * std::sin(b));
      const glm::vec2 d(g.uniform(0.008f, 0.016f), g.uniform(-0.006f, 0.006f));
      g.add(p - d, p + d, g.uniform(0.032f, 0.045f), ink * g.uniform(0.85f, 1.05f), Shape::Dab, kNear);
    }
    g.add(centre - glm::vec2(0.04f, 0.0f), centre + glm::vec2(0.04f, 0.0f), 0.16f, 0.75f, Shape::Dab, kMiddle);
  }
  g.add({split.x, 0.52f}, {split.x, 0.78f}, 0.44f, 0.78f, Shape::Dab, kFar);
}

void branches(Grower& g, glm::vec2 from, float angle, float length, float width, int depth) {
  const glm::vec2 to = from + length * glm::vec2(std::sin(angle), std::cos(angle));
  g.add(from, to, width, 0.92f, Shape::Branch, depth <= 1 ? (kMiddle | kNear) : kNear);
  if (depth >= 4) return;
  const int children = g.uniform() < 0.3f ? 3 : 2;
  for (int c = 0; c < children; ++c) {
    const float spread = (c == 0 ? -1.0f : c == 1 ? 1.0f : 0.0f) * g.uniform(0.3f, 0.7f);
    branches(g, to, angle + spread + g.uniform(-0.12f, 0.12f), length * g.uniform(0.6f, 0.75f),
             std::max(width * 0.62f, 0.008f), depth + 1);
  }
}

void bare(Grower& g) {
  branches(g, {0.0f, 0.0f}, g.uniform(-0.1f, 0.1f), 0.4f, 0.045f, 0);
  g.add({0.0f, 0.1f}, {0.0f, 0.78f}, 0.14f, 0.6f, Shape::Leaf, kFar);
}

// A distant tree: a clump of upright dots (the Mi family's dots) over a short stem. The stem
// is drawn at the middle level too, under its two dabs, which reach down to it: they began at
// 0.38 of the height with nothing under them, and a tree 25 px high on a near bank read as two
// ovals floating over the water.
void distant(Grower& g) {
  g.add({0.0f, 0.0f}, {g.uniform(-0.03f, 0.03f), 0.3f}, 0.03f, 0.85f, Shape::Branch, kMiddle | kNear);
  // Drawn near, the crown is a dense clump of small upright dabs (a painter's vertical dots),
  // each under a tenth of the crown's width, overlapping into one mass.
  const int dots = g.count(24, 32);
  for (int i = 0; i < dots; ++i) {
    const float a = g.uniform(0.0f, 2.0f * kPi), r = std::sqrt(g.uniform(0.0f, 1.0f));
    const glm::vec2 c(0.13f * r * std::cos(a), 0.57f + 0.21f * r * std::sin(a));
    const float len = g.uniform(0.06f, 0.09f);
    g.add(c - glm::vec2(0.0f, 0.5f * len), c + glm::vec2(g.uniform(-0.01f, 0.01f), 0.5f * len),
          g.uniform(0.04f, 0.055f), g.uniform(0.7f, 0.95f), Shape::Leaf, kNear);
  }
  g.add({-0.06f, 0.26f}, {-0.05f, 0.7f}, 0.14f, 0.85f, Shape::Leaf, kMiddle);
  g.add({0.06f, 0.3f}, {0.05f, 0.76f}, 0.14f, 0.85f, Shape::Leaf, kMiddle);
  g.add({0.0f, 0.3f}, {0.0f, 0.82f}, 0.28f, 0.82f, Shape::Leaf, kFar);
}

float smooth(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

std::vector<Mark> growBrushwork(Kind kind, std::uint32_t seed) {
  Grower g(seed);
  switch (kind) {
    case Kind::Pine:
      pine(g);
      break;
    case Kind::Leafy:
      leafy(g);
      break;
    case Kind::Bare:
      bare(g);
      break;
    case Kind::Distant:
      distant(g);
      break;
    case Kind::MossDot:
      g.add({-0.12f, 0.0f}, {0.12f, 0.0f}, 1.0f, 1.0f, Shape::Dab, kFar | kMiddle | kNear);
      break;
  }
  return std::move(g.marks);
}

std::array<float, 3> levelWeights(double px) {
  const float p = static_cast<float>(px);
  const float middle_in = smooth(kLevelBands[0], kLevelBands[1], p),
              near_in = smooth(kLevelBands[2], kLevelBands[3], p);
  return {1.0f - middle_in, middle_in * (1.0f - near_in), middle_in * near_in};
}

}  // namespace shanshui::elements
