// Parameterization (SPEC.md section 5): distortion metrics against analytic answers, every
// method on a synthetic mountain, auto on the real DEMs, and the refusals.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/param/distortion.h"
#include "shanshui/param/parameterize.h"
#include "shanshui/param/uv_adjust.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::param {
namespace {

mesh::Mesh flatGrid(int n = 12) {
  return test::heightGrid(n, n, 1.0, [](double, double) { return 0.0; });
}

// A mountain: a Gaussian bump with a ridge, 40×40 vertices, 25 m cells.
mesh::Mesh mountain() {
  return test::heightGrid(40, 40, 25.0, [](double x, double y) {
    const double dx = x - 500, dy = y - 450;
    return 350.0 * std::exp(-(dx * dx + dy * dy) / (2 * 220.0 * 220.0)) +
           60.0 * std::sin(x / 90.0) * std::cos(y / 130.0);
  });
}

void setUvs(mesh::Mesh& m, double su, double sv) {
  m.uvs.clear();
  for (const glm::dvec3& p : m.positions)
    m.uvs.emplace_back(static_cast<float>(su * p.x), static_cast<float>(sv * p.y));
}

TEST(Distortion, IsometricMapIsIdealAtAnyScale) {
  mesh::Mesh m = flatGrid();
  for (double scale : {1.0, 0.01, 37.0}) {
    setUvs(m, scale, scale);
    const Distortion d = measureDistortion(m);
    EXPECT_NEAR(d.l2_stretch, 1.0, 1e-6) << scale;
    EXPECT_NEAR(d.linf_stretch, 1.0, 1e-6);
    EXPECT_NEAR(d.angle_distortion, 1.0, 1e-6);
    EXPECT_NEAR(d.area_distortion, 0.0, 1e-6);
    EXPECT_TRUE(d.valid());
  }
}

TEST(Distortion, AnisotropicScaleMatchesTheAnalyticValues) {
  // u = 2x, v = y. After equalising areas the UV->surface map has singular values
  // sqrt(2) and 1/sqrt(2): L2 = sqrt((2 + 1/2)/2), Linf = sqrt(2), angle 2, area 0.
  mesh::Mesh m = flatGrid();
  setUvs(m, 2.0, 1.0);
  const Distortion d = measureDistortion(m);
  EXPECT_NEAR(d.l2_stretch, std::sqrt(1.25), 1e-6);
  EXPECT_NEAR(d.linf_stretch, std::sqrt(2.0), 1e-6);
  EXPECT_NEAR(d.angle_distortion, 2.0, 1e-6);
  EXPECT_NEAR(d.area_distortion, 0.0, 1e-6);
}

TEST(Distortion, SlopedPlaneProjectedFlatStretchesBySecantOfTheSlope) {
  // z = x tan(30°) projected to xy: one direction stretched by 1/cos 30°.
  const double t = std::tan(std::numbers::pi / 6);
  mesh::Mesh m = test::heightGrid(10, 10, 1.0, [&](double x, double) { return t * x; });
  setUvs(m, 1.0, 1.0);
  const Distortion d = measureDistortion(m);
  const double c = 1.0 / std::cos(std::numbers::pi / 6);
  const double k = std::sqrt(1.0 / c);  // equal-area normalisation: σ = (c, 1)·k
  EXPECT_NEAR(d.l2_stretch, k * std::sqrt((c * c + 1) / 2), 1e-6);
  EXPECT_NEAR(d.angle_distortion, c, 1e-6);
}

TEST(Distortion, CountsFlippedDegenerateAndNonFiniteFaces) {
  mesh::Mesh m = flatGrid(6);
  setUvs(m, 1.0, 1.0);
  m.uvs[14] = m.uvs[14] + glm::vec2(2.2f, 0.0f);  // folds the faces around vertex 14
  Distortion d = measureDistortion(m);
  EXPECT_GT(d.flipped, 0);
  EXPECT_FALSE(d.valid());
  setUvs(m, 1.0, 1.0);
  m.uvs[7] = m.uvs[8];  // collapses two faces
  d = measureDistortion(m);
  EXPECT_GE(d.degenerate, 1);
  setUvs(m, 1.0, 1.0);
  m.uvs[3].x = std::nanf("");
  d = measureDistortion(m);
  EXPECT_GE(d.non_finite, 1);
  EXPECT_FALSE(d.valid());
}

TEST(UvAdjust, TexelSizeAndNormalize) {
  mesh::Mesh m = flatGrid(11);  // 10 x 10 units
  setUvs(m, 3.0, 3.0);
  scaleToTexelSize(m, 2.5);
  float maxU = 0;
  for (const glm::vec2& uv : m.uvs) maxU = std::max(maxU, uv.x);
  EXPECT_NEAR(maxU, 4.0f, 1e-5f);  // 10 units / 2.5 units per repeat
  normalizeUvs(m);
  glm::vec2 lo(1e9f), hi(-1e9f);
  for (const glm::vec2& uv : m.uvs) {
    lo = glm::min(lo, uv);
    hi = glm::max(hi, uv);
  }
  EXPECT_EQ(lo, glm::vec2(0.0f));
  EXPECT_NEAR(std::max(hi.x, hi.y), 1.0f, 1e-6f);
  test::expectErrorNaming([&] { scaleToTexelSize(m, 0.0); }, "texel size", "positive");
}

TEST(Parameterize, EveryMethodGivesAOneToOneMapOnAMountain) {
  const mesh::Mesh m = mountain();
  for (Method method :
       {Method::Xy, Method::Mvc, Method::Dcm, Method::Tutte, Method::Lscm, Method::Arap, Method::Authalic}) {
    for (Border border : {Border::Circle, Border::Square}) {
      ParamOptions o;
      o.method = method;
      o.border = border;
      ParamReport r;
      const mesh::Mesh out = parameterize(m, o, &r);
      SCOPED_TRACE(std::string(methodName(method)) + " " + borderName(border));
      ASSERT_EQ(out.uvs.size(), m.positions.size());
      const Distortion d = measureDistortion(out);
      EXPECT_TRUE(d.valid()) << d.summary();
      EXPECT_NEAR(d.l2_stretch, r.distortion.l2_stretch, 1e-9);
      EXPECT_EQ(out.positions, m.positions) << "positions must come back unchanged";
      // Planar projection and ARAP are close to isometric here; LSCM is conformal (angles
      // kept, areas not) and a little further off.
      const double limit = method == Method::Xy || method == Method::Arap ? 1.06 : method == Method::Lscm ? 1.15 : 1e9;
      EXPECT_LT(d.l2_stretch, limit) << d.summary();
    }
  }
}

// CGAL 5.5's authalic parameterizer writes "last_solve.off" into the working directory and
// prints every iteration (DEBUG_L0 is hard-coded); neither may reach the user.
TEST(Parameterize, AuthalicLeavesTheWorkingDirectoryAndStdoutAlone) {
  const test::TempDir dir;
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  ParamOptions o;
  o.method = Method::Authalic;
  testing::internal::CaptureStdout();
  const mesh::Mesh out = parameterize(mountain(), o);
  const std::string printed = testing::internal::GetCapturedStdout();
  const std::filesystem::path after = std::filesystem::current_path();
  std::filesystem::current_path(before);
  EXPECT_EQ(after, dir.path());
  EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << "CGAL's debug file leaked into the working directory";
  EXPECT_EQ(printed, "");
  EXPECT_TRUE(measureDistortion(out).valid());
}

// z = f(x) only: developable, so an isometric map exists (L2 stretch 1). The projection is
// stretched by the slopes. Without refinement LSCM finds the isometry, and auto stops there
// instead of also running ARAP (seconds on such a mesh); with it (the default), ARAP rounds
// from the projection find it first, and no solver runs at all.
TEST(Parameterize, AutoStopsAtTheFirstNearIsometricMethod) {
  const mesh::Mesh ridge = test::heightGrid(40, 40, 10.0, [](double x, double) { return 250.0 * std::sin(x / 150.0); });
  ParamOptions plain;
  plain.refine = false;
  ParamReport r;
  const mesh::Mesh out = parameterize(ridge, plain, &r);
  EXPECT_EQ(r.method, Method::Lscm);
  EXPECT_NEAR(r.distortion.l2_stretch, 1.0, 1e-6);
  EXPECT_TRUE(measureDistortion(out).valid());
  EXPECT_TRUE(r.refinements.empty());
  ASSERT_GE(r.trials.size(), 4u);
  EXPECT_GT(r.trials[0].distortion.l2_stretch, 1.02) << "the projection is not accepted";
  for (const MethodTrial& t : r.trials) {
    if (t.method != Method::Arap && t.method != Method::Charts) continue;
    EXPECT_FALSE(t.ran) << methodName(t.method);
    EXPECT_NE(t.note.find("already found"), std::string::npos) << t.note;
  }
  EXPECT_EQ(r.atlas.charts.size(), 0u);

  // The rounds stop as soon as the map is good enough, as the plan does; asked for less
  // stretch, they go on to the isometry.
  for (const double accept : {ParamOptions{}.auto_accept_stretch, 1.0005}) {
    SCOPED_TRACE(accept);
    ParamOptions o;
    o.auto_accept_stretch = accept;
    ParamReport refined;
    const mesh::Mesh map = parameterize(ridge, o, &refined);
    EXPECT_EQ(refined.method, Method::Xy);
    ASSERT_EQ(refined.refinements.size(), 1u);
    EXPECT_TRUE(refined.refinements[0].kept);
    EXPECT_TRUE(refined.refinements[0].enough);
    EXPECT_LE(refined.distortion.l2_stretch, accept);
    EXPECT_NEAR(measureDistortion(map).l2_stretch, refined.distortion.l2_stretch, 1e-9);
    EXPECT_EQ(measureDistortion(map).flipped, 0);
    EXPECT_NE(refined.decision.find("refined"), std::string::npos) << refined.decision;
    for (std::size_t i = 1; i < refined.trials.size(); ++i) {
      EXPECT_FALSE(refined.trials[i].ran) << methodName(refined.trials[i].method);
      EXPECT_NE(refined.trials[i].note.find("already found"), std::string::npos) << refined.trials[i].note;
    }
  }
}

// The refinement is anytime: it stops at the budget whatever the size, lowering the
// stretch of the map it starts from. A small mesh stops because the rounds stop gaining;
// a round that stops for the budget has spent the share it was given. (A steep mountain:
// the projection's L2 stretch is about 1.03, and the early stop is put out of reach.)
// Nothing here compares two run times: on a loaded machine the trials of 900 vertices
// once took longer than those of 14 400, so how the time grows is the benchmark's.
TEST(Parameterize, AutoRefinesWithinItsBudgetAndStopsWhenTheRoundsStopGaining) {
  auto mountain = [](int n) {
    return test::heightGrid(n, n, 14000.0 / (n - 1), [](double x, double y) {
      const double dx = x - 7000, dy = y - 7500;
      return 3200.0 * std::exp(-(dx * dx + dy * dy) / (2 * 2600.0 * 2600.0)) +
             650.0 * std::sin(x / 700.0) * std::cos(y / 900.0);
    });
  };
  ParamOptions o;
  o.budget_seconds = 0.4;
  o.auto_accept_stretch = 1.0001;  // out of reach here: the rounds go on to convergence or the budget
  for (const int n : {30, 60, 120}) {
    SCOPED_TRACE(n);
    ParamReport r;
    parameterize(mountain(n), o, &r);
    ASSERT_FALSE(r.refinements.empty()) << trialTable(r);
    const Refinement& f = r.refinements.front();
    EXPECT_EQ(f.from, Method::Xy);
    EXPECT_TRUE(f.kept) << trialTable(r);
    EXPECT_LT(f.distortion.l2_stretch, r.trials.front().distortion.l2_stretch);
    EXPECT_EQ(f.distortion.flipped, 0);
    EXPECT_LE(r.seconds, o.budget_seconds + 0.2) << trialTable(r);
    // 900 vertices converge in about 20 rounds and 0.04 s, a tenth of the budget.
    if (n == 30) {
      EXPECT_TRUE(f.converged) << trialTable(r);
    }
    // Stopped neither by convergence nor by the early stop: the budget ended it, after
    // at least half of what was left to the refinement deadline (93% of the budget).
    if (!f.converged && !f.enough) {
      EXPECT_GE(r.seconds, 0.5 * 0.93 * o.budget_seconds - 1e-3) << trialTable(r);
    }
  }
}

TEST(Parameterize, AutoOnEveryRealDemIsNearIsometricWithoutFlips) {
  // The repository's own DEMs always; the real ones beside it where they are.
  std::vector<std::filesystem::path> dems = {test::sourceDir() / "samples/terrain/mount_st_helens.dem",
                                             test::sourceDir() / "samples/terrain/hill.asc"};
  for (const char* name : {"jacksboro_fault_dem_u16.png", "bc_coast_topobathy.asc"}) {
    const std::filesystem::path f = test::sharedData() / "terrain" / name;
    if (std::filesystem::exists(f))
      dems.push_back(f);
    else
      std::printf("not in the shared data, not tested: %s\n", f.c_str());
  }
  for (const auto& f : dems) {
    SCOPED_TRACE(f.filename().string());
    terrain::HeightfieldOptions ho;
    if (f.extension() == ".png") ho.cell_size = 90.0;
    terrain::TerrainMeshOptions mo;
    mo.max_vertices = 60000;
    const mesh::Mesh m = terrain::heightfieldToMesh(terrain::loadHeightfield(f, ho), mo);
    ParamReport r;
    const mesh::Mesh out = parameterize(m, ParamOptions{}, &r, f.string());
    EXPECT_LE(r.distortion.l2_stretch, 1.05) << r.distortion.summary();
    EXPECT_EQ(r.distortion.flipped, 0);
    EXPECT_TRUE(measureDistortion(out).valid());
  }
}

TEST(Parameterize, HugeUtmCoordinatesKeepTheirPrecision) {
  const mesh::Mesh near = mountain();
  const mesh::Mesh far = test::heightGrid(
      40, 40, 25.0,
      [](double x, double y) {
        const double dx = x - 500, dy = y - 450;
        return 350.0 * std::exp(-(dx * dx + dy * dy) / (2 * 220.0 * 220.0)) +
               60.0 * std::sin(x / 90.0) * std::cos(y / 130.0);
      },
      glm::dvec3(562710.0, 5114985.0, 1200.0));
  for (Method method : {Method::Xy, Method::Mvc, Method::Arap}) {
    ParamOptions o;
    o.method = method;
    ParamReport a, b;
    parameterize(near, o, &a);
    parameterize(far, o, &b);
    EXPECT_NEAR(a.distortion.l2_stretch, b.distortion.l2_stretch, 1e-4) << methodName(method);
    EXPECT_TRUE(b.distortion.valid());
  }
}

// A steep, folded heightfield: the projection folds, so auto goes on to the solvers.
mesh::Mesh eggCrate() {
  return test::heightGrid(60, 60, 1.0, [](double x, double y) { return 8.0 * std::sin(x / 3.0) * std::sin(y / 4.0); });
}

TEST(Parameterize, AutoSpendsNoMoreThanItsBudgetAllows) {
  // With no budget only the first method runs; the others are skipped, saying why.
  ParamOptions o;
  o.budget_seconds = 0.0;
  o.accept_over_stretch = true;
  ParamReport r;
  try {
    parameterize(eggCrate(), o, &r);
  } catch (const Error&) {
    // the projection folds: nothing valid is allowed, which is the point
  }
  ASSERT_GE(r.trials.size(), 2u);
  EXPECT_TRUE(r.trials[0].ran);
  for (std::size_t i = 1; i < r.trials.size(); ++i) {
    EXPECT_FALSE(r.trials[i].ran) << methodName(r.trials[i].method);
    EXPECT_NE(r.trials[i].note.find("budget"), std::string::npos) << r.trials[i].note;
    EXPECT_GT(r.trials[i].predicted_seconds, 0.0);
  }
  // With a budget that affords them every method runs on this 3600-vertex mesh. (Not the
  // default 5 s: the plan predicts from the measured speed, and under a loaded CI run the
  // default skipped one.)
  ParamReport full;
  ParamOptions ample;
  ample.budget_seconds = 600.0;
  parameterize(eggCrate(), ample, &full);
  for (const MethodTrial& t : full.trials)
    EXPECT_TRUE(t.ran || t.note.find("already found") != std::string::npos) << t.note;
}

// The kept map is the least L2 stretch of the valid trials (an atlas only when the best
// one-piece map is more than the preference factor worse), and the report says so.
TEST(Parameterize, AutoKeepsTheLeastStretchOfWhatItTried) {
  for (const mesh::Mesh& m : {eggCrate(), test::uvSphere(2.0, 16, 32), test::torus(3.0, 1.0, 24, 12)}) {
    ParamReport r;
    const mesh::Mesh out = parameterize(m, {}, &r);
    double piece = std::numeric_limits<double>::infinity(), atlas = piece;
    for (const MethodTrial& t : r.trials) {
      if (!t.ran || !t.distortion.valid()) continue;
      (t.method == Method::Charts ? atlas : piece) =
          std::min(t.method == Method::Charts ? atlas : piece, t.distortion.l2_stretch);
    }
    for (const Refinement& f : r.refinements)
      if (f.kept) piece = std::min(piece, f.distortion.l2_stretch);
    const bool atlasWins = piece > ParamOptions{}.one_piece_preference * atlas;
    EXPECT_EQ(r.method == Method::Charts, atlasWins) << trialTable(r);
    EXPECT_DOUBLE_EQ(r.distortion.l2_stretch, atlasWins ? atlas : piece);
    EXPECT_NEAR(measureDistortion(out).l2_stretch, r.distortion.l2_stretch, 1e-6);
    EXPECT_NE(r.decision.find(methodName(r.method)), std::string::npos) << r.decision;
  }
}

TEST(Parameterize, AMapAboveTheStretchLimitIsAnErrorUnlessAccepted) {
  ParamOptions o;
  o.method = Method::Tutte;  // circle border on a square grid: L2 ~1.5
  o.max_stretch = 1.1;
  test::expectErrorNaming([&] { parameterize(mountain(), o, nullptr, "peak.obj"); }, "peak.obj", "--max-stretch");
  o.accept_over_stretch = true;
  ParamReport r;
  const mesh::Mesh out = parameterize(mountain(), o, &r, "peak.obj");
  EXPECT_GT(r.distortion.l2_stretch, 1.1);
  EXPECT_TRUE(measureDistortion(out).valid());
}

// When the budget left methods out, the refusal says which, and that a larger budget would
// try them: a closed cube with no time tries one method (the first always runs).
TEST(Parameterize, ARefusalNamesWhatTheBudgetLeftOut) {
  ParamOptions o;
  o.budget_seconds = 0.0;
  o.max_stretch = 1.0;
  ParamReport r;
  try {
    parameterize(test::uvSphere(1.0, 12, 24), o, &r, "ball.off");
    ADD_FAILURE() << "no refusal";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("--max-stretch"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a larger budget would try"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(Parameterize, ClosedSphereIsCutOpenAlongOneSeam) {
  const mesh::Mesh sphere = test::uvSphere(2.0, 16, 32);
  for (Method method : {Method::Auto, Method::Tutte, Method::Lscm, Method::Arap}) {
    ParamOptions o;
    o.method = method;
    ParamReport r;
    const mesh::Mesh out = parameterize(sphere, o, &r, "ball.off");
    SCOPED_TRACE(methodName(method));
    ASSERT_GE(r.seam_vertices, 3);
    // The seam's interior vertices appear twice; nothing else changes.
    EXPECT_EQ(out.positions.size(), sphere.positions.size() + static_cast<std::size_t>(r.seam_vertices - 2));
    EXPECT_EQ(out.triangles.size(), sphere.triangles.size());
    EXPECT_EQ(borderLoops(out), 1);
    EXPECT_TRUE(measureDistortion(out).valid()) << measureDistortion(out).summary();
  }
}

// The one-piece methods refuse what is not a disc and point to charts; auto and charts
// take it (see the Charts tests).
TEST(Parameterize, OnePieceMethodsRefuseWhatIsNotADisc) {
  ParamOptions lscm;
  lscm.method = Method::Lscm;
  test::expectErrorNaming([&] { parameterize(test::torus(3.0, 1.0, 24, 12), lscm, nullptr, "ring.off"); }, "ring.off",
                          "closed mesh of genus 1");
  test::expectErrorNaming([&] { parameterize(test::torus(3.0, 1.0, 24, 12), lscm, nullptr, "ring.off"); }, "ring.off",
                          "--method charts");
  mesh::Mesh holed = flatGrid(8);
  holed.triangles.erase(holed.triangles.begin() + 48, holed.triangles.begin() + 50);  // an interior hole
  test::expectErrorNaming([&] { parameterize(holed, lscm, nullptr, "holed.obj"); }, "holed.obj", "2 border loops");
  mesh::Mesh two = flatGrid(4);
  const mesh::Mesh other = test::heightGrid(
      4, 4, 1.0, [](double, double) { return 0.0; }, glm::dvec3(10, 0, 0));
  const auto n = static_cast<unsigned>(two.positions.size());
  two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
  for (glm::uvec3 t : other.triangles) two.triangles.push_back(t + glm::uvec3(n));
  test::expectErrorNaming([&] { parameterize(two, lscm, nullptr, "two.obj"); }, "two.obj", "border loops");
  mesh::Mesh nan = flatGrid(4);
  nan.positions[5].z = std::nan("");
  test::expectErrorNaming([&] { parameterize(nan, {}, nullptr, "nan.ply"); }, "nan.ply", "NaN");
  test::expectErrorNaming([] { parameterize(mesh::Mesh{}, {}, nullptr, "empty.off"); }, "empty.off", "no triangles");
  test::expectErrorNaming([] { parseMethod("magic"); }, "--method", "'magic'");
}

// Every CGAL test mesh (libcgal-demo): after the repair the tool runs, a valid map within
// the default stretch limit (closed ones, handles included, through charts), never a
// crash, a refusal or NaN.
TEST(Parameterize, EveryCgalTestMeshGetsAValidMap) {
  const char* names[] = {
      "three_peaks",    "elephant-with-holes", "holes",       "lion", "blobby_3cc", "triceratops", "anchor",
      "degtri_sliding", "oblong-shuffled",     "cube-ouvert", "bear", "cube_quad",  "cross_quad"};
  int parameterized = 0;
  for (const char* name : names) {
    const std::filesystem::path f = test::cgalMeshes() / (std::string(name) + ".off");
    if (!std::filesystem::exists(f)) {
      ADD_FAILURE() << "missing " << f;
      continue;
    }
    SCOPED_TRACE(name);
    mesh::RepairOptions ro;
    ro.max_hole_edges = 1 << 30;
    const mesh::Mesh m = mesh::repairMesh(mesh::readPolygonSoup(f), ro, nullptr, f.string());
    try {
      ParamReport r;
      // Every method auto would try, whatever the machine's load: the budget's skips are
      // timing, tested on their own (AutoSpendsNoMoreThanItsBudgetAllows); under load a
      // 5 s budget skipped charts for the lion and kept MVC's L2 5.5.
      ParamOptions o;
      o.budget_seconds = 1e9;
      const mesh::Mesh out = parameterize(m, o, &r, f.string());
      EXPECT_TRUE(measureDistortion(out).valid());
      for (const glm::vec2& uv : out.uvs) ASSERT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
      ++parameterized;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(f.string()), std::string::npos) << msg;
      ADD_FAILURE() << msg;
    }
  }
  EXPECT_EQ(parameterized, static_cast<int>(std::size(names)));  // handles and all, through charts
}

}  // namespace

}  // namespace shanshui::param
