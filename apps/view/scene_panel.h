// The viewer's panel: one Dear ImGui widget per scene key, built from the scene's JSON and
// the parameter description's schema (kind, range, meaning as a tooltip). It needs an ImGui
// frame, not a window or GL, so the suite builds it headless for every sample scene.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shanshui::view {

//! One key's widget as drawn this frame.
struct PanelWidget {
  std::string path;      //!< dotted key ("camera.path", "objects.0.lines.curve_factor")
  float width = 0.0f;    //!< width of the value's frame in pixels (the item width it was given)
  bool editable = true;  //!< false: shown as read-only text
};

struct PanelOptions {
  bool open_all = false;                      //!< open every group (the tests' way to see every key)
  std::vector<PanelWidget>* drawn = nullptr;  //!< when set, each key's widget is appended
};

//! Draws a widget for every key of `scene` (a scene's JSON, as scene::toJson writes it) in
//! the current ImGui window. Returns true when the user changed a value; `scene` then holds
//! it. Lists of entries (objects, camera and object paths) can be added to and removed
//! from; an empty list shows as empty with an "add" button.
bool editScene(nlohmann::json& scene, const PanelOptions& options = {});

//! A new entry for the list at `path` ("camera.path"), every key at its documented default.
nlohmann::json defaultEntry(const std::string& path);

}  // namespace shanshui::view
