#include "shanshui/render/gl_context.h"

#include <dlfcn.h>
#include <sys/resource.h>

#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <GLFW/glfw3.h>
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/render/gl_check.h"

namespace shanshui::render {

namespace {

std::mutex& debugMutex() {
  static std::mutex m;
  return m;
}
std::vector<std::string>& debugMessages() {
  static std::vector<std::string> messages;
  return messages;
}

void GLAPIENTRY debugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                             const void*) {
  if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
    std::fprintf(stderr, "GL debug: %s\n", message);
    const std::lock_guard<std::mutex> lock(debugMutex());
    debugMessages().emplace_back(message);
  }
}

void enableDebugOutput() {
  if (epoxy_gl_version() >= 43 || epoxy_has_gl_extension("GL_KHR_debug")) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugMessage, nullptr);
  }
}

void requireVersion(const char* platform) {
  if (epoxy_gl_version() < 45) {
    throw makeError(platform, ": OpenGL ", epoxy_gl_version() / 10, ".", epoxy_gl_version() % 10,
                    " context; shanshui needs 4.5 core");
  }
}

// libepoxy aborts the process when it cannot load the GL libraries at the first call: check
// they load first, so a missing driver or a tight memory limit is one line, not SIGABRT.
void requireGlLibraries(bool egl) {
  static std::once_flag once;
  static std::string missing;
  std::call_once(once, [egl] {
    auto loads = [](const char* name) {
      void* h = ::dlopen(name, RTLD_LAZY | RTLD_LOCAL);
      if (h == nullptr) return false;
      ::dlclose(h);
      return true;
    };
    if (egl && !loads("libEGL.so.1")) {
      missing = "libEGL.so.1";
    } else if (!loads("libOpenGL.so.0") && !loads("libGL.so.1")) {
      missing = "libGL.so.1 (or libOpenGL.so.0)";
    }
  });
  if (!missing.empty()) {
    throw makeError("OpenGL: cannot load ", missing, addressSpaceLimitNote(),
                    "; install the GL driver (Mesa's libegl1 and libgl1 on Debian)");
  }
}

// ---- headless: EGL without a window system ------------------------------------------

class EglContext final : public GlContext {
 public:
  explicit EglContext(const ContextOptions& options) {
    requireGlLibraries(true);
    guardCrashesUnderMemoryLimit("the GL driver");
    display_ = openDisplay();
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor)) {
      throw makeError("EGL: eglInitialize failed (error 0x", std::hex, eglGetError(), ")", std::dec,
                      addressSpaceLimitNote());
    }
    if (!eglBindAPI(EGL_OPENGL_API)) throw makeError("EGL: desktop OpenGL is not available");
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    eglChooseConfig(display_, configAttribs, &config, 1, &count);
    if (count == 0) {
      if (!epoxy_has_egl_extension(display_, "EGL_KHR_no_config_context")) {
        throw makeError("EGL: no config supports desktop OpenGL");
      }
      config = EGL_NO_CONFIG_KHR;
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     options.debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT) {
      throw makeError("EGL: cannot create an OpenGL 4.5 core context (error 0x", std::hex, eglGetError(), ")");
    }
    makeCurrent();
    requireVersion("EGL");
    if (options.debug) enableDebugOutput();
  }

  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY && !memoryRanOut()) {  // a driver out of memory may hang: leave it
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      eglTerminate(display_);
    }
  }

  ContextKind kind() const override { return ContextKind::Headless; }

  void makeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw makeError("EGL: cannot make the context current without a surface (error 0x", std::hex, eglGetError(), ")");
    }
  }

 private:
  // Mesa's surfaceless platform on CPUs and most Linux GPUs; the EGL device platform for
  // NVIDIA's driver; the default display as a last resort.
  static EGLDisplay openDisplay() {
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
      EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (d != EGL_NO_DISPLAY) return d;
    }
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") &&
        epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) {
      EGLDeviceEXT devices[8];
      EGLint n = 0;
      if (eglQueryDevicesEXT(8, devices, &n) && n > 0) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
        if (d != EGL_NO_DISPLAY) return d;
      }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d == EGL_NO_DISPLAY) throw makeError("EGL: no display (is Mesa's libEGL installed?)");
    return d;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

// ---- window: GLFW -------------------------------------------------------------------

std::string g_glfwError;

class GlfwContext final : public GlContext {
 public:
  explicit GlfwContext(const ContextOptions& options) {
    glfwSetErrorCallback([](int, const char* message) { g_glfwError = message; });
    requireGlLibraries(false);
    guardCrashesUnderMemoryLimit("the GL driver");
    if (!glfwInit()) {
      throw makeError("GLFW: cannot initialise (", g_glfwError, "); is DISPLAY set? try xvfb-run");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (!window_) {
      glfwTerminate();
      throw makeError("GLFW: cannot open a window with an OpenGL 4.5 core context (", g_glfwError, ")");
    }
    makeCurrent();
    glfwSwapInterval(options.vsync ? 1 : 0);
    requireVersion("GLFW");
    if (options.debug) enableDebugOutput();
  }

  ~GlfwContext() override {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
  }

  ContextKind kind() const override { return ContextKind::Window; }
  void makeCurrent() override { glfwMakeContextCurrent(window_); }
  GLFWwindow* window() const override { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

const char* glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    default:
      return "unknown GL error";
  }
}

}  // namespace

void checkGlError(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    while (glGetError() != GL_NO_ERROR) {
    }
    throw makeError("OpenGL error after ", where, ": ", glErrorName(e), " (0x", std::hex, e, ")");
  }
}

void checkGlAllocation(const char* what) {
  GLenum e = glGetError();
  bool out_of_memory = false;
  for (; e != GL_NO_ERROR; e = glGetError()) out_of_memory = out_of_memory || e == GL_OUT_OF_MEMORY;
  if (out_of_memory) {
    noteMemoryRanOut();
    throw makeError("OpenGL: out of memory allocating ", what, addressSpaceLimitNote());
  }
}

std::unique_ptr<GlContext> GlContext::create(const ContextOptions& options) {
  if (options.kind == ContextKind::Window) return std::make_unique<GlfwContext>(options);
  return std::make_unique<EglContext>(options);
}

std::string GlContext::description() const {
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return std::string(kind() == ContextKind::Headless ? "EGL headless" : "GLFW window") + ", " + str(GL_VENDOR) + ", " +
         str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

std::vector<std::string> GlContext::takeDebugMessages() {
  const std::lock_guard<std::mutex> lock(debugMutex());
  return std::exchange(debugMessages(), {});
}

}  // namespace shanshui::render
