// shanshui-view: a GLFW window on a scene, drawn by the same InkRenderer as shanshui-render,
// with a Dear ImGui panel over every scene parameter, per-pass timings and shader reload.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include "scene_panel.h"
#include "shanshui/core/parse.h"
#include "shanshui/image/image_io.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/render/shader_library.h"
#include "shanshui/scene/scene.h"
#include "tool_main.h"

namespace {

using namespace shanshui;
using nlohmann::json;

// Reads the window's back buffer (what the next swap will show), row 0 at the top.
image::Image readBackBuffer(int width, int height) {
  image::Image img(width, height, 3);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<float> rows(img.pixels.size());
  glReadPixels(0, 0, width, height, GL_RGB, GL_FLOAT, rows.data());
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::copy_n(&rows[static_cast<std::size_t>(height - 1 - y) * row], row,
                &img.pixels[static_cast<std::size_t>(y) * row]);
  }
  return img;
}

struct ViewState {
  render::OrbitCamera camera;
  bool dragging = false, panning = false;
  double last_x = 0, last_y = 0;
  bool screenshot = false, reload = false;
};

std::filesystem::file_time_type newestShader(const std::filesystem::path& dir) {
  std::filesystem::file_time_type newest{};
  std::error_code ec;
  // Every folder below it too: shaders/ has a folder per pass.
  for (std::filesystem::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    newest = std::max(newest, it->last_write_time(ec));
  return newest;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Interactive ink-wash viewer. Left drag orbits, right drag pans, scroll zooms; S saves a "
      "screenshot, R reloads shaders, Esc quits. The panel edits every scene parameter live.",
      "shanshui-view"};
  app.footer(
      "Examples:\n  shanshui-view samples/scenes/default.json\n"
      "  shanshui-view samples/scenes/default.json --shaders shaders   # hot reload while editing GLSL\n"
      "  xvfb-run -a shanshui-view scene.json --frames 3 --screenshot shot.png   # scripted");
  std::string input, size = "1024x768", screenshot = "shanshui-screenshot.png", shader_dir, save_path;
  std::vector<std::string> sets;
  int frames = 0;
  double orbit = 0.0;
  bool no_ui = false, with_ui = false;
  app.add_option("scene", input, "scene (.json), or a mesh or DEM to view with default parameters")->required();
  app.add_option("--size", size, "window size WxH")->default_val("1024x768");
  app.add_option("--set", sets, "override a scene key, dotted path = JSON value (repeatable)");
  app.add_option("--frames", frames,
                 "quit after N frames (0: run until closed); with --screenshot, "
                 "the last frame is saved")
      ->default_val(0);
  app.add_option("--orbit", orbit, "scripted camera: degrees turned per frame around +Z")->default_val(0.0);
  app.add_option("--screenshot", screenshot, "file for screenshots (S key, or the last of --frames)");
  app.add_option("--shaders", shader_dir, "read shaders from this directory and reload them when they change");
  app.add_option("--save-to", save_path, "where the panel's Save writes the scene (default: the input scene)");
  app.add_flag("--no-ui", no_ui, "hide the panel");
  app.add_flag("--screenshot-ui", with_ui, "screenshots include the panel");
  return tools::runTool(app, argc, argv, [&] {
    const Size2 s = parseSize(size, "--size");
    if (frames < 0) throw makeError("--frames: ", frames, " is negative");
    if (!std::isfinite(orbit)) throw makeError("--orbit: must be finite");
    if (!shader_dir.empty()) {
      if (!std::filesystem::is_directory(shader_dir)) throw makeError("--shaders: ", shader_dir, ": not a directory");
      render::setShaderDirectory(shader_dir);
    }
    std::vector<std::string> notes;
    scene::AssetCache cache;  // takes the lone input's file, read for its proportions
    scene::Scene sc = scene::loadSceneInput(input, sets, &notes, &cache);
    for (const std::string& n : notes)
      std::fprintf(stderr, "shanshui-view: note: %s: %s; --set changes it\n", input.c_str(), n.c_str());
    if (save_path.empty()) {
      save_path = std::filesystem::path(input).extension() == ".json"
                      ? input
                      : std::filesystem::path(input).replace_extension(".scene.json").string();
    }
    auto objects = cache.getAll(sc);
    const auto context = render::GlContext::create({.kind = render::ContextKind::Window,
                                                    .width = s.width,
                                                    .height = s.height,
                                                    .title = "shanshui-view: " + input,
                                                    .vsync = frames == 0});
    GLFWwindow* window = context->window();
    auto renderer = std::make_unique<render::InkRenderer>(sc, objects);
    // Pass times are read when the GPU has reached them, a frame or two later, so the
    // viewer never waits for the GPU inside a frame.
    renderer->setLateTiming(true);

    ViewState state;
    auto resetCamera = [&](int width, int height) {
      state.camera = renderer->camera(render::frameKey(sc, 0, 1, 0.0), static_cast<double>(width) / height);
    };
    resetCamera(s.width, s.height);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains to the callbacks below
    ImGui_ImplOpenGL3_Init("#version 450");

    glfwSetWindowUserPointer(window, &state);
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
      ImGui_ImplGlfw_MouseButtonCallback(w, button, action, mods);
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      if (ImGui::GetIO().WantCaptureMouse && action == GLFW_PRESS) return;
      if (button == GLFW_MOUSE_BUTTON_LEFT) st->dragging = action == GLFW_PRESS;
      if (button == GLFW_MOUSE_BUTTON_RIGHT) st->panning = action == GLFW_PRESS;
      glfwGetCursorPos(w, &st->last_x, &st->last_y);
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      const double dx = x - st->last_x, dy = y - st->last_y;
      st->last_x = x;
      st->last_y = y;
      render::OrbitCamera& c = st->camera;
      if (st->dragging) {
        c.azimuth_deg -= 0.3 * dx;
        c.elevation_deg = std::clamp(c.elevation_deg + 0.3 * dy, -85.0, 85.0);
      } else if (st->panning) {
        const glm::dvec3 forward = glm::normalize(c.target - c.eye());
        const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
        const glm::dvec3 up = glm::cross(right, forward);
        const double scale = c.distance * 0.0015;
        c.target += (-dx * right + dy * up) * scale;
      }
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double dx, double dy) {
      ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
      if (ImGui::GetIO().WantCaptureMouse) return;
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      const double f = std::pow(1.1, -dy);
      st->camera.distance *= f;
      st->camera.near_plane *= f;  // keeps the depth range proportionate
      st->camera.far_plane = std::max(st->camera.far_plane, st->camera.distance * 2);
    });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int code, int action, int mods) {
      ImGui_ImplGlfw_KeyCallback(w, key, code, action, mods);
      if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
      if (key == GLFW_KEY_S) st->screenshot = true;
      if (key == GLFW_KEY_R) st->reload = true;
    });

    json edited = scene::toJson(sc);
    std::string scene_error, status;
    render::FrameStats stats;
    std::vector<render::PassTime> last_passes;  //!< the GPU times of the last frame it finished
    auto shader_stamp = shader_dir.empty() ? std::filesystem::file_time_type{} : newestShader(shader_dir);
    double last_poll = glfwGetTime();
    // Frame rate: smoothed for the panel; for a scripted run, over every frame after the
    // first (which compiles shaders and uploads meshes), printed at the end.
    double fps = 0.0, last_swap = 0.0, first_swap = 0.0;
    // Tree and dot marks the frame had no room for (render::InkRenderer::marksDropped): read
    // back every 30th rendered frame, since reading waits for the GPU.
    std::size_t dropped = 0;
    int rendered = 0;
    for (int frame = 1; !glfwWindowShouldClose(window); ++frame) {
      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      if (!shader_dir.empty() && glfwGetTime() - last_poll > 0.5) {
        last_poll = glfwGetTime();
        const auto stamp = newestShader(shader_dir);
        if (stamp != shader_stamp) state.reload = true, shader_stamp = stamp;
      }
      if (state.reload) {
        state.reload = false;
        try {
          renderer->reloadShaders();
          status = "shaders reloaded";
        } catch (const std::exception& e) {
          status = std::string("shader error (old shaders kept): ") + e.what();
        }
      }
      if (width > 0 && height > 0) {
        if (orbit != 0.0) {
          // The scene's camera turned, framed again from each azimuth as shanshui-render
          // --orbit frames it (fill framing and presets depend on the angle).
          scene::CameraKey key = render::frameKey(sc, 0, 1, 0.0);
          key.azimuth_deg += orbit * frame;
          state.camera = renderer->camera(key, static_cast<double>(width) / height);
        }
        // Spinning objects run on the clock (scripted runs: 1/24 s per frame).
        const double time = frames > 0 ? frame / 24.0 : glfwGetTime();
        const render::Framebuffer& fb = renderer->render(state.camera, width, height, &stats, true, time);
        if (!stats.cached && rendered++ % 30 == 0) dropped = renderer->marksDropped();
        while (std::optional<std::vector<render::PassTime>> t = renderer->lateTimes(false)) last_passes = std::move(*t);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitNamedFramebuffer(fb.id(), 0, 0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        const bool last = frames > 0 && frame >= frames;
        const bool take = state.screenshot || (last && app.count("--screenshot"));
        auto saveScreenshot = [&] {
          image::saveImage(readBackBuffer(width, height), screenshot);
          std::printf("%s\n", screenshot.c_str());
          status = "saved " + screenshot;
          state.screenshot = false;
        };
        if (take && !with_ui) saveScreenshot();  // the picture alone, as shanshui-render writes it
        if (!no_ui) {
          ImGui_ImplOpenGL3_NewFrame();
          ImGui_ImplGlfw_NewFrame();
          ImGui::NewFrame();
          ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
          ImGui::SetNextWindowSize(ImVec2(380, static_cast<float>(height) - 16), ImGuiCond_FirstUseEver);
          ImGui::Begin("shanshui");
          ImGui::Text("%zu triangles, %dx%d", renderer->triangleCount(), width, height);
          ImGui::Text("%s, %.1f fps", stats.cached ? "frame: cached (nothing re-rendered)" : "frame: rendered", fps);
          double total = 0;
          for (const auto& p : last_passes) {
            ImGui::Text("  %-10s %7.2f ms", p.name.c_str(), p.gpu_ms);
            total += p.gpu_ms;
          }
          ImGui::Text("  %-10s %7.2f ms (GPU)", "total", total);
          if (ImGui::Button("Reset camera")) resetCamera(width, height);
          ImGui::SameLine();
          if (ImGui::Button("Save scene")) {
            try {
              scene::saveScene(sc, save_path);
              status = "saved " + save_path;
            } catch (const std::exception& e) {
              status = e.what();
            }
          }
          ImGui::SameLine();
          if (ImGui::Button("Reload shaders")) state.reload = true;
          if (!status.empty()) ImGui::TextWrapped("%s", status.c_str());
          if (!scene_error.empty()) ImGui::TextColored(ImVec4(1, 0.3f, 0.2f, 1), "%s", scene_error.c_str());
          if (dropped > 0) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.3f, 0.2f, 1));
            ImGui::TextWrapped(
                "%zu tree and dot marks had no room in the frame and are left out: lower trees.density or "
                "dots.density",
                dropped);
            ImGui::PopStyleColor();
          }
          ImGui::Separator();
          if (view::editScene(edited)) {
            try {
              scene::Scene next = scene::parseScene(edited, "panel", sc.base_dir);
              const bool camera_changed = scene::toJson(next)["camera"] != scene::toJson(sc)["camera"];
              if (render::InkRenderer::structureKey(next) == render::InkRenderer::structureKey(sc)) {
                renderer->setScene(next);
              } else {
                auto loaded = cache.getAll(next);
                renderer = std::make_unique<render::InkRenderer>(next, loaded);
                renderer->setLateTiming(true);
              }
              sc = std::move(next);
              if (camera_changed) resetCamera(width, height);
              scene_error.clear();
            } catch (const std::exception& e) {
              scene_error = e.what();  // the last good scene stays on screen
            }
          }
          ImGui::End();
          ImGui::Render();
          ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        }
        if (take && with_ui) saveScreenshot();
        glfwSwapBuffers(window);
        const double now = glfwGetTime();
        if (last_swap > 0.0 && now > last_swap)
          fps = fps > 0.0 ? 0.9 * fps + 0.1 / (now - last_swap) : 1.0 / (now - last_swap);
        last_swap = now;
        if (frame == 1) first_swap = now;
        if (last) {
          if (frame > 1 && now > first_swap) {
            std::fprintf(stderr, "shanshui-view: %d frames at %dx%d in %.2f s after the first: %.1f fps\n", frame - 1,
                         width, height, now - first_swap, (frame - 1) / (now - first_swap));
          }
          break;
        }
      }
      if (frames > 0 || sc.hasAnimation())
        glfwPollEvents();
      else
        glfwWaitEventsTimeout(0.05);  // nothing moves: wake for input only
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  });
}
