// Placement of trees and moss dots on a terrain (issue 44). Trees are a Thomas cluster
// process thinned by the site: grove centres fall uniformly over the object's horizontal
// bounds (grown by the grove's reach, so groves at the edge are whole), each grove's trees
// scatter around its centre with a Gaussian spread and a tree is kept with the probability
// its site suits trees. The expected density at a point is then `density` × suitability,
// while the trees stand in groves (the 2D scroll generators' neighbour rule, without a grid).
#include "shanshui/elements/placement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "shanshui/core/error.h"
#include "shanshui/core/random.h"

namespace shanshui::elements {

namespace {

double smooth(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// A seeded stream of numbers, the same on every platform (std's distributions are not).
class Random {
 public:
  explicit Random(std::uint64_t seed) : seed_(seed) {}
  std::uint64_t bits() { return streamValue(seed_, n_++); }
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {  // Box–Muller
    const double u = std::max(uniform(), 1e-300), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
  }
  int poisson(double mean) {
    if (mean <= 0.0) return 0;
    if (mean > 60.0) return std::max(0, static_cast<int>(std::lround(mean + std::sqrt(mean) * normal())));
    const double limit = std::exp(-mean);
    int k = 0;
    for (double p = uniform(); p > limit; p *= uniform()) ++k;
    return k;
  }

 private:
  std::uint64_t seed_, n_ = 0;
};

// A kind drawn from the shares, each weighted by how much the site draws it: pines on
// ridges and high ground, leafy trees in hollows, on valley floors and low ground, bare
// trees anywhere, distant trees (dabs) along the high ridges that make skylines.
Kind drawKind(const TreeOptions& o, const Site* s, Random& r) {
  std::array<double, kTreeKinds> w = o.kinds;
  if (s) {
    w[0] *= 0.5 + s->ridge + s->height;
    w[1] *= 0.5 + s->hollow + s->floor + (1.0 - s->height);
    w[3] *= 0.2 + 2.0 * s->ridge * s->height;
  }
  double total = 0.0;
  for (double x : w) total += x;
  if (total <= 0.0) return Kind::Pine;
  double u = r.uniform() * total;
  for (int k = 0; k < kTreeKinds; ++k) {
    if (u < w[k]) return static_cast<Kind>(k);
    u -= w[k];
  }
  return Kind::Distant;
}

double kindScale(Kind k) {
  switch (k) {
    case Kind::Pine:
      return 1.1;
    case Kind::Leafy:
      return 0.9;
    case Kind::Bare:
      return 0.8;
    case Kind::Distant:
      return 0.75;
    case Kind::MossDot:
      break;
  }
  return 1.0;
}

}  // namespace

double treeSuitability(const Site& s, const TreeOptions& o) {
  if (s.slope_deg > o.max_slope_deg) return 0.0;
  if (s.height < o.band[0] || s.height > o.band[1]) return 0.0;
  const double slope = 1.0 - smooth(0.7 * o.max_slope_deg, o.max_slope_deg, s.slope_deg);
  const double edge = 0.04;  // the band's edges fade over this much of the relief
  const double band = (o.band[0] > 0.0 ? smooth(o.band[0], o.band[0] + edge, s.height) : 1.0) *
                      (o.band[1] < 1.0 ? 1.0 - smooth(o.band[1] - edge, o.band[1], s.height) : 1.0);
  const double site = o.open + (1.0 - o.open) * std::max({s.ridge, s.hollow, s.floor});
  return std::clamp(slope * band * site, 0.0, 1.0);
}

double dotSuitability(const Site& s) {
  const double steep = smooth(28.0, 50.0, s.slope_deg);
  return std::clamp(std::max(s.ridge * (0.3 + 0.7 * s.height), 0.8 * steep * (0.3 + 0.7 * s.ridge)), 0.0, 1.0);
}

Terrain::Terrain(const mesh::Mesh& m, int cells) : mesh_(m), bounds_(mesh::bounds(m)) {
  const glm::dvec3 size = bounds_.size();
  cell_ = std::max(std::max(size.x, size.y) / cells, 1e-12);
  nx_ = std::max(2, static_cast<int>(std::ceil(size.x / cell_)) + 1);
  ny_ = std::max(2, static_cast<int>(std::ceil(size.y / cell_)) + 1);
  buckets_.resize(static_cast<std::size_t>(nx_) * ny_);
  auto cellOf = [&](double v, double lo, int n) { return std::clamp(static_cast<int>((v - lo) / cell_), 0, n - 1); };
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const glm::uvec3& f = m.triangles[t];
    const glm::dvec3 &a = m.positions[f.x], &b = m.positions[f.y], &c = m.positions[f.z];
    const int x0 = cellOf(std::min({a.x, b.x, c.x}), bounds_.min.x, nx_);
    const int x1 = cellOf(std::max({a.x, b.x, c.x}), bounds_.min.x, nx_);
    const int y0 = cellOf(std::min({a.y, b.y, c.y}), bounds_.min.y, ny_);
    const int y1 = cellOf(std::max({a.y, b.y, c.y}), bounds_.min.y, ny_);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        buckets_[static_cast<std::size_t>(y) * nx_ + x].push_back(static_cast<std::uint32_t>(t));
  }
  // Heights and slopes at the cell centres; the relief's form from the height less its
  // Gaussian average over about a fortieth of the larger side (a normalised convolution,
  // so the mesh's outside does not pull its edges down).
  const std::size_t n = static_cast<std::size_t>(nx_) * ny_;
  height_.assign(n, std::numeric_limits<float>::quiet_NaN());
  slope_.assign(n, 0.0f);
  cv::Mat z(ny_, nx_, CV_32F, cv::Scalar(0)), w(ny_, nx_, CV_32F, cv::Scalar(0));
  std::size_t covered = 0;
  for (int y = 0; y < ny_; ++y) {
    for (int x = 0; x < nx_; ++x) {
      glm::dvec3 p;
      double slope = 0.0;
      if (!surface(bounds_.min.x + (x + 0.5) * cell_, bounds_.min.y + (y + 0.5) * cell_, p, slope)) continue;
      const std::size_t i = static_cast<std::size_t>(y) * nx_ + x;
      height_[i] = static_cast<float>(p.z);
      slope_[i] = static_cast<float>(slope);
      z.at<float>(y, x) = static_cast<float>(p.z - bounds_.min.z);
      w.at<float>(y, x) = 1.0f;
      ++covered;
    }
  }
  area_ = static_cast<double>(covered) * cell_ * cell_;
  const double sigma = std::max(3.0, std::max(nx_, ny_) / 40.0);
  cv::Mat zb, wb;
  cv::GaussianBlur(z, zb, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
  cv::GaussianBlur(w, wb, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
  std::vector<float> form(n, 0.0f);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const int x = static_cast<int>(i % nx_), y = static_cast<int>(i / nx_);
    if (std::isnan(height_[i])) continue;
    form[i] = z.at<float>(y, x) - zb.at<float>(y, x) / std::max(wb.at<float>(y, x), 1e-6f);
    sum2 += static_cast<double>(form[i]) * form[i];
  }
  const double spread = std::sqrt(sum2 / std::max<std::size_t>(covered, 1)) + 1e-12 * (size.z + 1.0);
  ridge_.assign(n, 0.0f);
  hollow_.assign(n, 0.0f);
  for (std::size_t i = 0; i < n; ++i) {
    ridge_[i] = static_cast<float>(smooth(0.25, 1.25, form[i] / spread));
    hollow_[i] = static_cast<float>(smooth(0.25, 1.25, -form[i] / spread));
  }
}

bool Terrain::surface(double x, double y, glm::dvec3& point, double& slope_deg) const {
  const int cx = static_cast<int>(std::floor((x - bounds_.min.x) / cell_));
  const int cy = static_cast<int>(std::floor((y - bounds_.min.y) / cell_));
  if (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) return false;
  bool found = false;
  for (std::uint32_t t : buckets_[static_cast<std::size_t>(cy) * nx_ + cx]) {
    const glm::uvec3& f = mesh_.triangles[t];
    const glm::dvec3 &a = mesh_.positions[f.x], &b = mesh_.positions[f.y], &c = mesh_.positions[f.z];
    const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (std::abs(det) < 1e-300) continue;  // vertical: never the surface a tree stands on
    const double u = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
    const double v = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
    const double eps = -1e-9;
    if (u < eps || v < eps || u + v > 1.0 - eps) continue;
    const double z = a.z + u * (b.z - a.z) + v * (c.z - a.z);
    if (found && z <= point.z) continue;
    found = true;
    point = {x, y, z};
    const glm::dvec3 nrm = glm::cross(b - a, c - a);
    slope_deg = glm::degrees(std::acos(std::clamp(std::abs(nrm.z) / std::max(glm::length(nrm), 1e-300), 0.0, 1.0)));
  }
  return found;
}

double Terrain::sample(const std::vector<float>& grid, double x, double y) const {
  const double gx = std::clamp((x - bounds_.min.x) / cell_ - 0.5, 0.0, nx_ - 1.0);
  const double gy = std::clamp((y - bounds_.min.y) / cell_ - 0.5, 0.0, ny_ - 1.0);
  const int x0 = std::min(static_cast<int>(gx), nx_ - 2), y0 = std::min(static_cast<int>(gy), ny_ - 2);
  const double fx = gx - x0, fy = gy - y0;
  auto at = [&](int xx, int yy) { return static_cast<double>(grid[static_cast<std::size_t>(yy) * nx_ + xx]); };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

Site Terrain::site(double x, double y) const {
  Site s;
  glm::dvec3 p;
  if (!surface(x, y, p, s.slope_deg)) return s;
  const double relief = bounds_.size().z;
  s.height = relief > 0.0 ? std::clamp((p.z - bounds_.min.z) / relief, 0.0, 1.0) : 0.0;
  s.ridge = sample(ridge_, x, y);
  s.hollow = sample(hollow_, x, y);
  // A valley floor: flat, low and lying below its surroundings (where a stream or a bank
  // would be), not a whole plain.
  s.floor = (1.0 - smooth(4.0, 12.0, s.slope_deg)) * (1.0 - smooth(0.12, 0.3, s.height)) * s.hollow;
  return s;
}

double massing(double massed_beyond, double side) {
  return massed_beyond > 0.0 && side > massed_beyond ? massed_beyond / side : 1.0;
}

namespace {

// The options placeElements uses on land `side` wide: the massing applied.
TreeOptions massedTrees(const TreeOptions& t, double side) {
  TreeOptions out = t;
  const double f = massing(t.massed_beyond, side);
  out.grove = t.grove / f;
  out.open = t.open * f;
  return out;
}

DotOptions massedDots(const DotOptions& d, double side) {
  DotOptions out = d;
  out.density = d.density * massing(d.massed_beyond, side);
  return out;
}

}  // namespace

std::vector<Instance> placeElements(const mesh::Mesh& m, const TreeOptions& asked_trees, const DotOptions& asked_dots,
                                    std::uint64_t scene_seed, const std::string& where) {
  std::vector<Instance> out;
  double shares = 0.0;
  for (double k : asked_trees.kinds) shares += k;
  // Massing (f > 0) leaves every density that is above 0 above 0: whether anything is
  // placed is decided on the keys as asked.
  const bool want_trees = asked_trees.enabled && asked_trees.density > 0.0 && shares > 0.0;  // no kind: no tree
  const bool want_dots = asked_dots.enabled && (asked_dots.density > 0.0 || (want_trees && asked_dots.at_trees > 0.0));
  if (!(want_trees || want_dots) || m.triangles.empty()) return out;
  const Terrain terrain(m);
  const mesh::Bounds& b = terrain.bounds();
  const double land_side = std::max(b.size().x, b.size().y);
  const TreeOptions trees = massedTrees(asked_trees, land_side);
  const DotOptions dots = massedDots(asked_dots, land_side);
  const double hectares = terrain.area() / 1e4;
  auto tooMany = [&](const char* key, double expected) {
    if (expected > static_cast<double>(kMaxElements))
      throw makeError(where, ".", key, ": ", expected, " expected over ", hectares, " hectares; at most ", kMaxElements,
                      " elements an object (lower the density)");
  };
  if (want_trees) tooMany("trees.density", trees.density * hectares);
  if (want_dots)
    tooMany("dots.density",
            (dots.density * dots.cluster + (want_trees ? 2.0 * dots.at_trees * trees.density : 0.0)) * hectares);

  // Each grove, each tree of a grove and each cluster of dots draws from a stream of its own
  // (its index in the one before): whether the ground takes one tree does not move the draws
  // of the next, so a small change to the ground (a z_scale, a DEM's last digit) changes the
  // trees where the ground changed, instead of reshuffling the whole forest.
  if (want_trees) {
    const std::uint64_t stream = streamValue(trees.seed ? trees.seed : scene_seed, 0x7e55ull);
    Random r(stream);
    // A grove spreads at most over the object; centres fall at most half its size beyond it
    // (a grove wider than that is a scatter, and the centres to sample stay within 4x its
    // area, however wide a grove the keys ask for).
    const double side = std::max(std::max(b.size().x, b.size().y), 1e-9);
    const double sigma = std::min(trees.grove_radius > 0.0 ? trees.grove_radius : 6.0 * trees.size, side);
    const double reach = std::min(3.0 * sigma, 0.5 * side);
    const double w = b.size().x + 2 * reach, h = b.size().y + 2 * reach;
    const int groves = r.poisson(trees.density / 1e4 * w * h / trees.grove);
    for (int g = 0; g < groves; ++g) {
      const double cx = b.min.x - reach + w * r.uniform(), cy = b.min.y - reach + h * r.uniform();
      const Site centre = terrain.site(cx, cy);
      const Kind grove_kind = drawKind(trees, &centre, r);
      const int count = r.poisson(trees.grove);
      const std::uint64_t grove_stream = streamValue(stream, 0x67000000ull + static_cast<std::uint64_t>(g));
      for (int i = 0; i < count; ++i) {
        Random tr(streamValue(grove_stream, static_cast<std::uint64_t>(i)));
        const double x = cx + sigma * tr.normal(), y = cy + sigma * tr.normal();
        const double keep = tr.uniform();
        glm::dvec3 p;
        double slope = 0.0;
        if (!terrain.surface(x, y, p, slope)) continue;
        const Site s = terrain.site(x, y);
        if (keep >= treeSuitability(s, trees)) continue;
        Instance t;
        t.position = glm::vec3(p);
        t.kind = tr.uniform() < 0.75 ? grove_kind : drawKind(trees, &s, tr);
        t.size = static_cast<float>(trees.size * kindScale(t.kind) * std::exp(trees.size_spread * tr.normal()));
        t.lean = static_cast<float>(0.06 * tr.normal());
        t.mirrored = tr.uniform() < 0.5;
        t.seed = static_cast<std::uint32_t>(tr.bits());
        out.push_back(t);
      }
    }
  }

  if (want_dots) {
    const std::uint64_t stream = streamValue(dots.seed ? dots.seed : scene_seed, 0xd075ull);
    Random r(stream);
    const double side = std::max(std::max(b.size().x, b.size().y), 1e-9);
    const double sigma = std::min(dots.spread > 0.0 ? dots.spread : 0.004 * side, side);
    auto addDot = [&](Random& dr, double x, double y) {
      const double size = dr.uniform(0.65, 1.35), lean = dr.uniform(-0.6, 0.6);
      const auto seed = static_cast<std::uint32_t>(dr.bits());
      glm::dvec3 p;
      double slope = 0.0;
      if (!terrain.surface(x, y, p, slope)) return;
      Instance d;
      d.position = glm::vec3(p);
      d.kind = Kind::MossDot;
      d.size = static_cast<float>(size);
      d.lean = static_cast<float>(lean);
      d.seed = seed;
      out.push_back(d);
    };
    // At the feet of trees: one to three dots beside the trunk, drawn from the tree's own seed.
    const std::size_t tree_count = out.size();
    for (std::size_t i = 0; i < tree_count; ++i) {
      const Instance t = out[i];
      Random dr(streamValue(stream, 0x74000000ull + t.seed));
      if (dr.uniform() >= dots.at_trees) continue;
      const int n = 1 + static_cast<int>(dr.uniform() * 3.0);
      for (int k = 0; k < n; ++k) {
        const double x = t.position.x + t.size * dr.uniform(-0.5, 0.5),
                     y = t.position.y + t.size * dr.uniform(-0.5, 0.5);
        addDot(dr, x, y);
      }
    }
    // Clusters along ridges and rock edges.
    const double reach = std::min(3.0 * sigma, 0.5 * side);
    const double w = b.size().x + 2 * reach, h = b.size().y + 2 * reach;
    const int clusters = dots.density > 0.0 ? r.poisson(dots.density / 1e4 * w * h) : 0;
    for (int c = 0; c < clusters; ++c) {
      Random cr(streamValue(stream, 0x63000000ull + static_cast<std::uint64_t>(c)));
      const double cx = b.min.x - reach + w * cr.uniform(), cy = b.min.y - reach + h * cr.uniform();
      if (cr.uniform() >= dotSuitability(terrain.site(cx, cy))) continue;
      const int n = 1 + cr.poisson(dots.cluster - 1.0);
      for (int k = 0; k < n; ++k) {
        const double x = cx + sigma * cr.normal(), y = cy + sigma * cr.normal();
        addDot(cr, x, y);
      }
    }
  }
  return out;
}

}  // namespace shanshui::elements
