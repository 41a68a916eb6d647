// shanshui-view: a GLFW window on a mesh; drag to orbit, scroll to zoom, S for a screenshot.
#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>

#include "shanshui/core/parse.h"
#include "shanshui/image/image_io.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/mesh_preview.h"
#include "tool_main.h"

namespace {

using namespace shanshui;

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
    std::copy_n(&rows[static_cast<std::size_t>(height - 1 - y) * row], row, &img.pixels[static_cast<std::size_t>(y) * row]);
  }
  return img;
}

struct ViewState {
  render::PreviewOptions options;
  bool dragging = false;
  double lastX = 0, lastY = 0;
  bool screenshotRequested = false;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Interactive viewer: drag to orbit, scroll to zoom, S saves a screenshot, Esc quits.",
               "shanshui-view"};
  app.footer("Example:\n  shanshui-view out/st_helens.obj\n"
             "  xvfb-run -a shanshui-view mesh.obj --frames 3 --screenshot shot.png   # scripted");
  std::string input, size = "1024x768", screenshot = "shanshui-screenshot.png";
  int frames = 0;
  ViewState state;
  app.add_option("input", input, "mesh (.obj, .ply, .off)")->required();
  app.add_option("--size", size, "window size WxH")->default_val("1024x768");
  app.add_option("--azimuth", state.options.azimuth_deg, "initial camera azimuth, degrees")->default_val(-60.0);
  app.add_option("--elevation", state.options.elevation_deg, "initial camera elevation, degrees")->default_val(25.0);
  app.add_option("--frames", frames, "quit after N frames (0: run until closed); with --screenshot, "
                                     "the last frame is saved")->default_val(0);
  app.add_option("--screenshot", screenshot, "file for screenshots (S key, or the last of --frames)");
  return tools::runTool(app, argc, argv, [&] {
    const Size2 s = parseSize(size, "--size");
    if (frames < 0) throw makeError("--frames: ", frames, " is negative");
    render::validate(state.options);
    mesh::RepairReport report;
    const mesh::Mesh m = mesh::repairMesh(mesh::readPolygonSoup(input), {}, &report, input);
    const auto context = render::GlContext::create(
        {.kind = render::ContextKind::Window, .width = s.width, .height = s.height,
         .title = "shanshui-view: " + input, .vsync = frames == 0});
    GLFWwindow* window = context->window();
    glfwSetWindowUserPointer(window, &state);
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      if (button == GLFW_MOUSE_BUTTON_LEFT) {
        st->dragging = action == GLFW_PRESS;
        glfwGetCursorPos(w, &st->lastX, &st->lastY);
      }
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      if (!st->dragging) return;
      st->options.azimuth_deg -= 0.3 * (x - st->lastX);
      st->options.elevation_deg = std::clamp(st->options.elevation_deg + 0.3 * (y - st->lastY), -85.0, 85.0);
      st->lastX = x;
      st->lastY = y;
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      st->options.zoom = std::clamp(st->options.zoom * std::pow(1.1, dy), 0.05, 100.0);
    });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
      auto* st = static_cast<ViewState*>(glfwGetWindowUserPointer(w));
      if (action != GLFW_PRESS) return;
      if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
      if (key == GLFW_KEY_S) st->screenshotRequested = true;
    });

    const render::MeshPreview preview(m);
    render::Framebuffer fb;
    for (int frame = 1; !glfwWindowShouldClose(window); ++frame) {
      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      if (width > 0 && height > 0) {
        if (fb.width() != width || fb.height() != height) fb = render::Framebuffer(width, height, {GL_RGBA8}, true);
        state.options.width = width;
        state.options.height = height;
        // The same offscreen pass as shanshui-render, then shown: one code path for both.
        preview.render(fb, state.options);
        glBlitNamedFramebuffer(fb.id(), 0, 0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        const bool last = frames > 0 && frame >= frames;
        if (state.screenshotRequested || (last && app.count("--screenshot"))) {
          image::saveImage(readBackBuffer(width, height), screenshot);
          std::printf("%s\n", screenshot.c_str());
          state.screenshotRequested = false;
        }
        glfwSwapBuffers(window);
        if (last) break;
      }
      if (frames > 0) glfwPollEvents();
      else glfwWaitEventsTimeout(0.05);
    }
  });
}
