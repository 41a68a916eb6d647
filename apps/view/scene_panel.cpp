#include "scene_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "shanshui/scene/scene.h"

namespace shanshui::view {
namespace {

using nlohmann::json;

// "objects.2.lines.curve_factor" -> "objects.*.lines.curve_factor", the schema's spelling:
// every index into a list of entries is a star.
std::string schemaPath(const std::string& path) {
  std::string out, part;
  auto flush = [&] {
    const bool index = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    out += (out.empty() ? "" : ".") + (index ? std::string("*") : part);
    part.clear();
  };
  for (char c : path) {
    if (c == '.')
      flush();
    else
      part += c;
  }
  flush();
  return out;
}

const scene::SchemaEntry* findSchema(const std::string& path) {
  const std::string p = schemaPath(path);
  for (const auto& e : scene::sceneSchema()) {
    if (e.path == p) return &e;
  }
  return nullptr;
}

// A documented default ("-60", "`none`", "[0, 0, 1]", "null") as JSON.
json parseDefault(std::string text) {
  text.erase(std::remove(text.begin(), text.end(), '`'), text.end());
  json v = json::parse(text, nullptr, false);
  return v.is_discarded() ? json(text) : v;
}

class Panel {
 public:
  explicit Panel(const PanelOptions& o) : options_(o) {}

  bool edit(json& node, const std::string& path, const std::string& label) {
    const scene::SchemaEntry* e = findSchema(path);
    if (node.is_object()) return group(node, path, label);
    if (node.is_array() && ((e && e->kind == "entries") || (!node.empty() && node[0].is_object())))
      return entries(node, path, label, e);
    return leaf(node, path, label, e);
  }

 private:
  bool open(const char* id, ImGuiTreeNodeFlags flags) {
    if (options_.open_all) ImGui::SetNextItemOpen(true);
    return ImGui::TreeNodeEx(id, flags);
  }

  bool group(json& node, const std::string& path, const std::string& label) {
    const bool top = path.empty();
    bool changed = false;
    if (top || open(label.c_str(), path.find('.') == std::string::npos ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
      for (auto& [key, value] : node.items()) changed |= edit(value, top ? key : path + "." + key, key);
      if (!top) ImGui::TreePop();
    }
    return changed;
  }

  // A list of entries: each entry a group with a button that removes it, and a button that
  // adds one at its defaults (the scene's own check then says whether the list is valid).
  bool entries(json& node, const std::string& path, const std::string& label, const scene::SchemaEntry* e) {
    bool changed = false;
    const std::string title = label + " (" + std::to_string(node.size()) + ")###" + label;
    if (!open(title.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) return false;
    if (node.empty()) ImGui::TextDisabled("empty");
    std::size_t remove = node.size();
    for (std::size_t i = 0; i < node.size(); ++i) {
      ImGui::PushID(static_cast<int>(i));
      const std::string name = node[i].is_object() && node[i].contains("name") && node[i]["name"].is_string()
                                   ? node[i]["name"].get<std::string>()
                                   : std::to_string(i);
      changed |= edit(node[i], path + "." + std::to_string(i), name + "##entry");
      if (ImGui::SmallButton("remove")) remove = i;
      ImGui::PopID();
    }
    if (remove < node.size()) {
      node.erase(node.begin() + static_cast<std::ptrdiff_t>(remove));
      changed = true;
    }
    const bool full = e && static_cast<double>(node.size()) >= e->max;
    if (full) ImGui::BeginDisabled();
    const bool add = ImGui::Button(("add " + label).c_str());
    record(path, ImGui::GetItemRectSize().x, true);
    if (full) ImGui::EndDisabled();
    if (add) {
      node.push_back(defaultEntry(path));
      changed = true;
    }
    if (e && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) tooltip(*e);
    ImGui::TreePop();
    return changed;
  }

  bool leaf(json& node, const std::string& path, const std::string& label, const scene::SchemaEntry* e) {
    const char* id = label.c_str();
    const float lo = e ? static_cast<float>(e->min) : 0.0f, hi = e ? static_cast<float>(e->max) : 0.0f;
    const bool bounded = e && hi - lo < 1e5f;
    const float speed = bounded ? (hi - lo) / 500.0f : 0.05f;
    const float width = ImGui::CalcItemWidth();
    bool changed = false;
    if (node.is_boolean()) {
      bool v = node.get<bool>();
      if (ImGui::Checkbox(id, &v)) node = v, changed = true;
      record(path, ImGui::GetFrameHeight(), true);
    } else if (e && e->kind == "choice" && node.is_string()) {
      const std::string current = node.get<std::string>();
      if (ImGui::BeginCombo(id, current.c_str())) {
        for (const auto& c : e->choices) {
          if (ImGui::Selectable(c.c_str(), c == current)) node = c, changed = true;
        }
        ImGui::EndCombo();
      }
      record(path, width, true);
    } else if (node.is_string()) {
      char buf[1024];
      std::snprintf(buf, sizeof buf, "%s", node.get<std::string>().c_str());
      if (ImGui::InputText(id, buf, sizeof buf, ImGuiInputTextFlags_EnterReturnsTrue))
        node = std::string(buf), changed = true;
      record(path, width, true);
    } else if (node.is_number_integer()) {
      // 64-bit: the seed goes up to 2^53.
      long long v = node.get<long long>();
      const long long vlo = e ? static_cast<long long>(e->min) : 0, vhi = e ? static_cast<long long>(e->max) : 0;
      if (ImGui::DragScalar(id, ImGuiDataType_S64, &v, std::max(1.0f, speed), e ? &vlo : nullptr, e ? &vhi : nullptr)) {
        node = v, changed = true;
      }
      record(path, width, true);
    } else if (node.is_number()) {
      float v = node.get<float>();
      if (ImGui::DragFloat(id, &v, speed, bounded ? lo : 0.0f, bounded ? hi : 0.0f, "%.4g")) node = v, changed = true;
      record(path, width, true);
    } else if (node.is_array() && !node.empty() && node.size() <= 8 &&
               std::all_of(node.begin(), node.end(), [](const json& x) { return x.is_number(); })) {
      float v[8] = {};
      for (std::size_t i = 0; i < node.size(); ++i) v[i] = node[i].get<float>();
      const int n = static_cast<int>(node.size());
      const bool edited = e && e->kind == "color" && n == 3
                              ? ImGui::ColorEdit3(id, v)
                              : ImGui::DragScalarN(id, ImGuiDataType_Float, v, n, speed, bounded ? &lo : nullptr,
                                                   bounded ? &hi : nullptr, "%.3g");
      if (edited) {
        for (std::size_t i = 0; i < node.size(); ++i) node[i] = v[i];
        changed = true;
      }
      record(path, width, true);
    } else {
      // Anything else (null = automatic, a list of other values): its value as text.
      std::string text = node.is_null() ? std::string("auto") : node.dump();
      if (text.size() > 60) text = text.substr(0, 57) + "...";
      ImGui::LabelText(id, "%s", text.c_str());
      record(path, width, false);
    }
    if (e && ImGui::IsItemHovered()) tooltip(*e);
    return changed;
  }

  void tooltip(const scene::SchemaEntry& e) {
    ImGui::SetTooltip("%s%s%s\nrange %s%s", e.doc.c_str(), e.unit.empty() ? "" : ", ", e.unit.c_str(),
                      e.range_text.c_str(),
                      e.effect == scene::Effect::Rebuild ? "; a change rebuilds the renderer" : "");
  }

  void record(const std::string& path, float width, bool editable) {
    if (options_.drawn) options_.drawn->push_back({path, width, editable});
  }

  PanelOptions options_;
};

// Puts `value` at the dotted `rest` of `node`, making the groups on the way.
void place(json& node, const std::string& rest, json value) {
  const std::size_t dot = rest.find('.');
  if (dot == std::string::npos) {
    node[rest] = std::move(value);
    return;
  }
  place(node[rest.substr(0, dot)], rest.substr(dot + 1), std::move(value));
}

}  // namespace

json defaultEntry(const std::string& path) {
  const std::string prefix = schemaPath(path) + ".*.";
  json entry = json::object();
  for (const auto& e : scene::sceneSchema()) {
    if (e.path.rfind(prefix, 0) != 0) continue;
    const std::string rest = e.path.substr(prefix.size());
    if (rest.find('*') != std::string::npos) continue;  // a nested list's entries: it starts empty
    place(entry, rest, parseDefault(e.default_text));
  }
  return entry;
}

bool editScene(json& scene, const PanelOptions& options) {
  Panel panel(options);
  return panel.edit(scene, "", "scene");
}

}  // namespace shanshui::view
