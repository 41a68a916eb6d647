// The viewer's panel, built headless (an ImGui frame without a window or GL) for every
// sample scene: every key gets a widget with a usable width, and lists can be grown.
#include <imgui.h>

#include <filesystem>
#include <set>

#include "scene_panel.h"
#include "shanshui/scene/scene.h"
#include "test_support.h"

namespace shanshui::view {
namespace {

using nlohmann::json;

// One ImGui frame with the panel in a 420 px window, as the viewer lays it out.
class HeadlessFrame {
 public:
  HeadlessFrame() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(1280, 100000);  // tall: nothing is clipped away
    io.DeltaTime = 1.0f / 60.0f;
    io.IniFilename = nullptr;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
  }
  ~HeadlessFrame() { ImGui::DestroyContext(); }

  std::vector<PanelWidget> draw(json& scene, bool* changed = nullptr) {
    std::vector<PanelWidget> drawn;
    ImGui::NewFrame();
    ImGui::SetNextWindowSize(ImVec2(420, 90000));
    ImGui::Begin("panel");
    const bool c = editScene(scene, {.open_all = true, .drawn = &drawn});
    if (changed) *changed = c;
    ImGui::End();
    ImGui::Render();
    return drawn;
  }
};

// Every leaf key of a scene's JSON (scalars, lists of values, and lists of entries).
void leaves(const json& node, const std::string& path, std::set<std::string>& out) {
  if (node.is_object()) {
    for (const auto& [k, v] : node.items()) leaves(v, path.empty() ? k : path + "." + k, out);
    return;
  }
  if (node.is_array() && !node.empty() && node[0].is_object()) {
    out.insert(path);  // the list itself: its "add" button
    for (std::size_t i = 0; i < node.size(); ++i) leaves(node[i], path + "." + std::to_string(i), out);
    return;
  }
  out.insert(path);
}

TEST(ViewPanel, EverySampleSceneKeyHasAVisibleWidget) {
  int scenes = 0;
  for (const auto& f : std::filesystem::directory_iterator(test::sourceDir() / "samples/scenes")) {
    SCOPED_TRACE(f.path().filename().string());
    json j = scene::toJson(scene::loadScene(f.path()));
    std::set<std::string> keys;
    leaves(j, "", keys);
    HeadlessFrame frame;
    const auto drawn = frame.draw(j);
    std::set<std::string> seen;
    for (const PanelWidget& w : drawn) {
      seen.insert(w.path);
      EXPECT_GE(w.width, 12.0f) << w.path;
      EXPECT_LE(w.width, 420.0f) << w.path;
    }
    for (const std::string& k : keys) EXPECT_TRUE(seen.count(k)) << "no widget for " << k;
    // The empty camera path came before the keys that lost their widgets (issue 46).
    EXPECT_TRUE(seen.count("camera.path"));
    EXPECT_TRUE(seen.count("canvas.type"));
    ++scenes;
  }
  EXPECT_GE(scenes, 7);
}

TEST(ViewPanel, AddingToAnEmptyListGivesAnEntryAtItsDefaults) {
  const json entry = defaultEntry("camera.path");
  ASSERT_TRUE(entry.is_object()) << entry.dump();
  EXPECT_EQ(entry.size(), 3u) << entry.dump();
  EXPECT_EQ(entry["azimuth"], -60);
  EXPECT_EQ(entry["elevation"], 25);
  EXPECT_EQ(entry["zoom"], 1);
  // A new object parses as a scene object (its mesh aside) and nests its own groups.
  const json object = defaultEntry("objects");
  EXPECT_TRUE(object.contains("lines") && object["lines"].is_object()) << object.dump();
  EXPECT_TRUE(object.contains("trees") && object["trees"].contains("enabled")) << object.dump();
  // Two keys make a valid path: the scene parses with them.
  json j = scene::toJson(scene::loadScene(test::sourceDir() / "samples/scenes/level_distance.json"));
  j["camera"]["path"] = json::array({defaultEntry("camera.path"), defaultEntry("camera.path")});
  j["camera"]["path"][1]["azimuth"] = 30;
  const scene::Scene s = scene::parseScene(j, "panel", test::sourceDir() / "samples/scenes");
  EXPECT_EQ(s.camera.path.size(), 2u);
}

}  // namespace
}  // namespace shanshui::view
