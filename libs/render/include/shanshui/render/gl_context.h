// An OpenGL 4.5 core context, headless (EGL) or in a GLFW window, chosen at run time.
#pragma once

#include <memory>
#include <string>
#include <vector>

struct GLFWwindow;

namespace shanshui::render {

enum class ContextKind {
  Headless,  //!< EGL without a surface: Mesa's surfaceless platform, else an EGL device (GPU)
  Window,    //!< a GLFW window (needs a display, e.g. under xvfb-run)
};

struct ContextOptions {
  ContextKind kind = ContextKind::Headless;
  int width = 1024;  //!< window size; headless contexts render into framebuffers of any size
  int height = 768;
  std::string title = "shanshui";
  bool visible = true;  //!< window only
  bool vsync = true;    //!< window only
  bool debug = false;   //!< GL debug context: errors and high-severity messages are printed and kept
};

//! Owns the context; it is current on the creating thread after create().
class GlContext {
 public:
  virtual ~GlContext() = default;
  //! Throws Error with the platform's reason when no 4.5 core context can be made.
  static std::unique_ptr<GlContext> create(const ContextOptions& options);

  virtual ContextKind kind() const = 0;
  virtual void makeCurrent() = 0;
  //! Window only; null for headless contexts.
  virtual GLFWwindow* window() const { return nullptr; }
  //! One line naming the platform, vendor, renderer and version.
  std::string description() const;
  //! The GL errors and high-severity messages of debug contexts (KHR_debug) since the
  //! last call; the GL tests fail on any.
  static std::vector<std::string> takeDebugMessages();
};

}  // namespace shanshui::render
