// Error against run time for parameterization (SPEC.md sections 5 and 12): distortion and
// seconds per method on the real DEMs and CGAL's test meshes, plus `auto` end to end
// (read OBJ, repair, parameterize, write OBJ) on a 230k-vertex mountain. The input with a
// known answer is a developable ridge (z depends on x only): it unrolls isometrically, so
// every method's L2 stretch should be 1. Writes param_tradeoff.csv, .md and _points.csv
// (for shanshui-bench's plots). --quick: small meshes, no CGAL meshes, no 230k run.
//   bench_param_tradeoff [--out DIR] [--max-vertices N] [--quick]
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_data.h"
#include "bench_output.h"
#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/param/parameterize.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Input {
  std::string name;
  mesh::Mesh mesh;
};

mesh::Mesh demMesh(const fs::path& f, int maxVertices) {
  terrain::HeightfieldOptions ho;
  if (f.extension() == ".png") ho.cell_size = 90.0;  // 3 arc-seconds
  terrain::TerrainMeshOptions mo;
  mo.max_vertices = maxVertices;
  return terrain::heightfieldToMesh(terrain::loadHeightfield(f, ho), mo);
}

const char* const kDevelopable = "developable ridge";

// z = f(x) only: a ruled surface with zero Gaussian curvature, so an isometric map (L2
// stretch exactly 1) exists — the unrolled cross-section.
mesh::Mesh developableRidge(int n) {
  mesh::Mesh m;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = i * 10.0, y = j * 10.0;
      m.positions.emplace_back(x, y, 250.0 * std::sin(x / 150.0) + 120.0 * std::exp(-(x - 600) * (x - 600) / 20000.0));
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto a = static_cast<unsigned>(j * n + i), w = static_cast<unsigned>(n);
      m.triangles.emplace_back(a, a + 1, a + w + 1);
      m.triangles.emplace_back(a, a + w + 1, a + w);
    }
  return m;
}

// A cube of six n × n grids: developable piece by piece, so an atlas can reach L2 stretch
// exactly 1 (the known answer for the chart knobs).
mesh::Mesh subdividedCube(int n) {
  mesh::Mesh m;
  std::map<std::array<long, 3>, unsigned> index;
  auto vertex = [&](glm::dvec3 p) {
    const std::array<long, 3> key{std::lround(p.x * n), std::lround(p.y * n), std::lround(p.z * n)};
    const auto [it, inserted] = index.emplace(key, static_cast<unsigned>(m.positions.size()));
    if (inserted) m.positions.push_back(p);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          unsigned q[4];
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            glm::dvec3 p(0.0);
            p[axis] = side;
            p[u] = static_cast<double>(i + di[k]) / n;
            p[v] = static_cast<double>(j + dj[k]) / n;
            q[k] = vertex(p);
          }
          // Outward winding: (u, v, axis) is right-handed, so side 1 keeps the order.
          if (side == 1) {
            m.triangles.emplace_back(q[0], q[1], q[2]);
            m.triangles.emplace_back(q[0], q[2], q[3]);
          } else {
            m.triangles.emplace_back(q[0], q[2], q[1]);
            m.triangles.emplace_back(q[0], q[3], q[2]);
          }
        }
    }
  return m;
}

// A steep mountain on an n × n grid of 30 m cells: the projection's L2 stretch is about
// 1.03, above auto's early stop, so auto goes on to the solvers as far as its budget allows.
mesh::Mesh steepMountain(int n) {
  return mesh::heightGrid(n, n, 14000.0 / (n - 1), [](double x, double y) {
    const double dx = x - 7000, dy = y - 7500;
    return 3200.0 * std::exp(-(dx * dx + dy * dy) / (2 * 2600.0 * 2600.0)) +
           650.0 * std::sin(x / 700.0) * std::cos(y / 900.0);
  });
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(
      argc, argv, "bench_param_tradeoff [--out DIR] [--max-vertices N] [--quick]", {"--max-vertices"});
  const fs::path out = args.out;
  const bool quick = args.quick;
  const int maxVertices = args.integer("--max-vertices", quick ? 3000 : 30000);
  fs::create_directories(out);
  std::vector<Input> inputs;
  inputs.push_back({kDevelopable, developableRidge(quick ? 40 : 120)});
  const fs::path source = SHANSHUI_SOURCE_DIR, data = bench::dataDir();
  for (const fs::path& f : {source / "samples/terrain/mount_st_helens.dem",
                            data / "terrain/jacksboro_fault_dem_u16.png", data / "terrain/bc_coast_topobathy.asc"}) {
    if (fs::exists(f)) inputs.push_back({f.filename().string(), demMesh(f, maxVertices)});
  }
  for (const char* name : {"three_peaks", "holes", "lion", "blobby_3cc"}) {
    if (quick) break;
    const fs::path f = fs::path(SHANSHUI_TEST_MESH_DIR) / (std::string(name) + ".off");
    if (!fs::exists(f)) continue;
    mesh::RepairOptions ro;
    ro.max_hole_edges = 1 << 30;
    inputs.push_back({f.filename().string(), mesh::repairMesh(mesh::readPolygonSoup(f), ro, nullptr, f.string())});
  }

  struct Config {
    std::string name;
    param::Method method;
    param::Border border;
  };
  using param::Border;
  using param::Method;
  const std::vector<Config> configs = {
      {"auto", Method::Auto, Border::Circle},
      {"xy", Method::Xy, Border::Circle},
      {"mvc circle", Method::Mvc, Border::Circle},
      {"mvc square", Method::Mvc, Border::Square},
      {"dcm circle", Method::Dcm, Border::Circle},
      {"tutte circle", Method::Tutte, Border::Circle},
      {"authalic circle", Method::Authalic, Border::Circle},
      {"lscm", Method::Lscm, Border::Circle},
      {"arap", Method::Arap, Border::Circle},
      {"charts", Method::Charts, Border::Circle},
  };
  bench::OutputFile csv(out / "param_tradeoff.csv");
  csv << "input,vertices,config,seconds,l2_stretch,linf_stretch,angle_distortion,area_distortion,flipped,"
         "degenerate,valid,note\n";
  bench::OutputFile md(out / "param_tradeoff.md");
  md << "Parameterization: distortion against seconds per method (DEMs decimated to at most " << maxVertices
     << " vertices). L2/Linf: Sander stretch, angle: mean σ1/σ2, area: mean |log σ1σ2| (all area-weighted; "
        "1, 1, 1, 0 ideal). Invalid = flipped or degenerate UV faces.\n\n"
     << "| input | vertices | method | seconds | L2 | Linf | angle | area | valid "
        "|\n|---|---|---|---|---|---|---|---|---|\n";
  bench::TradeoffPoints points(out / "param_tradeoff_points.csv");
  char line[512];
  for (const Input& in : inputs) {
    for (const Config& c : configs) {
      param::ParamOptions o;
      o.method = c.method;
      o.border = c.border;
      o.accept_over_stretch = c.method != Method::Auto;  // the table shows each method as it is
      param::ParamReport r;
      std::string note;
      const auto start = Clock::now();
      try {
        param::parameterize(in.mesh, o, &r, in.name);
      } catch (const Error& e) {
        note = e.what();
        if (!r.trials.empty()) r.distortion = r.trials.back().distortion;
      }
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      const param::Distortion& d = r.distortion;
      const std::string label =
          c.method == Method::Auto ? "auto -> " + std::string(param::methodName(r.method)) : c.name;
      csv << in.name << "," << in.mesh.vertexCount() << "," << label << "," << seconds << "," << d.l2_stretch << ","
          << d.linf_stretch << "," << d.angle_distortion << "," << d.area_distortion << "," << d.flipped << ","
          << d.degenerate << "," << (note.empty() && d.valid()) << ",\"" << note << "\"\n";
      std::snprintf(line, sizeof line, "| %s | %zu | %s | %.3f | %.4f | %.3g | %.4f | %.4f | %s |\n", in.name.c_str(),
                    in.mesh.vertexCount(), label.c_str(), seconds, d.l2_stretch, d.linf_stretch, d.angle_distortion,
                    d.area_distortion, note.empty() && d.valid() ? "yes" : "no");
      md << line;
      std::fprintf(stderr, "%s", line);
      if (in.name == kDevelopable && note.empty())
        points.add("parameterization of a developable ridge", "L2 stretch - 1 (0 = isometric)", label, false,
                   1000.0 * seconds, d.l2_stretch - 1.0);
    }
  }

  // Charts: the stretch limit per chart against run time, on a subdivided cube (an atlas
  // can be exactly isometric there) and on CGAL's cow.
  md << "\n## Charts: the per-chart stretch limit against run time\n\n"
        "| input | faces | chart stretch limit | seconds | charts | L2 | Linf | flipped | atlas usage |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  std::vector<Input> chartInputs;
  chartInputs.push_back({"subdivided cube", subdividedCube(quick ? 6 : 16)});
  const fs::path meshDir = SHANSHUI_TEST_MESH_DIR;
  auto cgal = [&](const char* name) {
    const fs::path f = meshDir / (std::string(name) + ".off");
    mesh::RepairOptions ro;
    ro.components = mesh::ComponentPolicy::KeepAll;
    ro.max_hole_edges = 1 << 30;
    return Input{f.filename().string(), mesh::repairMesh(mesh::readPolygonSoup(f), ro, nullptr, f.string())};
  };
  if (!quick && fs::exists(meshDir / "cow.off")) chartInputs.push_back(cgal("cow"));
  for (const Input& in : chartInputs) {
    for (const double limit : {1.01, 1.05, 1.2, 1.5, 2.0}) {
      param::ChartOptions co;
      co.max_chart_stretch = limit;
      param::AtlasReport ar;
      const auto start = Clock::now();
      const mesh::Mesh atlas = param::parameterizeCharts(in.mesh, co, &ar, in.name);
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      const param::Distortion d = param::measureDistortion(atlas);
      std::snprintf(line, sizeof line, "| %s | %zu | %.2f | %.3f | %zu | %.4f | %.3g | %d | %.2f |\n", in.name.c_str(),
                    in.mesh.triangleCount(), limit, seconds, ar.charts.size(), d.l2_stretch, d.linf_stretch, d.flipped,
                    ar.usage);
      md << line;
      std::fprintf(stderr, "%s", line);
      if (in.name == "subdivided cube") {
        points.add("charts of a subdivided cube", "L2 stretch - 1 (0 = isometric)", "charts", true, 1000.0 * seconds,
                   d.l2_stretch - 1.0);
      }
    }
  }

  // Charts and auto on closed meshes and meshes with handles (CGAL's demo meshes, when
  // extracted), and a 100k-face closed mesh of our own.
  if (!quick) {
    md << "\n## Closed meshes: charts, and what auto keeps\n\n"
          "| input | faces | genus | charts: seconds | charts | L2 | flipped | usage | auto: seconds | auto keeps | "
          "L2 |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<Input> closed;
    for (const char* name : {"cow", "elk", "camel", "bear", "anchor", "armadillo", "bunny00"}) {
      if (fs::exists(meshDir / (std::string(name) + ".off"))) closed.push_back(cgal(name));
    }
    mesh::Mesh bumpy = mesh::uvSphere(1.0, 224, 224);
    for (glm::dvec3& p : bumpy.positions) {
      p *= 1.0 + 0.15 * std::sin(5 * p.x) * std::cos(4 * p.y) + 0.08 * std::sin(9 * p.z);
    }
    closed.push_back({"bumpy sphere", bumpy});
    for (const Input& in : closed) {
      const long long euler = [&] {
        std::set<std::pair<unsigned, unsigned>> edges;
        for (const glm::uvec3& t : in.mesh.triangles)
          for (int k = 0; k < 3; ++k) edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
        return static_cast<long long>(in.mesh.vertexCount()) - static_cast<long long>(edges.size()) +
               static_cast<long long>(in.mesh.triangleCount());
      }();
      param::AtlasReport ar;
      auto start = Clock::now();
      const mesh::Mesh atlas = param::parameterizeCharts(in.mesh, {}, &ar, in.name);
      const double chartSeconds = std::chrono::duration<double>(Clock::now() - start).count();
      const param::Distortion d = param::measureDistortion(atlas);
      param::ParamReport r;
      std::string kept;
      start = Clock::now();
      try {
        param::parameterize(in.mesh, {}, &r, in.name);
        kept = param::methodName(r.method);
      } catch (const Error& e) {
        kept = "refused";
      }
      const double autoSeconds = std::chrono::duration<double>(Clock::now() - start).count();
      std::snprintf(line, sizeof line, "| %s | %zu | %lld | %.2f | %zu | %.3f | %d | %.2f | %.2f | %s | %.3f |\n",
                    in.name.c_str(), in.mesh.triangleCount(), (2 - euler) / 2, chartSeconds, ar.charts.size(),
                    d.l2_stretch, d.flipped, ar.usage, autoSeconds, kept.c_str(), r.distortion.l2_stretch);
      md << line;
      std::fprintf(stderr, "%s", line);
    }

    // Budgeted auto against size on a terrain whose projection is just over the early stop
    // (refined with what is left of the budget, or not).
    md << "\n## auto against size (budget 5 s)\n\n| vertices | refine | seconds | methods run | kept | L2 "
          "|\n|---|---|---|---|---|---|\n";
    for (const int n : {100, 160, 240, 324, 400, 500}) {
      const mesh::Mesh m = steepMountain(n);
      for (const bool refine : {true, false}) {
        param::ParamOptions o;
        o.refine = refine;
        param::ParamReport r;
        const auto t0 = Clock::now();
        param::parameterize(m, o, &r, "steep mountain");
        const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        std::string ran;
        for (const param::MethodTrial& t : r.trials)
          if (t.ran) ran += std::string(ran.empty() ? "" : ", ") + param::methodName(t.method);
        for (const param::Refinement& f : r.refinements) {
          ran += ", refine " + std::string(param::methodName(f.from)) + " (" + std::to_string(f.rounds) + " rounds, " +
                 (f.converged ? "converged"
                  : f.enough  ? "good enough"
                              : "budget") +
                 ")";
        }
        std::snprintf(line, sizeof line, "| %zu | %s | %.2f | %s | %s | %.4f |\n", m.vertexCount(),
                      refine ? "yes" : "no", seconds, ran.c_str(), param::methodName(r.method),
                      r.distortion.l2_stretch);
        md << line;
        std::fprintf(stderr, "%s", line);
      }
    }
  }

  // auto end to end on a 230k-vertex mountain (480 x 480 grid, 30 m cells).
  if (!quick) {
    mesh::Mesh m;
    const int n = 480;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = i * 30.0, y = j * 30.0, dx = x - 7000, dy = y - 7500;
        m.positions.emplace_back(x + 500000.0, y + 4100000.0,
                                 1800.0 * std::exp(-(dx * dx + dy * dy) / (2 * 3000.0 * 3000.0)) +
                                     150.0 * std::sin(x / 700.0) * std::cos(y / 900.0));
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const unsigned a = static_cast<unsigned>(j * n + i);
        m.triangles.emplace_back(a, a + 1, a + n + 1);
        m.triangles.emplace_back(a, a + n + 1, a + n);
      }
    const fs::path in = out / "mountain_230k.obj", result = out / "mountain_230k_uv.obj";
    mesh::writeMesh(m, in);
    const auto start = Clock::now();
    mesh::Mesh read = mesh::repairMesh(mesh::readPolygonSoup(in), {}, nullptr, in.string());
    param::ParamReport r;
    read = param::parameterize(read, {}, &r, in.string());
    mesh::writeMesh(read, result);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::snprintf(line, sizeof line,
                  "\n`auto` end to end on a %zu-vertex mountain (read OBJ, repair, parameterize, write OBJ): %.2f s "
                  "(parameterization %.2f s, method %s, L2 %.4f, %d flipped).\n",
                  m.vertexCount(), seconds, r.seconds, param::methodName(r.method), r.distortion.l2_stretch,
                  r.distortion.flipped);
    md << line;
    std::fprintf(stderr, "%s", line);
    fs::remove(in);
    fs::remove(result);
  }
  std::fprintf(stderr, "wrote %s and %s\n", (out / "param_tradeoff.csv").c_str(), (out / "param_tradeoff.md").c_str());
  return 0;
}
