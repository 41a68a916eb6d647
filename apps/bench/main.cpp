// shanshui-bench: every approximate stage's error-against-run-time sweep, on inputs with
// known answers, in one call. Each stage is one or more of the bench programs built beside
// this one (bench/); each writes its Markdown and CSV tables and a points file
// (`plot,y_label,series,joined,ms,error`) into --out, from which this program draws one PNG
// per plot and an index (README.md) linking everything. A stage that fails is reported
// (with its log) and the others still run; the exit code is then 1.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "plot.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/core/input.h"
#include "subprocess.h"
#include "tool_main.h"

namespace {

namespace fs = std::filesystem;
using namespace shanshui;

struct StageDef {
  std::string name;
  std::vector<std::string> programs;
  std::string what;
};

const std::vector<StageDef> kStages = {
    {"quilt", {"bench_quilt_tradeoff"}, "image quilting: search and seam modes, error against the exhaustive search"},
    {"param",
     {"bench_param_tradeoff"},
     "parameterization: every method's distortion and time; a developable ridge has an isometric answer"},
    {"curvature",
     {"bench_curvature_tradeoff", "bench_ink_tradeoff", "bench_dequantize_tradeoff", "bench_upsample_tradeoff"},
     "curvature estimators on analytic surfaces, per vertex and per pixel; the ink frame against Lambert; wrinkle "
     "filters; heights stored in steps smoothed within them; coarse DEMs made finer"},
    {"diffusion",
     {"bench_diffusion_tradeoff"},
     "ink diffusion: distance transform against rings, n against a converged result"},
    {"strokes",
     {"bench_strokes_tradeoff"},
     "brush strokes: spline sampling against a silhouette of known radius; linking against the known chain count"},
    {"paper",
     {"bench_paper_tradeoff"},
     "paper and pigment: edge darkening's taps against 15 x 15; shadow map resolution against an analytic shadow"},
    {"noise", {"bench_canvas_tradeoff"}, "paper canvas: N′ against the analytic Gabor spectrum; temporal coherence"},
    {"pipeline", {"bench_pipeline_tradeoff"}, "the whole frame at quality presets against a high-quality reference"},
};

// One CSV record; fields may be double-quoted with "" for a quote.
std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        f.back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        f.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  return f;
}

double number(const std::string& s) {
  try {
    std::size_t used = 0;
    const double v = std::stod(s, &used);
    return used == s.size() ? v : std::nan("");
  } catch (const std::exception&) {
    return std::nan("");
  }
}

std::string slug(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      o += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!o.empty() && o.back() != '_')
      o += '_';
  }
  while (!o.empty() && o.back() == '_') o.pop_back();
  return o;
}

//! The plots of one points file, in order of first appearance.
std::vector<bench::Plot> readPoints(const fs::path& csv) {
  std::istringstream in(readInputFile(csv, "a bench points table (CSV)", kMaxTextInputBytes));
  std::string line;
  std::getline(in, line);
  if (line != "plot,y_label,series,joined,ms,error")
    throw makeError(csv.string(), ": header '", line, "', expected 'plot,y_label,series,joined,ms,error'");
  std::vector<bench::Plot> plots;
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> f = splitCsv(line);
    if (f.size() != 6) throw makeError(csv.string(), ":", row, ": ", f.size(), " fields, expected 6");
    auto p = std::find_if(plots.begin(), plots.end(), [&](const bench::Plot& q) { return q.title == f[0]; });
    if (p == plots.end()) {
      plots.push_back({f[0], "run time (ms)", f[1], {}});
      p = plots.end() - 1;
    }
    auto s = std::find_if(p->series.begin(), p->series.end(), [&](const bench::Series& q) { return q.label == f[2]; });
    if (s == p->series.end()) {
      p->series.push_back({f[2], {}, {}, f[3] == "1"});
      s = p->series.end() - 1;
    }
    s->x.push_back(number(f[4]));
    s->y.push_back(number(f[5]));
  }
  return plots;
}

struct Ran {
  std::string stage, program;
  double seconds = 0;
  bool ok = false;
  bool earlier = false;  //!< not run by this call: its results were already in --out
  std::string last_line;
  std::vector<std::string> pngs;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Runs the error-against-run-time sweep of every approximate stage on inputs with known answers and "
      "writes tables (Markdown, CSV), plots (PNG) and an index (README.md) under --out.",
      "shanshui-bench"};
  app.footer(
      "Stages: quilt, param, curvature, diffusion, noise, pipeline (or all). A full run takes about seven minutes\n"
      "on two idle CPU cores with llvmpipe; --quick runs every sweep on small inputs in under a minute.\n\n"
      "Example:\n"
      "  shanshui-bench --stage all --out bench-results\n"
      "  shanshui-bench --stage curvature --stage pipeline --out bench-results --quick");
  std::vector<std::string> stages{"all"};
  std::string out;
  bool quick = false;
  std::vector<std::string> names{"all"};
  for (const StageDef& d : kStages) names.push_back(d.name);
  app.add_option("--stage", stages, "stages to run (repeatable)")->check(CLI::IsMember(names))->capture_default_str();
  app.add_option("--out", out, "output directory (created)")->required();
  app.add_flag("--quick", quick, "small inputs and short sweeps (the shape of each trade-off, not final numbers)");
  return tools::runTool(app, argc, argv, [&] {
    const fs::path dir(out), logs = dir / "logs";
    fs::create_directories(logs);
    const fs::path bin = fs::canonical("/proc/self/exe").parent_path();
    const bool all = std::find(stages.begin(), stages.end(), "all") != stages.end();
    // One PNG per plot of a program's points file.
    auto plot = [&](Ran& r) {
      const std::string base = r.program.substr(std::string("bench_").size());
      const fs::path points = dir / (base + "_points.csv");
      if (!fs::exists(points)) return;
      try {
        for (const bench::Plot& p : readPoints(points)) {
          const std::string png = base + "_" + slug(p.title) + ".png";
          bench::writePlot(p, dir / png);
          r.pngs.push_back(png);
        }
      } catch (const Error& e) {  // a bad points file fails this program, not the run
        r.ok = false;
        r.last_line = e.what();
      }
    };
    std::vector<Ran> ran;
    for (const StageDef& d : kStages) {
      const bool asked = all || std::find(stages.begin(), stages.end(), d.name) != stages.end();
      for (const std::string& program : d.programs) {
        if (!asked) {
          // Results of an earlier call in the same directory stay in the index.
          Ran r;
          r.stage = d.name;
          r.program = program;
          r.earlier = r.ok = fs::exists(dir / (program.substr(std::string("bench_").size()) + ".md"));
          if (r.earlier) {
            plot(r);
            ran.push_back(std::move(r));
          }
          continue;
        }
        Ran r;
        r.stage = d.name;
        r.program = program;
        const fs::path exe = bin / program;
        const auto start = std::chrono::steady_clock::now();
        if (!fs::exists(exe)) {
          r.last_line = "not built: " + exe.string() + " (configure with -DSHANSHUI_BUILD_BENCH=ON)";
        } else {
          std::fprintf(stderr, "[%s] %s\n", d.name.c_str(), program.c_str());
          std::vector<std::string> args{"--out", dir.string()};
          if (quick) args.push_back("--quick");
          const tools::ProgramRun run = tools::runProgram(exe, args, logs / (program + ".log"), "[" + d.name + "]   ");
          r.ok = run.ok;
          r.last_line = run.last_line;
        }
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (r.ok) plot(r);
        std::fprintf(stderr, "[%s] %s: %s in %.1f s%s\n", d.name.c_str(), program.c_str(), r.ok ? "done" : "FAILED",
                     r.seconds, r.ok ? "" : (" — " + r.last_line).c_str());
        ran.push_back(std::move(r));
      }
    }

    std::string index = "# shanshui-bench results\n\n";
    index += std::string("The last call ran ") +
             (quick ? "quick sweeps (--quick: small inputs; the numbers show the shape, "
                      "not the final values)"
                    : "full sweeps") +
             "; rows marked *earlier* are results an earlier call left in this directory.\n\n";
    index += "| stage | program | seconds | status | tables |\n|---|---|---|---|---|\n";
    int failed = 0, now = 0;
    for (const Ran& r : ran) {
      const std::string base = r.program.substr(std::string("bench_").size());
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.1f", r.seconds);
      const std::string status = r.earlier ? "*earlier*"
                                 : r.ok    ? "ok"
                                           : "**failed**: " + r.last_line + " (logs/" + r.program + ".log)";
      index += "| " + r.stage + " | " + r.program + " | " + (r.earlier ? "—" : seconds) + " | " + status + " | " +
               (r.ok ? "[" + base + ".md](" + base + ".md), [csv](" + base + ".csv)" : "") + " |\n";
      failed += r.ok || r.earlier ? 0 : 1;
      now += r.earlier ? 0 : 1;
    }
    for (const StageDef& d : kStages) {
      std::string pictures;
      for (const Ran& r : ran)
        if (r.stage == d.name)
          for (const std::string& png : r.pngs) pictures += "![" + png + "](" + png + ")\n";
      if (!pictures.empty()) index += "\n## " + d.name + ": " + d.what + "\n\n" + pictures;
    }
    writeFileAtomically(dir / "README.md", index);
    std::fprintf(stderr, "wrote %s\n", (dir / "README.md").c_str());
    if (failed) throw makeError(failed, " of ", now, " bench programs failed (see ", (dir / "README.md").string(), ")");
  });
}
