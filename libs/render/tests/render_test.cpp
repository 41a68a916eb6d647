#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "gl_test.h"
#include "shanshui/core/error.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/gpu_timer.h"
#include "shanshui/render/mesh_preview.h"
#include "shanshui/render/shader_library.h"
#include "shanshui/render/shader_program.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using Headless = test::HeadlessGl;

bool isPaper(const image::Image& img, int x, int y, const glm::vec3& paper) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(img.at(x, y, c) - paper[c]) > 1.5f / 255) return false;
  }
  return true;
}

TEST_F(Headless, ContextIsOpenGl45Core) {
  EXPECT_GE(epoxy_gl_version(), 45);
  EXPECT_NE(context_->description().find("EGL headless"), std::string::npos);
}

TEST_F(Headless, SphereCoversItsAnalyticDiscAndIsLitFromAbove) {
  for (double radius : {0.01, 1.0, 3000.0}) {
    SCOPED_TRACE(radius);
    const mesh::Mesh sphere = test::uvSphere(radius, 64, 128, glm::dvec3(5e5, 4e6, 100.0));
    PreviewOptions o;
    o.width = o.height = 256;
    o.elevation_deg = 25;
    const image::Image img = renderPreview(sphere, o);
    // The camera frames the bounding box's sphere (radius r*sqrt(3)); the sphere itself
    // then subtends asin(r/d) and covers a disc of known radius in pixels.
    const double pi = std::numbers::pi, halfFov = o.fov_y_deg * pi / 360;
    const double d = std::sqrt(3.0) * radius / std::sin(halfFov);
    const double rPixels = std::tan(std::asin(radius / d)) / std::tan(halfFov) * o.height / 2;
    std::size_t covered = 0;
    double top = 0, bottom = 0;
    std::size_t nTop = 0, nBottom = 0;
    for (int y = 0; y < img.height; ++y) {
      for (int x = 0; x < img.width; ++x) {
        if (isPaper(img, x, y, o.paper)) continue;
        ++covered;
        const double l = img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2);
        if (y < img.height / 2) {
          top += l;
          ++nTop;
        } else {
          bottom += l;
          ++nBottom;
        }
      }
    }
    EXPECT_NEAR(covered / (pi * rPixels * rPixels), 1.0, 0.03);
    ASSERT_GT(nTop, 0u);
    ASSERT_GT(nBottom, 0u);
    EXPECT_GT(top / nTop, bottom / nBottom + 0.1);  // the light is above: the top is lighter
    EXPECT_TRUE(isPaper(img, 0, 0, o.paper));
  }
}

TEST_F(Headless, FrontToBackOrdersDrawTheSameDepthAsTheFileOrder) {
  const mesh::Mesh m = test::uvSphere(1.0, 24, 48);
  const GpuMesh plain(m, glm::dvec3(0.0)), sorted(m, glm::dvec3(0.0), nullptr, true);
  const Program p({"lambert.vert", "lambert.frag"});
  const Framebuffer a(96, 96, {GL_RGBA8}, true), b(96, 96, {GL_RGBA8}, true);
  for (const glm::vec3 view : {glm::vec3(1, 0.2f, 0), glm::vec3(0, -1, 0.3f), glm::vec3(0.1f, 0, -1)}) {
    OrbitCamera cam;
    cam.distance = 4.0;
    cam.azimuth_deg = glm::degrees(std::atan2(-view.y, -view.x));
    cam.elevation_deg = glm::degrees(std::asin(-view.z / glm::length(view)));
    p.use();
    p.set("u_model", glm::mat4(1.0f));
    p.set("u_normal_matrix", glm::mat3(1.0f));
    p.set("u_view_projection", cam.projection(1.0) * cam.view());
    p.set("u_light_dir", glm::vec3(0, 0, 1));
    glEnable(GL_DEPTH_TEST);
    for (const Framebuffer* fb : {&a, &b}) {
      fb->bind();
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      if (fb == &a)
        plain.draw();
      else
        sorted.drawFrontToBack(view);
    }
    EXPECT_EQ(a.depth().download(1).pixels, b.depth().download(1).pixels);
    EXPECT_EQ(a.colour(0).download(3).pixels, b.colour(0).download(3).pixels);
  }
}

TEST_F(Headless, FloatTextureRoundTripsExactly) {
  image::Image img(13, 7, 4);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = static_cast<float>(i) * 0.37f - 5.0f;
  const Texture2D t = Texture2D::fromImage(img, GL_RGBA32F);
  const image::Image back = t.download(4);
  EXPECT_EQ(back.pixels, img.pixels);  // including row order
}

TEST_F(Headless, WorkBetweenPassesCountsInTheNextPassUnlessMarkedAsAGap) {
  // Oracle: a 60 ms pause between two passes that draw nothing. Back to back, the second
  // pass starts at the first's end and so takes the pause; after gap() it starts afresh.
  auto second = [](bool gap) {
    GpuTimer timer;
    timer.begin("first");
    timer.end();
    glFlush();
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
    if (gap) timer.gap();
    timer.begin("second");
    timer.end();
    const std::vector<PassTime> passes = timer.collect();
    EXPECT_EQ(passes.size(), 2u);
    return passes.back().gpu_ms;
  };
  EXPECT_GE(second(false), 50.0);
  EXPECT_LT(second(true), 30.0);
}

// Late reading: frames closed without waiting come back in order, each with its own
// passes; a 40 ms pause inside the second frame's pass is that frame's, not another's.
TEST_F(Headless, FramesTimedLateComeBackInOrderWithTheirOwnPasses) {
  GpuTimer timer;
  for (int frame = 0; frame < 3; ++frame) {
    timer.begin("a" + std::to_string(frame));
    timer.end();
    glFlush();
    timer.begin("b" + std::to_string(frame));
    if (frame == 1) {
      glFlush();
      std::this_thread::sleep_for(std::chrono::milliseconds(40));
    }
    timer.end();
    timer.endFrame();
  }
  EXPECT_EQ(timer.framesLate(), 3u);
  std::vector<std::vector<PassTime>> frames;
  for (int i = 0; i < 1000 && frames.size() < 3; ++i) {
    glFlush();
    // Without waiting: a frame the GPU has not reached yet is left for later.
    if (auto t = timer.collectLate(i > 500)) frames.push_back(std::move(*t));
  }
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(timer.framesLate(), 0u);
  EXPECT_FALSE(timer.collectLate(true).has_value());
  for (int frame = 0; frame < 3; ++frame) {
    ASSERT_EQ(frames[frame].size(), 2u);
    EXPECT_EQ(frames[frame][0].name, "a" + std::to_string(frame));
    EXPECT_EQ(frames[frame][1].name, "b" + std::to_string(frame));
    for (const PassTime& p : frames[frame]) EXPECT_GE(p.gpu_ms, 0.0) << p.name;
  }
  EXPECT_GE(frames[1][1].gpu_ms, 30.0);
  EXPECT_LT(frames[0][1].gpu_ms, 30.0);
  EXPECT_LT(frames[2][1].gpu_ms, 30.0);
  // Reading at once still works between late frames, and its queries are reused.
  timer.begin("now");
  timer.end();
  const std::vector<PassTime> now = timer.collect();
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].name, "now");
}

// A program keeps the locations it was asked for: the same as the driver's for every
// active uniform (array elements and unknown names too), asked in any order, twice.
TEST_F(Headless, KeptUniformLocationsAreTheDriversOwn) {
  Program p({"fullscreen.vert", "ink.frag"}, {"LINES", "SHADING", "WRINKLE", "CANVAS", "BORDER", "MIST", "OBJECTS=2"});
  GLint count = 0;
  glGetProgramInterfaceiv(p.id(), GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
  std::vector<std::string> names;
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    glGetProgramResourceName(p.id(), GL_UNIFORM, static_cast<GLuint>(i), sizeof name, nullptr, name);
    if (std::string(name).find('.') == std::string::npos) names.push_back(name);  // not a block member
  }
  ASSERT_GE(names.size(), 5u);
  names.insert(names.end(), {"u_not_there", "u_fade_range[0]", "u_eye"});
  for (int round = 0; round < 2; ++round) {
    for (auto it = names.rbegin(); it != names.rend(); ++it) {
      EXPECT_EQ(p.location(it->c_str()), glGetUniformLocation(p.id(), it->c_str())) << *it;
    }
  }
  // A moved program keeps them, and stays right.
  Program q = std::move(p);
  for (const std::string& n : names) EXPECT_EQ(q.location(n.c_str()), glGetUniformLocation(q.id(), n.c_str())) << n;
}

// A value the program already holds is not sent again: the count of values sent grows by
// one per change (none for a name that is not active), the driver holds the last value set,
// and a moved program keeps what it holds.
TEST_F(Headless, AUniformIsSentOnlyWhenItsValueChanges) {
  Program p({"fullscreen.vert", "ink.frag"}, {"LINES", "SHADING", "CANVAS", "ELEMENTS", "SINGLE_OBJECT"});
  ASSERT_GE(p.location("u_canvas_contrast"), 0);
  ASSERT_GE(p.location("u_element_colour"), 0);
  auto held = [](const Program& q, const char* name, int n) {
    float v[3] = {0.0f, 0.0f, 0.0f};
    glGetUniformfv(q.id(), q.location(name), v);
    return std::vector<float>(v, v + n);
  };
  const std::uint64_t start = uniformsSet();
  p.set("u_canvas_contrast", 0.25f);
  p.set("u_canvas_contrast", 0.25f);
  EXPECT_EQ(uniformsSet() - start, 1u);
  p.set("u_canvas_contrast", 0.5f);
  p.set("u_element_colour", glm::vec3(0.1f, 0.2f, 0.3f));
  p.set("u_element_colour", glm::vec3(0.1f, 0.2f, 0.3f));
  p.set("u_not_there", 1.0f);
  EXPECT_EQ(uniformsSet() - start, 3u);
  EXPECT_EQ(held(p, "u_canvas_contrast", 1), std::vector<float>{0.5f});
  EXPECT_EQ(held(p, "u_element_colour", 3), (std::vector<float>{0.1f, 0.2f, 0.3f}));
  const Program q = std::move(p);
  q.set("u_canvas_contrast", 0.5f);
  EXPECT_EQ(uniformsSet() - start, 3u);
  q.set("u_element_colour", glm::vec3(0.1f, 0.2f, 0.4f));
  EXPECT_EQ(uniformsSet() - start, 4u);
  EXPECT_EQ(held(q, "u_element_colour", 3), (std::vector<float>{0.1f, 0.2f, 0.4f}));
}

TEST_F(Headless, DriverErrorsAreMappedToFileAndLine) {
  // Preprocess a real shader, then break it at a known line of a known file.
  PreprocessedShader pre = preprocessShader("mesh_preview.frag", {"SOME_VARIANT", "LEVEL=3"});
  EXPECT_NE(pre.text.find("#define SOME_VARIANT\n"), std::string::npos);
  EXPECT_NE(pre.text.find("#define LEVEL 3\n"), std::string::npos);
  pre.text += "#line 42 0\nthis is not glsl;\n";
  const GLuint s = glCreateShader(GL_FRAGMENT_SHADER);
  const char* src = pre.text.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 1;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  char log[4096] = {};
  glGetShaderInfoLog(s, sizeof log, nullptr, log);
  glDeleteShader(s);
  ASSERT_FALSE(ok);
  // The driver also reports the broken shader on the debug output: expected here.
  for (const std::string& m : GlContext::takeDebugMessages()) EXPECT_NE(m.find("error"), std::string::npos) << m;
  const std::string mapped = mapShaderLog(log, pre.files);
  EXPECT_NE(mapped.find("mesh_preview.frag:42"), std::string::npos) << mapped << " from " << log;
  // The variant defines do not shift line numbers of the real code either.
  EXPECT_NE(mapShaderLog("0:7(3): error: x", pre.files).find("mesh_preview.frag:7:3: error: x"), std::string::npos);
  EXPECT_NE(mapShaderLog("0(7) : error C0000: x", pre.files).find("mesh_preview.frag:7: error C0000: x"),
            std::string::npos);
}

TEST_F(Headless, EveryEmbeddedShaderProgramLinks) {
  EXPECT_NO_THROW(Program({"mesh_preview.vert", "mesh_preview.frag"}));
  EXPECT_THROW(shaderSource("no_such_shader.frag"), Error);
  EXPECT_GE(shaderNames().size(), 2u);
}

TEST_F(Headless, BadPreviewOptionsAreRefused) {
  const mesh::Mesh sphere = test::uvSphere(1.0, 8, 16);
  PreviewOptions o;
  o.width = 0;
  EXPECT_THROW(renderPreview(sphere, o), Error);
  o = {};
  o.elevation_deg = 90;
  EXPECT_THROW(renderPreview(sphere, o), Error);
  EXPECT_THROW(renderPreview(mesh::Mesh{}, {}), Error);
}

}  // namespace
}  // namespace shanshui::render

namespace shanshui::render {
namespace {

// The GL tests' debug output catches a real error: an invalid enum reaches the list.
TEST_F(Headless, DebugOutputReportsGlErrors) {
  GlContext::takeDebugMessages();
  glBindTexture(GL_TEXTURE_2D + 12345, 0);  // GL_INVALID_ENUM
  const std::vector<std::string> messages = GlContext::takeDebugMessages();
  EXPECT_FALSE(messages.empty());
  while (glGetError() != GL_NO_ERROR) {
  }
}

}  // namespace
}  // namespace shanshui::render
