#include "shanshui/render/pixel_stage.h"

#include <cstdlib>

#include "shanshui/core/error.h"

namespace shanshui::render {

bool pixelPassesAsCompute() {
  if (const char* choice = std::getenv("SHANSHUI_PIXEL_PASSES")) {
    const std::string c = choice;
    if (c == "compute") return true;
    if (c == "fragment") return false;
    if (!c.empty()) {
      throw makeError("SHANSHUI_PIXEL_PASSES is '", c,
                      "'; expected 'compute', 'fragment' or unset (chosen by the GPU)");
    }
  }
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string r = renderer ? renderer : "";
  return r.find("llvmpipe") == std::string::npos && r.find("softpipe") == std::string::npos;
}

bool strokesGathered() {
  const char* choice = std::getenv("SHANSHUI_STROKES");
  const std::string c = choice ? choice : "";
  if (c.empty() || c == "stamp") return false;
  if (c == "gather") return true;
  throw makeError("SHANSHUI_STROKES is '", c, "'; expected 'gather', 'stamp' or unset (stamp)");
}

void dispatchPixels(const Program& p, const glm::ivec4& rect) {
  const int width = rect.z - rect.x, height = rect.w - rect.y;
  if (width <= 0 || height <= 0) return;
  p.set("u_pixel_rect", rect);
  glDispatchCompute(static_cast<GLuint>((width + 7) / 8), static_cast<GLuint>((height + 7) / 8), 1);
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

Program pixelProgram(const std::string& frag, const std::vector<std::string>& defines, bool compute) {
  return compute ? Program::pixelCompute(frag, defines) : Program({"fullscreen.vert", frag}, defines);
}

void shadePixels(const Program& p, bool compute, const Framebuffer& target, const std::vector<GLenum>& formats,
                 const glm::ivec4& rect) {
  if (!compute) {
    target.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return;
  }
  for (std::size_t i = 0; i < formats.size(); ++i) {
    glBindImageTexture(static_cast<GLuint>(7 - i), target.colour(static_cast<int>(i)).id(), 0, GL_FALSE, 0,
                       GL_WRITE_ONLY, formats[i]);
  }
  dispatchPixels(p, rect);
}

}  // namespace shanshui::render
