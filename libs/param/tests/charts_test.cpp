// Atlases of charts (charts.h): the targets of issue 27 on CGAL's cow, charts that are
// discs lying apart by the padding (checked by brute force on the output), seams that
// split vertices and nothing else, and the odd inputs.
#include "shanshui/param/charts.h"

#include <cmath>
#include <map>
#include <set>

#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/param/parameterize.h"
#include "shanshui/param/seam_cut.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::param {
namespace {

mesh::Mesh cgalMesh(const char* name) {
  const std::filesystem::path f = test::cgalMeshes() / (std::string(name) + ".off");
  mesh::RepairOptions ro;
  ro.components = mesh::ComponentPolicy::KeepAll;
  ro.max_hole_edges = 1 << 30;
  return mesh::repairMesh(mesh::readPolygonSoup(f), ro, nullptr, f.string());
}

double cross2(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}

double segmentDistance(glm::dvec2 p, glm::dvec2 q, glm::dvec2 r, glm::dvec2 s) {
  auto pointSegment = [](glm::dvec2 x, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 d = b - a;
    const double t = glm::dot(d, d) > 0 ? std::clamp(glm::dot(x - a, d) / glm::dot(d, d), 0.0, 1.0) : 0.0;
    return glm::length(x - (a + t * d));
  };
  const double d1 = cross2(q - p, r - p), d2 = cross2(q - p, s - p), d3 = cross2(s - r, p - r),
               d4 = cross2(s - r, q - r);
  if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return 0.0;
  return std::min({pointSegment(p, r, s), pointSegment(q, r, s), pointSegment(r, p, q), pointSegment(s, p, q)});
}

// Least distance between the UV triangles of two different charts (0 when they overlap),
// by brute force over pairs of triangles whose boxes come within `within`.
double closestCharts(const mesh::Mesh& m, const std::vector<int>& chartOf, double within) {
  struct Tri {
    glm::dvec2 p[3], lo, hi;
    int chart;
  };
  std::vector<Tri> tris;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    Tri t;
    for (int k = 0; k < 3; ++k) t.p[k] = glm::dvec2(m.uvs[m.triangles[i][k]]);
    t.lo = glm::min(t.p[0], glm::min(t.p[1], t.p[2]));
    t.hi = glm::max(t.p[0], glm::max(t.p[1], t.p[2]));
    t.chart = chartOf[i];
    tris.push_back(t);
  }
  std::sort(tris.begin(), tris.end(), [](const Tri& a, const Tri& b) { return a.lo.x < b.lo.x; });
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < tris.size(); ++i) {
    for (std::size_t j = i + 1; j < tris.size() && tris[j].lo.x <= tris[i].hi.x + within; ++j) {
      const Tri &a = tris[i], &b = tris[j];
      if (a.chart == b.chart || b.lo.y > a.hi.y + within || a.lo.y > b.hi.y + within) continue;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          closest = std::min(closest, segmentDistance(a.p[k], a.p[(k + 1) % 3], b.p[l], b.p[(l + 1) % 3]));
    }
  }
  return closest;
}

// Each chart's faces, as a mesh of their own, form a disc: one border loop, Euler 1.
void expectChartsAreDiscs(const mesh::Mesh& out, const AtlasReport& a) {
  std::map<int, mesh::Mesh> charts;
  for (std::size_t i = 0; i < out.triangles.size(); ++i)
    charts[a.chart_of_face[i]].triangles.push_back(out.triangles[i]);
  ASSERT_EQ(charts.size(), a.charts.size());
  for (auto& [c, m] : charts) {
    std::set<std::uint32_t> vertices;
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const glm::uvec3& t : m.triangles)
      for (int k = 0; k < 3; ++k) {
        vertices.insert(t[k]);
        edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
      }
    m.positions = out.positions;
    EXPECT_EQ(static_cast<long long>(vertices.size()) - static_cast<long long>(edges.size()) +
                  static_cast<long long>(m.triangles.size()),
              1)
        << "chart " << c;
    EXPECT_EQ(borderLoops(m), 1) << "chart " << c;
  }
}

// Issue 27's targets on a closed genus-0 animal of ~6k faces.
TEST(Charts, CowMeetsTheAtlasTargets) {
  SHANSHUI_REQUIRE_FILE(test::cgalMeshes() / "cow.off");
  const mesh::Mesh cow = cgalMesh("cow");
  ParamOptions o;
  o.method = Method::Charts;
  ParamReport r;
  const mesh::Mesh out = parameterize(cow, o, &r, "cow.off");
  const Distortion d = measureDistortion(out);
  EXPECT_LE(d.l2_stretch, 1.5) << d.summary();
  EXPECT_EQ(d.flipped, 0);
  EXPECT_TRUE(d.valid());
  EXPECT_LE(r.atlas.charts.size(), 20u);
  EXPECT_GE(r.atlas.usage, 0.6);
  // Usage is the UV area over the atlas rectangle, recomputed here from the output.
  double uvArea = 0.0;
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const glm::uvec3& t : out.triangles) {
    const glm::dvec2 a = out.uvs[t.x], b = out.uvs[t.y], c = out.uvs[t.z];
    uvArea += 0.5 * std::abs(cross2(b - a, c - a));
  }
  for (const glm::vec2& uv : out.uvs) {
    lo = glm::min(lo, glm::dvec2(uv));
    hi = glm::max(hi, glm::dvec2(uv));
  }
  EXPECT_NEAR(r.atlas.usage, uvArea / ((hi.x - lo.x) * (hi.y - lo.y)), 0.01);
  // Every chart within its own limit, so the whole within it too (an area-weighted mean).
  for (const ChartReport& c : r.atlas.charts) EXPECT_LE(c.distortion.l2_stretch, o.charts.max_chart_stretch);
  expectChartsAreDiscs(out, r.atlas);
  // auto keeps the atlas: the single seam gives L2 in the hundreds.
  ParamReport autoReport;
  parameterize(cow, {}, &autoReport, "cow.off");
  EXPECT_EQ(autoReport.method, Method::Charts) << trialTable(autoReport);
}

TEST(Charts, ChartsLieApartByAtLeastThePadding) {
  for (const double padding : {0.0, 4.0, 12.0}) {
    SCOPED_TRACE(padding);
    ChartOptions o;
    o.padding_texels = padding;
    o.atlas_resolution = 512;
    AtlasReport a;
    const mesh::Mesh out = parameterizeCharts(test::torus(3.0, 1.0, 36, 18), o, &a);
    ASSERT_GE(a.charts.size(), 2u);
    const double closest = closestCharts(out, a.chart_of_face, padding * a.texel + 1e-9);
    // The texel is the atlas's longer side over the resolution, measured on the output.
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::vec2& uv : out.uvs) {
      lo = glm::min(lo, glm::dvec2(uv));
      hi = glm::max(hi, glm::dvec2(uv));
    }
    EXPECT_NEAR(a.texel, std::max(hi.x - lo.x, hi.y - lo.y) / 512.0, 1e-6 * a.texel * 512);
    if (padding > 0) {
      EXPECT_GE(closest, padding * a.texel * 0.999) << closest / a.texel << " texels";
    } else {
      EXPECT_GT(closest, 0.0) << "charts overlap";
    }
    EXPECT_TRUE(measureDistortion(out).valid());
    expectChartsAreDiscs(out, a);
  }
}

// Seams only split vertices: every triangle keeps its corners' positions and its place,
// copies of a vertex share its normal, and only chart borders are split.
TEST(Charts, SeamsSplitVerticesAndChangeNothingElse) {
  const mesh::Mesh ball = test::uvSphere(2.0, 16, 32);
  AtlasReport a;
  const mesh::Mesh out = parameterizeCharts(ball, {}, &a);
  ASSERT_EQ(out.triangles.size(), ball.triangles.size());
  ASSERT_EQ(out.normals.size(), out.positions.size());
  const std::vector<glm::vec3> normals = mesh::vertexNormals(ball);
  std::map<std::uint32_t, std::set<int>> chartsAt;  // input vertex -> charts using it
  for (std::size_t i = 0; i < ball.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = ball.triangles[i][k], w = out.triangles[i][k];
      EXPECT_EQ(out.positions[w], ball.positions[v]);
      EXPECT_LT(glm::length(out.normals[w] - normals[v]), 1e-6f);
      chartsAt[v].insert(a.chart_of_face[i]);
    }
  // Output vertices = one per (input vertex, chart using it): fans are not split further
  // on a clean sphere.
  std::size_t expected = 0;
  for (const auto& [v, charts] : chartsAt) expected += charts.size();
  EXPECT_EQ(out.positions.size(), expected);
  if (a.charts.size() > 1) {
    EXPECT_GT(out.positions.size(), ball.positions.size());
  }
}

// A disc that projects well is one chart; several components and a mesh with handles are
// charted, never refused.
TEST(Charts, AnyTopologyIsCharted) {
  AtlasReport a;
  const mesh::Mesh plane = test::heightGrid(20, 20, 1.0, [](double x, double y) { return 0.1 * x + 0.05 * y; });
  mesh::Mesh out = parameterizeCharts(plane, {}, &a);
  EXPECT_EQ(a.charts.size(), 1u);
  EXPECT_NEAR(measureDistortion(out).l2_stretch, 1.0, 1e-9);

  mesh::Mesh two = test::uvSphere(1.0, 10, 20);
  const mesh::Mesh ring = test::torus(3.0, 1.0, 24, 12);
  const auto n = static_cast<unsigned>(two.positions.size());
  // A sphere and a torus in one mesh, their normals following (per vertex or none).
  two.positions.insert(two.positions.end(), ring.positions.begin(), ring.positions.end());
  if (two.normals.size() == n && ring.normals.size() == ring.positions.size())
    two.normals.insert(two.normals.end(), ring.normals.begin(), ring.normals.end());
  else
    two.normals.clear();
  two.uvs.clear();
  for (glm::uvec3 t : ring.triangles) two.triangles.push_back(t + glm::uvec3(n));
  ParamReport r;
  out = parameterize(two, {}, &r, "two.obj");
  EXPECT_EQ(r.method, Method::Charts);
  EXPECT_TRUE(measureDistortion(out).valid());
  EXPECT_LE(r.distortion.l2_stretch, 1.5);
  expectChartsAreDiscs(out, r.atlas);

  SHANSHUI_REQUIRE_FILE(test::cgalMeshes() / "anchor.off");
  out = parameterize(cgalMesh("anchor"), {}, &r, "anchor.off");  // genus 4
  EXPECT_EQ(r.method, Method::Charts);
  EXPECT_TRUE(measureDistortion(out).valid());
}

// A closed mesh whose normal list does not match its vertices (assembled by hand) is cut
// open without reading past the list: the cut drops it (it was read past its end, found by
// AddressSanitizer in Charts.AnyTopologyIsCharted).
TEST(Charts, CuttingOpenKeepsAttributesPerVertexOrDropsThem) {
  mesh::Mesh sphere = test::uvSphere(1.0, 10, 20);
  sphere.normals.assign(sphere.positions.size() / 2, glm::vec3(0, 0, 1));
  sphere.uvs.assign(sphere.positions.size(), glm::vec2(0.5f));
  const SeamCut cut = cutOpen(sphere, "sphere");
  EXPECT_GT(cut.duplicated, 0);
  EXPECT_TRUE(cut.mesh.normals.empty());
  EXPECT_EQ(cut.mesh.uvs.size(), cut.mesh.positions.size());
}

TEST(Charts, SameInputSameAtlas) {
  const mesh::Mesh ring = test::torus(3.0, 1.0, 24, 12);
  const mesh::Mesh a = parameterizeCharts(ring, {});
  const mesh::Mesh b = parameterizeCharts(ring, {});
  EXPECT_EQ(a.uvs, b.uvs);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(Charts, HugeAndTinyCoordinatesGiveTheSameAtlas) {
  const mesh::Mesh ring = test::torus(3.0, 1.0, 24, 12);
  mesh::Mesh far = ring, tiny = ring;
  for (glm::dvec3& p : far.positions) p += glm::dvec3(562710.0, 5114985.0, 1200.0);
  for (glm::dvec3& p : tiny.positions) p *= 1e-6;
  AtlasReport ra, rf, rt;
  const Distortion d = measureDistortion(parameterizeCharts(ring, {}, &ra));
  const Distortion df = measureDistortion(parameterizeCharts(far, {}, &rf));
  const Distortion dt = measureDistortion(parameterizeCharts(tiny, {}, &rt));
  EXPECT_TRUE(df.valid() && dt.valid());
  EXPECT_EQ(ra.charts.size(), rt.charts.size());
  EXPECT_NEAR(d.l2_stretch, dt.l2_stretch, 1e-6);
  EXPECT_NEAR(d.l2_stretch, df.l2_stretch, 0.05);
}

TEST(Charts, BadOptionsAreRefusedByName) {
  const mesh::Mesh ring = test::torus(3.0, 1.0, 12, 6);
  ChartOptions o;
  o.padding_texels = -1;
  test::expectErrorNaming([&] { parameterizeCharts(ring, o); }, "padding", "-1");
  o = {};
  o.atlas_resolution = 10;
  test::expectErrorNaming([&] { parameterizeCharts(ring, o); }, "resolution", "10");
  o = {};
  o.max_chart_stretch = 0.5;
  test::expectErrorNaming([&] { parameterizeCharts(ring, o); }, "stretch", "0.5");
  o = {};
  o.min_fill = 2;
  test::expectErrorNaming([&] { parameterizeCharts(ring, o); }, "fill", "2");
  test::expectErrorNaming([] { parameterizeCharts(mesh::Mesh{}, {}, nullptr, "empty.off"); }, "empty.off",
                          "no triangles");
}

}  // namespace
}  // namespace shanshui::param
