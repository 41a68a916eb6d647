// shanshui-demo: the whole chain on the bundled samples, the way a content artist runs it:
// enhance a scanned wrinkle sample, quilt a large texture from it, mesh the DEM, give the
// mesh UVs, paint the scene (lines, shading, wrinkles, canvas, diffusion) as a still and an
// orbit, and write a one-page report. Each stage runs one of the shanshui programs; its key
// is a content hash of the program, its arguments and its input files, and a stage whose
// key and outputs are unchanged since the last run is reused instead of run again.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/input.h"
#include "subprocess.h"
#include "tool_main.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Every file the demo reads itself (samples to hash, caches, reports of its stages) passes
// the input gate: a FIFO or a link to /dev/zero among the samples is refused by name.
std::string readFile(const fs::path& p) {
  return shanshui::readInputFile(p, "a file the demo reads", shanshui::kMaxMediaInputBytes);
}

// Whether `path` already holds exactly `bytes` (a missing, empty or different file does not):
// a file the demo writes is left alone then.
bool holds(const fs::path& path, const std::string& bytes) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && fs::file_size(path, ec) == bytes.size() && !ec && readFile(path) == bytes;
}

// A file copied into the assets (the scan, the reference): read through the input gate and
// written atomically, left alone when the copy is already there.
void copyAsset(const fs::path& from, const fs::path& to) {
  const std::string bytes = readFile(from);
  if (!holds(to, bytes)) shanshui::writeFileAtomically(to, bytes);
}

// FNV-1a, 64 bits: enough to notice a changed input (not meant against tampering).
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

struct Stage {
  std::string name, tool;
  std::vector<std::string> args;
  std::vector<fs::path> inputs, outputs;
};

struct Result {
  bool reused = false;
  double seconds = 0.0;
  std::string summary;  //!< the program's last output line
};

class Runner {
 public:
  Runner(fs::path bin_dir, fs::path out, bool force, double stage_limit_s)
      : bin_(std::move(bin_dir)), out_(std::move(out)), force_(force), stage_limit_s_(stage_limit_s) {
    fs::create_directories(out_ / ".cache");
    fs::create_directories(out_ / "logs");
  }

  //! Runs the stage unless it is up to date; `prepare` runs just before the program does.
  Result run(const Stage& s, const std::function<void()>& prepare = {}) {
    Result r;
    const fs::path tool = bin_ / s.tool;
    std::uint64_t key = fnv1a(readFile(tool));
    for (const std::string& a : s.args) key = fnv1a(a + '\0', key);
    for (const fs::path& in : s.inputs) key = fnv1a(readFile(in), key);
    const fs::path cache = out_ / ".cache" / (s.name + ".json");
    const fs::path log = out_ / "logs" / (s.name + ".log");
    bool outputs_there = true;
    for (const fs::path& o : s.outputs) outputs_there = outputs_there && fs::exists(o);
    if (!force_ && outputs_there && fs::exists(cache)) {
      const json c = json::parse(readFile(cache), nullptr, false);
      if (!c.is_discarded() && c.value("key", "") == hex(key)) {
        r.reused = true;
        r.seconds = c.value("seconds", 0.0);
        r.summary = c.value("summary", "");
        std::printf("%-8s reused (inputs unchanged)\n", s.name.c_str());
        return r;
      }
    }
    if (prepare) prepare();
    std::printf("%-8s running %s\n", s.name.c_str(), s.tool.c_str());
    std::fflush(stdout);
    const auto start = std::chrono::steady_clock::now();
    const shanshui::tools::ProgramRun run = shanshui::tools::runProgram(tool, s.args, log, {}, stage_limit_s_);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (run.timed_out) {
      fs::remove(cache);
      throw shanshui::makeError("stage ", s.name, " (", s.tool, ") was still running after --stage-limit ",
                                stage_limit_s_, " s and was stopped; its last line: ", run.last_line,
                                " (log: ", log.string(), ")");
    }
    if (!run.ok) {
      fs::remove(cache);
      throw shanshui::makeError("stage ", s.name, " failed: ", run.last_line, " (log: ", log.string(), ")");
    }
    r.summary = run.last_line;
    shanshui::writeFileAtomically(
        cache, json{{"key", hex(key)}, {"seconds", r.seconds}, {"summary", r.summary}}.dump(2) + "\n");
    return r;
  }

 private:
  fs::path bin_, out_;
  bool force_;
  double stage_limit_s_;
};

// A sample scene's JSON, or an error naming the file and where the text breaks (the
// scene's own checks run in shanshui-render).
json readSampleScene(const fs::path& scene) {
  try {
    return json::parse(readFile(scene));
  } catch (const json::exception& e) {
    std::string msg = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 2: ..." -> the part after "] ".
    if (const auto cut = msg.find("] "); cut != std::string::npos) msg = msg.substr(cut + 2);
    throw shanshui::makeError(scene.string(), ": not valid JSON: ", msg);
  }
}

// The sample scene pointed at the chain's own assets: the parameterized mesh and its UVs,
// the quilted wrinkle texture, diffusion on.
void writeScene(const fs::path& sample_scene, const fs::path& out, bool quick) {
  json j = readSampleScene(sample_scene);
  json& o = j["objects"][0];
  o.erase("dem");
  o.erase("z_scale");
  o.erase("max_vertices");
  o["mesh"] = "st_helens_uv.obj";
  o["wrinkle"]["texture"] = "wrinkle.png";
  o["wrinkle"]["uv"] = "mesh";
  j["diffusion"]["ring_steps"] = 3;
  j["diffusion"]["iterations"] = 5;
  if (quick) j["output"] = {{"width", 160}, {"height", 120}};
  const std::string text = j.dump(2) + "\n";
  if (holds(out, text)) return;  // same content: nothing to do
  shanshui::writeFileAtomically(out, text);
}

// The painting sample (issue 45) made from the chain's own assets: its far peaks become the
// chain's St. Helens mesh with its UVs, wrinkled by seed 001's mapping with the quilted
// texture, drawn as terrain (dissolving border, mist, marks); the other ranges, the models
// and the boat stay the sample's files (paths made absolute, as the scene moves to assets/).
void writePainting(const fs::path& sample_scene, const fs::path& out, bool quick) {
  json j = readSampleScene(sample_scene);
  const fs::path base = fs::absolute(sample_scene).parent_path();
  for (json& o : j["objects"]) {
    for (const char* key : {"mesh", "dem"})
      if (o.contains(key)) o[key] = (base / o[key].get<std::string>()).lexically_normal().string();
    if (quick && o.contains("dem")) o["max_vertices"] = 4000;
  }
  json& far = j["objects"][0];
  far.erase("dem");
  far.erase("max_vertices");
  far["mesh"] = "st_helens_uv.obj";
  far["up"] = "z";
  far["border"]["mode"] = "dissolve";  // the sample's width kept
  far["wrinkle"] = {{"texture", "wrinkle.png"}, {"uv", "mesh"}, {"repeat", 10}, {"inner_tex_factor", 0.9}};
  // The terrain stage made it 1.5 times as high as the DEM the sample scales.
  far["transform"]["scale"][2] = far["transform"]["scale"][2].get<double>() / 1.5;
  if (quick) j["output"] = {{"width", 120}, {"height", 160}};
  const std::string text = j.dump(2) + "\n";
  if (holds(out, text)) return;
  shanshui::writeFileAtomically(out, text);
}

std::string jsonNumber(const fs::path& file, const std::vector<std::string>& path, int precision = 3) {
  json j = json::parse(readFile(file), nullptr, false);
  for (const std::string& k : path) {
    if (!j.is_object() || !j.contains(k)) return "—";
    j = j[k];
  }
  if (!j.is_number()) return j.is_string() ? j.get<std::string>() : "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, j.get<double>());
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Runs the whole shanshui chain on the bundled samples and writes the assets, the pictures and a "
      "report (report.md) under the output directory. A second run reuses every stage whose program, "
      "arguments and input files are unchanged.",
      "shanshui-demo"};
  app.footer(
      "Example:\n"
      "  shanshui-demo --samples samples --out out       # what `make demo` runs\n"
      "  shanshui-demo --samples samples --out out --force   # run every stage again");
  std::string samples = "samples", out = "out";
  bool force = false, quick = false;
  int frames = 12;
  double stage_limit_s = 1800;
  app.add_option("--samples", samples, "the samples directory (scan, DEM, scene)")->capture_default_str();
  app.add_option("--out", out, "output directory")->capture_default_str();
  app.add_option("--frames", frames, "frames of the orbit sequence")->check(CLI::Range(1, 3600))->capture_default_str();
  app.add_flag("--force", force, "run every stage even when its inputs are unchanged");
  app.add_option("--stage-limit", stage_limit_s,
                 "seconds a stage may run before it is stopped with everything it started and the demo "
                 "fails naming it (the slowest takes about a minute here)")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  app.add_flag("--quick", quick, "small sizes everywhere (for tests)");
  std::string reference;
  app.add_option("--reference", reference,
                 "a real ink landscape (image) shown beside the paintings in the report; `make demo` passes "
                 "../shared/data/textures/ink_landscape_scan.jpg when it is there");
  return shanshui::tools::runTool(app, argc, argv, [&] {
    const fs::path s(samples), o(out), assets = fs::path(out) / "assets";
    for (const fs::path& f : {s / "textures/rain_strokes_scan.png", s / "terrain/mount_st_helens.dem",
                              s / "scenes/default.json", s / "scenes/painting.json"}) {
      if (!fs::exists(f)) throw shanshui::makeError(f.string(), ": not found (is --samples the samples directory?)");
      if (f.extension() == ".json") readSampleScene(f);  // a broken scene is named before any work
    }
    if (!reference.empty() && !fs::is_regular_file(reference)) {
      throw shanshui::makeError("--reference: ", reference, ": not found (expected an image file)");
    }
    fs::create_directories(assets);
    // Stages commit one by one: a second demo into the same --out waits for this one to end,
    // then finds every stage up to date, instead of mixing its stages with this run's.
    const shanshui::RunLock lock(o / ".demo.lock", "shanshui-demo");
    const fs::path bin = fs::canonical("/proc/self/exe").parent_path();
    Runner runner(bin, o, force, stage_limit_s);
    const std::string size = quick ? "128x128" : "1024x1024";
    const std::string max_vertices = quick ? "4000" : "250000";
    const std::string orbit_size = quick ? "96x72" : "640x480";
    std::vector<Stage> stages = {
        {"enhance",
         "shanshui-enhance",
         {(s / "textures/rain_strokes_scan.png").string(), "-o", (assets / "wrinkle_sample.png").string()},
         {s / "textures/rain_strokes_scan.png"},
         {assets / "wrinkle_sample.png"}},
        {"quilt",
         "shanshui-quilt",
         {(assets / "wrinkle_sample.png").string(), "-o", (assets / "wrinkle.png").string(), "--size", size,
          "--tileable", "--report", (assets / "quilt.json").string()},
         {assets / "wrinkle_sample.png"},
         {assets / "wrinkle.png", assets / "quilt.json"}},
        {"terrain",
         "shanshui-terrain",
         {(s / "terrain/mount_st_helens.dem").string(), "-o", (assets / "st_helens.obj").string(), "--z-scale", "1.5",
          "--max-vertices", max_vertices},
         {s / "terrain/mount_st_helens.dem"},
         {assets / "st_helens.obj"}},
        {"param",
         "shanshui-param",
         {(assets / "st_helens.obj").string(), "-o", (assets / "st_helens_uv.obj").string(), "--report",
          (assets / "param.json").string(), "--checker", (assets / "checker.png").string()},
         {assets / "st_helens.obj"},
         {assets / "st_helens_uv.obj", assets / "param.json", assets / "checker.png"}},
    };
    std::vector<Result> results;
    for (const Stage& st : stages) results.push_back(runner.run(st));
    // The report shows the scan beside what became of it.
    copyAsset(s / "textures/rain_strokes_scan.png", assets / "scan.png");
    writeScene(s / "scenes/default.json", assets / "scene.json", quick);
    const std::vector<fs::path> scene_inputs = {assets / "scene.json", assets / "st_helens_uv.obj",
                                                assets / "wrinkle.png"};
    Stage still{"still",
                "shanshui-render",
                {(assets / "scene.json").string(), "-o", (o / "mountain.png").string(), "--stats",
                 (o / "mountain_stats.json").string()},
                scene_inputs,
                {o / "mountain.png", o / "mountain_stats.json"}};
    Stage orbit{"orbit",
                "shanshui-render",
                {(assets / "scene.json").string(), "-o", (o / "orbit.png").string(), "--size", orbit_size, "--frames",
                 std::to_string(frames), "--orbit", "40", "--set", "camera.path=[]", "--stats",
                 (o / "orbit_stats.json").string()},
                scene_inputs,
                {o / "orbit_stats.json"}};
    // The headline: the painting sample on the chain's own mesh, UVs and texture.
    writePainting(s / "scenes/painting.json", assets / "painting.json", quick);
    std::vector<fs::path> painting_inputs = {assets / "painting.json", assets / "st_helens_uv.obj",
                                             assets / "wrinkle.png", s / "terrain/hill.asc"};
    for (const char* m : {"pagoda", "pavilion", "hut", "boulder_a", "boulder_b", "boulder_c", "fishing_boat"})
      painting_inputs.push_back(s / "meshes" / (std::string(m) + ".obj"));
    Stage painting{"painting",
                   "shanshui-render",
                   {(assets / "painting.json").string(), "-o", (o / "painting.png").string(), "--stats",
                    (o / "painting_stats.json").string()},
                   painting_inputs,
                   {o / "painting.png", o / "painting_stats.json"}};
    results.push_back(runner.run(painting));
    stages.push_back(painting);
    results.push_back(runner.run(still));
    stages.push_back(still);
    results.push_back(runner.run(orbit));
    stages.push_back(orbit);
    // The three distances, from the sample scenes as they are (DEM, wrinkle texture).
    const std::vector<std::string> distances = {"high", "deep", "level"};
    for (const std::string& d : distances) {
      const fs::path scene = s / "scenes" / (d + "_distance.json");
      if (!fs::exists(scene)) throw shanshui::makeError(scene.string(), ": not found");
      Stage st{d + "_distance",
               "shanshui-render",
               {scene.string(), "-o", (o / (d + ".png")).string(), "--stats", (o / (d + "_stats.json")).string()},
               {scene, s / "terrain/mount_st_helens.dem", s / "textures/rain_strokes_wrinkle.png"},
               {o / (d + ".png"), o / (d + "_stats.json")}};
      if (quick) {
        st.args.insert(st.args.end(), {"--set", "output.height=120", "--set", "output.width=160", "--set",
                                       "objects.0.max_vertices=4000"});
      }
      results.push_back(runner.run(st));
      stages.push_back(st);
    }
    // A sample scene rendered as it is, with its look statistics: `name`.png and
    // `name`_stats.json from scenes/`name`.json, which reads `inputs` besides.
    auto sampleStage = [&](const std::string& name, std::vector<fs::path> inputs) {
      const fs::path scene = s / ("scenes/" + name + ".json");
      if (!fs::exists(scene)) throw shanshui::makeError(scene.string(), ": not found");
      inputs.insert(inputs.begin(), scene);
      const fs::path png = o / (name + ".png"), stats = o / (name + "_stats.json");
      Stage st{name,
               "shanshui-render",
               {scene.string(), "-o", png.string(), "--stats", stats.string()},
               std::move(inputs),
               {png, stats}};
      if (quick) st.args.insert(st.args.end(), {"--set", "output.height=120", "--set", "output.width=160"});
      results.push_back(runner.run(st));
      stages.push_back(st);
    };
    // Trees and moss dots close up (issue 44): the grove on the project's own hill.
    sampleStage("grove", {s / "terrain/hill.asc", s / "textures/rain_strokes_wrinkle.png"});
    // Water (issue 45): the hill as an island in a lake, with the boat on it.
    sampleStage("lake",
                {s / "terrain/hill.asc", s / "textures/rain_strokes_wrinkle.png", s / "meshes/fishing_boat.obj"});
    // Seed 002's brush strokes (willow leaf) on the level distance.
    {
      const fs::path scene = s / "scenes/level_distance.json";
      Stage st{"level_strokes",
               "shanshui-render",
               {scene.string(), "-o", (o / "level_strokes.png").string(), "--stats",
                (o / "level_strokes_stats.json").string(), "--set", "objects.0.strokes.style=\"liuye\""},
               {scene, s / "terrain/mount_st_helens.dem", s / "textures/rain_strokes_wrinkle.png"},
               {o / "level_strokes.png", o / "level_strokes_stats.json"}};
      if (quick) {
        st.args.insert(st.args.end(), {"--set", "output.height=120", "--set", "output.width=160", "--set",
                                       "objects.0.max_vertices=4000"});
      }
      results.push_back(runner.run(st));
      stages.push_back(st);
    }
    // Seed 002's strokes on a mesh too (the sample boat), beside its feature lines.
    for (const bool strokes : {false, true}) {
      const fs::path mesh = s / "meshes/fishing_boat.obj";
      if (!fs::exists(mesh)) throw shanshui::makeError(mesh.string(), ": not found");
      const std::string name = strokes ? "boat_strokes" : "boat_lines";
      Stage st{name,
               "shanshui-render",
               {mesh.string(), "-o", (o / (name + ".png")).string(), "--size", quick ? "160x100" : "480x320", "--set",
                "objects.0.up=\"z\""},
               {mesh},
               {o / (name + ".png")}};
      if (strokes) {
        st.args.insert(st.args.end(),
                       {"--set", "objects.0.strokes.style=\"liuye\"", "--set", "objects.0.strokes.width=6", "--set",
                        "objects.0.strokes.crease=40", "--set", "objects.0.lines.enabled=false"});
      }
      results.push_back(runner.run(st));
      stages.push_back(st);
    }
    // Seeds 000 and 003: a light-colour wash, painted shadows, pooled edges, the paper's relief.
    {
      const fs::path scene = s / "scenes/light_colour.json";
      if (!fs::exists(scene)) throw shanshui::makeError(scene.string(), ": not found");
      Stage st{"light_colour",
               "shanshui-render",
               {scene.string(), "-o", (o / "light_colour.png").string(), "--stats",
                (o / "light_colour_stats.json").string()},
               {scene, s / "terrain/mount_st_helens.dem", s / "textures/rain_strokes_wrinkle.png"},
               {o / "light_colour.png", o / "light_colour_stats.json"}};
      if (quick) {
        st.args.insert(st.args.end(), {"--set", "output.height=120", "--set", "output.width=160", "--set",
                                       "objects.0.max_vertices=4000"});
      }
      results.push_back(runner.run(st));
      stages.push_back(st);
    }
    // Seed 004: a boat drifting below the mountain, three frames with motion blur and without.
    for (const bool blur : {true, false}) {
      const fs::path scene = s / "scenes/moving_boat.json";
      if (!fs::exists(scene)) throw shanshui::makeError(scene.string(), ": not found");
      const std::string name = blur ? "moving" : "moving_sharp";
      Stage st{blur ? "moving_boat" : "moving_boat_sharp",
               "shanshui-render",
               {scene.string(), "-o", (o / (name + ".png")).string(), "--frames", "3", "--orbit", "0", "--fps", "2",
                "--size", quick ? "160x80" : "640x320", "--stats", (o / (name + "_stats.json")).string(), "--set",
                blur ? "motion_blur.enabled=true" : "motion_blur.enabled=false"},
               {scene, s / "terrain/mount_st_helens.dem", s / "textures/rain_strokes_wrinkle.png",
                s / "meshes/fishing_boat.obj"},
               {o / (name + "_stats.json")}};
      if (quick) st.args.insert(st.args.end(), {"--set", "objects.0.max_vertices=4000"});
      results.push_back(runner.run(st));
      stages.push_back(st);
    }
    if (!reference.empty()) {
      copyAsset(reference, assets / ("reference" + fs::path(reference).extension().string()));
    }

    // The stability suite (built with the tests), its table for the report; keyed by the
    // suite and every program it runs. --quick runs only its fast library cases.
    const fs::path suite = bin / "test_stability", stability = o / "stability";
    const bool have_suite = fs::exists(suite);
    std::string stability_failure;
    if (have_suite) {
      ::setenv("SHANSHUI_STABILITY_DIR", fs::absolute(stability).c_str(), 1);
      std::vector<fs::path> programs;
      for (const char* p : {"shanshui-terrain", "shanshui-repair", "shanshui-enhance", "shanshui-quilt",
                            "shanshui-param", "shanshui-render"})
        programs.push_back(bin / p);
      Stage st{"stability", "test_stability", {"--gtest_brief=1"}, programs, {stability / "stability.md"}};
      if (quick)
        st.args.push_back(
            "--gtest_filter=Stability.RepairOn*:Stability.CurvatureOn*:Stability.InkDiffusionOn*:"
            "Stability.NoiseOn*");
      // A failing case still leaves its table: the report is written, then the demo fails.
      try {
        results.push_back(runner.run(st, [&] {
          fs::remove_all(stability);  // the suite assembles its table from every stage file there
          fs::create_directories(stability);
        }));
      } catch (const shanshui::Error& e) {
        stability_failure = e.what();
        results.push_back({false, 0.0, "FAILED: " + stability_failure});
      }
      stages.push_back(st);
    }

    // The report: pictures, and per stage its time and its quality numbers.
    std::ostringstream md;
    md << "# shanshui demo\n\nThe whole chain on the bundled samples (`shanshui-demo`). Stages marked *reused* were "
          "not run: their program, arguments and inputs hash to the same key as in the run that made their outputs "
          "(times are from that run).\n\n"
       << "| stage | program | seconds | this run | result |\n|---|---|---|---|---|\n";
    // Paths in the programs' messages, relative to the report.
    auto relative = [&](std::string text) {
      for (const auto& [from, to] :
           {std::pair{o.string() + "/", std::string()}, std::pair{s.string() + "/", std::string("samples/")}}) {
        for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
          text.replace(at, from.size(), to);
      }
      return text;
    };
    for (std::size_t i = 0; i < stages.size(); ++i) {
      std::string summary = relative(results[i].summary);
      for (char& c : summary)
        if (c == '|') c = '/';
      char secs[32];
      std::snprintf(secs, sizeof secs, "%.2f", results[i].seconds);
      md << "| " << stages[i].name << " | `" << stages[i].tool << "` | " << secs << " | "
         << (results[i].reused ? "reused" : "ran") << " | " << summary << " |\n";
    }
    md << "\n## Texture\n\n![scan](assets/scan.png) ![enhanced](assets/wrinkle_sample.png) "
          "![quilted](assets/wrinkle.png)\n\n"
       << "Scan, enhanced sample, quilted texture. Quilting: overlap error "
       << jsonNumber(assets / "quilt.json", {"overlap_error_per_pixel"}) << " per pixel, seam error "
       << jsonNumber(assets / "quilt.json", {"mean_seam_error_per_overlap_pixel"})
       << " per overlap pixel, largest copied "
       << "region " << jsonNumber(assets / "quilt.json", {"largest_copy_blocks"}) << " blocks.\n\n"
       << "## Mesh and UVs\n\n![checker](assets/checker.png)\n\nParameterization (`"
       << jsonNumber(assets / "param.json", {"method"}) << "`): L2 stretch "
       << jsonNumber(assets / "param.json", {"distortion", "l2_stretch"}) << ", angle distortion "
       << jsonNumber(assets / "param.json", {"distortion", "angle_distortion"}) << ", flipped faces "
       << jsonNumber(assets / "param.json", {"distortion", "flipped"}) << ".\n\n"
       << "## Painting\n\n![painting](painting.png)\n\n"
       << "The painting sample (`samples/scenes/painting.json`) on the chain's own assets: far peaks from the "
          "St. Helens mesh above with its UVs and the quilted texture (seed 001's mapping), a middle range and "
          "a near bank from the project's hill with texture marks (axe cuts, hemp fibres), trees and moss dots, "
          "a pagoda on the middle range's summit, a pavilion, a hut and boulders on the near bank, open water "
          "with a boat, mist between the ranges.\n\n"
       << "The sample scene's style on the chain's mesh alone:\n\n![mountain](mountain.png)\n\n";
    const json stats = json::parse(readFile(o / "mountain_stats.json"), nullptr, false);
    if (!stats.is_discarded() && stats.contains("frames") && !stats["frames"].empty()) {
      md << "Passes and GPU milliseconds of the still:";
      for (const auto& [name, ms] : stats["frames"][0]["passes"].items()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " %s %.1f;", name.c_str(), ms.get<double>());
        md << buf;
      }
      md << " device: " << stats.value("device", std::string("(not recorded)")) << ".\n\n";
    }
    md << "Orbit (" << frames << " frames): ";
    for (int i = 0; i < frames; i += std::max(1, frames / 4)) {
      char name[64];
      std::snprintf(name, sizeof name, frames > 1 ? "orbit_%04d.png" : "orbit.png", i);
      md << "![frame " << i << "](" << name << ") ";
    }
    md << "\n\n## The three distances, beside a real ink landscape\n\n";
    md << "High distance (a hanging scroll), deep distance, level distance";
    if (!reference.empty()) md << ", and the reference scan (`--reference`)";
    md << ":\n\n![high](high.png) ![deep](deep.png) ![level](level.png)";
    if (!reference.empty()) {
      md << " ![reference](assets/reference" << fs::path(reference).extension().string() << ")";
    }
    md << "\n\nTrees and moss dots grown on the terrain and drawn as brushwork (every sample has them; "
          "`samples/scenes/grove.json` shows them close, on a hill of the project's own): pines with needle fans, "
          "leafy trees of dot leaves, bare branches, distant trees as a few dots, in groves on ridges, in hollows "
          "and on valley floors, with clusters of moss dots:\n\n![grove](grove.png)";
    md << "\n\nWater (`samples/scenes/lake.json`, `water.level`): the land below the level is hidden and left as "
          "paper with a few horizontal wave strokes laid on the water, the shore drawn as a broken line "
          "(`water.bank_break`), the boat on the lake, nothing growing under it:\n\n![lake](lake.png)";
    md << "\n\nThe level distance with seed 002's brush strokes along its silhouettes and creases "
          "(`objects.N.strokes.style: liuye`, willow leaf: thin, thick, thin):\n\n"
          "![level strokes](level_strokes.png)\n\nOn a mesh (the sample boat): its feature lines, and liuye brush "
          "strokes along its silhouettes, borders and creases instead:\n\n"
          "![boat lines](boat_lines.png) ![boat strokes](boat_strokes.png)";
    md << "\n\nThe deep distance in light colour (seeds 000 and 003, `samples/scenes/light_colour.json`): an ochre "
          "wash laid by Kubelka-Munk over the ink, indigo cast shadows from a shadow map, pigment pooled at the "
          "edges of the washes, and the paper's relief under the dried paint:\n\n"
          "![light colour](light_colour.png)";
    md << "\n\nSomething moving (seed 004, `samples/scenes/moving_boat.json`): a fishing boat drifting below the "
          "mountain, three frames half a second apart, with motion blur (ink dragged behind it, running dry on "
          "the paper's grain) and without:\n\n"
          "![moving 0](moving_0000.png) ![moving 1](moving_0001.png) ![moving 2](moving_0002.png)\n\n"
          "![sharp 0](moving_sharp_0000.png) ![sharp 1](moving_sharp_0001.png) ![sharp 2](moving_sharp_0002.png)";
    md << "\n\nWhat a painter would look at, measured (`look` in `shanshui-render --stats`; docs/render.md): "
          "share of paper-tone pixels, share and mean width of the dark marks, ink of the far third of the "
          "land over the near third, longest straight edge over the width, and the brushwork: distinct dark "
          "marks per megapixel and the spread of their sizes (interquartile range of log2 area; two real ink "
          "landscapes have about 1,600 marks/MP and a spread of 2.6).\n\n"
       << "| picture | paper share | dark share | dark width px | far / near ink | longest straight | marks / MP | "
          "size spread |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const std::string& name : {std::string("painting"), std::string("mountain"), std::string("high"),
                                    std::string("deep"), std::string("level"), std::string("level_strokes"),
                                    std::string("light_colour"), std::string("grove"), std::string("lake")}) {
      const fs::path f = o / (name + "_stats.json");
      const json st = fs::exists(f) ? json::parse(readFile(f), nullptr, false) : json();
      md << "| " << name;
      for (const char* key : {"paper_share", "dark_share", "dark_width_px", "far_near_ink", "longest_straight",
                              "marks_per_mp", "mark_size_spread"}) {
        const bool has = !st.is_discarded() && st.contains("frames") && !st["frames"].empty() &&
                         st["frames"][0].contains("look") && st["frames"][0]["look"].contains(key);
        char buf[32] = "—";
        if (has) std::snprintf(buf, sizeof buf, "%.3g", st["frames"][0]["look"][key].get<double>());
        md << " | " << buf;
      }
      md << " |\n";
    }
    md << "\n## Stability\n\n";
    if (have_suite && fs::exists(stability / "stability.md")) {
      std::string table = readFile(stability / "stability.md");
      table = table.substr(table.find('\n') + 1);  // without its title
      md << "The stability suite (`test_stability`, also `ctest -L stability`)"
         << (quick ? ", fast cases only (--quick)" : "") << "; also as [CSV](stability/stability.csv).\n"
         << table;
    } else {
      md << "The stability suite is built with the tests (SHANSHUI_BUILD_TESTS=ON); this build has none, so no "
            "table.\n";
    }
    md << "\n## Error against run time\n\n`make bench` (or `shanshui-bench --stage all --out out/bench`) measures "
          "every "
          "approximate stage on inputs with known answers and writes tables and plots to out/bench/README.md; the "
          "results of a full run ship in docs/bench/README.md.\n";
    shanshui::writeFileAtomically(o / "report.md", md.str());
    std::printf("report: %s\n", (o / "report.md").string().c_str());
    if (!stability_failure.empty()) throw shanshui::makeError(stability_failure);
  });
}
