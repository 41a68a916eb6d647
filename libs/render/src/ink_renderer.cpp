#include "shanshui/render/ink_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "shanshui/core/error.h"
#include "shanshui/core/random.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/ink_object_params.h"

namespace shanshui::render {

namespace {

bool wrinkled(const scene::Object& o) { return !o.wrinkle.texture.empty() && o.shading.enabled; }

// The wrinkle texture's minification filter. Nearest is the default: on llvmpipe bilinear
// filtering cost ~5 ms a frame at 1024² on the sample scene, and a texel of the right mip
// level is about a pixel (bench/ink_tradeoff.cpp measures both against trilinear).
GLenum minFilter(scene::TextureFilter f) {
  switch (f) {
    case scene::TextureFilter::Nearest: return GL_NEAREST_MIPMAP_NEAREST;
    case scene::TextureFilter::Bilinear: return GL_LINEAR_MIPMAP_NEAREST;
    case scene::TextureFilter::Trilinear: return GL_LINEAR_MIPMAP_LINEAR;
  }
  return GL_NEAREST_MIPMAP_NEAREST;
}

std::vector<std::string> gbufferDefines(const scene::Scene& s, const scene::Object& o) {
  std::vector<std::string> d;
  if (s.usesShading()) d.emplace_back("SURFACE");
  if (wrinkled(o)) d.emplace_back("WRINKLE");
  if (o.lines.enabled) {
    d.emplace_back(scene::perVertex(o.lines.curvature) ? "OBJECT_CURVATURE" : "SCREEN_CURVATURE");
  }
  return d;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

}  // namespace

OrbitCamera sceneCamera(const scene::Scene& s, const mesh::Bounds& world_bounds, double aspect,
                        const scene::CameraKey& key) {
  const scene::Camera& c = s.camera;
  OrbitCamera cam = frameBounds(world_bounds, key.azimuth_deg, key.elevation_deg, c.fov_y_deg, aspect, key.zoom);
  cam.target += world_bounds.centre();
  const double radius = std::max(0.5 * glm::length(world_bounds.size()), 1e-6);
  if (c.target || c.distance > 0) {
    if (c.target) cam.target = *c.target;
    if (c.distance > 0) cam.distance = c.distance / key.zoom;
    // The planes enclose the bounds seen from wherever the camera now is.
    const double to_centre = glm::length(cam.eye() - world_bounds.centre());
    cam.near_plane = std::max(to_centre - radius * 1.01, std::max(cam.distance, to_centre) * 1e-4);
    cam.far_plane = to_centre + radius * 1.01;
  }
  return cam;
}

scene::CameraKey frameKey(const scene::Scene& s, int index, int count, double orbit_deg) {
  const scene::Camera& c = s.camera;
  scene::CameraKey key{c.azimuth_deg, c.elevation_deg, c.zoom};
  if (count <= 1) return key;
  if (!c.path.empty()) {
    if (c.path.size() == 1) return c.path[0];
    const double x = static_cast<double>(index) / (count - 1) * static_cast<double>(c.path.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(x), c.path.size() - 2);
    const double t = x - static_cast<double>(i);
    const scene::CameraKey &a = c.path[i], &b = c.path[i + 1];
    return {a.azimuth_deg + t * (b.azimuth_deg - a.azimuth_deg), a.elevation_deg + t * (b.elevation_deg - a.elevation_deg),
            a.zoom * std::pow(b.zoom / a.zoom, t)};
  }
  key.azimuth_deg += orbit_deg * index / count;
  return key;
}

std::string InkRenderer::structureKey(const scene::Scene& s) {
  std::ostringstream k;
  k << s.objects.size() << "|" << s.usesLines() << s.usesShading() << s.usesWrinkles() << s.hasAnimation() << "|"
    << static_cast<int>(s.canvas.type) << static_cast<int>(s.canvas.pattern()) << s.diffusion.enabled();
  for (const scene::Object& o : s.objects) {
    k << "|" << s.resolve(o.mesh.empty() ? o.dem : o.mesh).string() << "," << o.z_scale << "," << o.max_vertices << ","
      << o.recentre << "," << joined(gbufferDefines(s, o));
    if (wrinkled(o)) k << "," << s.resolve(o.wrinkle.texture).string() << "," << static_cast<int>(o.wrinkle.uv);
  }
  return k.str();
}

InkRenderer::InkRenderer(const scene::Scene& s, const std::vector<scene::LoadedObject>& objects) : scene_(s) {
  SHANSHUI_CHECK_EQ(objects.size(), s.objects.size());
  lines_ = s.usesLines();
  shading_ = s.usesShading();
  wrinkles_ = s.usesWrinkles();
  if (objects.size() > 255) throw makeError("a scene holds at most 255 objects; this one has ", objects.size());
  const bool canvas = s.canvas.type != scene::CanvasType::None;
  passes_ = {"gbuffer"};
  if (canvas) passes_.emplace_back(s.canvas.type == scene::CanvasType::Static ? "canvas_static" : "canvas");
  passes_.emplace_back("ink");
  if (s.diffusion.enabled()) {
    passes_.emplace_back("diffusion");
    diffusion_.emplace();
  }

  for (std::size_t i = 0; i < objects.size(); ++i) {
    const scene::ObjectAsset& a = *objects[i].geometry;
    const scene::Object& o = s.objects[i];
    const std::vector<std::string> defines = gbufferDefines(s, o);
    GpuObject g;
    const bool per_vertex = o.lines.enabled && scene::perVertex(o.lines.curvature);
    g.mesh = GpuMesh(a.mesh, a.bounds.centre(), per_vertex ? &a.curvature : nullptr, true);
    g.model_bounds = a.bounds;
    g.model_feature_size = a.feature_size;
    if (canvas) g.max_triangle_area = maxTriangleArea(a.mesh);
    if (wrinkled(o)) {
      SHANSHUI_CHECK(objects[i].wrinkle != nullptr);
      g.wrinkle = Texture2D::tiledFromImage(*objects[i].wrinkle, GL_R8);
    }
    const auto it = std::find_if(gbuffer_programs_.begin(), gbuffer_programs_.end(),
                                 [&](const GbufferProgram& p) { return p.defines == defines; });
    g.program = static_cast<int>(it - gbuffer_programs_.begin());
    if (it == gbuffer_programs_.end()) gbuffer_programs_.push_back({defines, Program()});
    objects_.push_back(std::move(g));
  }
  glCreateVertexArrays(1, &empty_vao_);
  glCreateBuffers(1, &params_buffer_);
  buildPrograms();
  setScene(s);
  if (canvas) {
    canvas_.emplace(s.canvas, s.seed, world_bounds_);
    variants_[canvas_->passName()] = canvas_->variants();
  }
}

InkRenderer::~InkRenderer() {
  if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
  if (params_buffer_) glDeleteBuffers(1, &params_buffer_);
}

std::size_t InkRenderer::triangleCount() const {
  std::size_t n = 0;
  for (const GpuObject& o : objects_) n += o.mesh.triangleCount();
  return n;
}

const Framebuffer* InkRenderer::passTarget(const std::string& pass) const {
  if (pass == "gbuffer") return &gbuffer_;
  if (pass == "ink") return &final_;
  if (pass == "diffusion") return diffusion_ ? &diffused_ : nullptr;
  if (pass == "canvas") return canvas_ ? &canvas_->target() : nullptr;
  return nullptr;
}

void InkRenderer::buildPrograms() {
  // Build everything first so a failure leaves the old programs in place.
  std::vector<Program> gbuffer;
  std::map<std::string, std::vector<std::string>> variants;
  for (const GbufferProgram& p : gbuffer_programs_) {
    gbuffer.emplace_back(std::vector<std::string>{"ink_gbuffer.vert", "ink_gbuffer.frag"}, p.defines);
    variants["gbuffer"].push_back(joined(p.defines));
  }
  std::vector<std::string> d;
  if (lines_) d.emplace_back("LINES");
  if (shading_) d.emplace_back("SHADING");
  if (wrinkles_) d.emplace_back("WRINKLE");
  if (objects_.size() == 1) d.emplace_back("SINGLE_OBJECT");
  // The paper grain goes on last: here, or after the diffusion when there is one.
  if (scene_.canvas.type != scene::CanvasType::None && !scene_.diffusion.enabled()) d.emplace_back("CANVAS");
  if (debug_outputs_) d.emplace_back("DEBUG_OUTPUTS");
  Program ink({"fullscreen.vert", "ink.frag"}, d);
  variants["ink"].push_back(joined(d));

  for (std::size_t i = 0; i < gbuffer.size(); ++i) gbuffer_programs_[i].program = std::move(gbuffer[i]);
  ink_program_ = std::move(ink);
  variants_ = std::move(variants);
  last_key_.clear();
}

void InkRenderer::setDebugOutputs(bool on) {
  if (on == debug_outputs_) return;
  debug_outputs_ = on;
  buildPrograms();
  final_ = Framebuffer();  // targets are remade with or without the extra outputs
}

void InkRenderer::reloadShaders() {
  buildPrograms();
  if (canvas_) {
    canvas_->reloadShaders();
    variants_[canvas_->passName()] = canvas_->variants();
  }
}

void InkRenderer::setScene(const scene::Scene& s) {
  if (structureKey(s) != structureKey(scene_)) {
    throw makeError("InkRenderer::setScene: the scene's files, passes or variants changed; build a new renderer");
  }
  if (!noise_seed_ || *noise_seed_ != s.seed) seedNoise(s);
  scene_ = s;
  if (canvas_) canvas_->setParams(s.canvas, s.seed);
  world_bounds_ = {glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    GpuObject& g = objects_[i];
    const glm::dmat4 t = s.objects[i].transform.matrix();
    g.model = t * glm::translate(glm::dmat4(1.0), g.model_bounds.centre());
    const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(t))));
    g.centre = glm::dvec3(t * glm::dvec4(g.model_bounds.centre(), 1.0));
    g.radius = std::max(0.5 * glm::length(g.model_bounds.size()) * scale, 1e-12);
    g.feature_size = g.model_feature_size * scale;
    if (g.wrinkle) {
      const GLint filter = static_cast<GLint>(minFilter(s.objects[i].wrinkle.filter));
      glTextureParameteri(g.wrinkle->id(), GL_TEXTURE_MIN_FILTER, filter);
    }
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1) ? g.model_bounds.max.x : g.model_bounds.min.x,
                              (c & 2) ? g.model_bounds.max.y : g.model_bounds.min.y,
                              (c & 4) ? g.model_bounds.max.z : g.model_bounds.min.z);
      const glm::dvec3 w(t * glm::dvec4(corner, 1.0));
      world_bounds_.min = glm::min(world_bounds_.min, w);
      world_bounds_.max = glm::max(world_bounds_.max, w);
    }
  }
  last_key_.clear();
}

void InkRenderer::seedNoise(const scene::Scene& s) {
  // Value noise is smooth at texel scale: one texel of the right mip level is enough when
  // minified (a quarter of the bilinear fetches); magnified it is still filtered.
  if (shading_) noise_ = Texture2D::tiledFromImage(noise::erosionNoise(256, s.seed), GL_RG8, GL_NEAREST_MIPMAP_NEAREST);
  if (s.diffusion.enabled() && s.canvas.type == scene::CanvasType::None) {
    // Without a canvas the paper's absorbency is value noise in [0.5, 1].
    image::Image noise = noise::erosionNoise(256, s.seed ^ 0xAB50Bull);
    image::Image a(noise.width, noise.height, 1);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = 0.5f + 0.5f * noise.pixels[2 * i];
    absorbency_ = Texture2D::fromImage(a, GL_R8);
  }
  noise_seed_ = s.seed;
}

void InkRenderer::ensureTargets(int width, int height) {
  if (final_.width() == width && final_.height() == height) return;
  // Normal and curvature in 16-bit unsigned normalised channels (encoded in
  // shaders/ink_gbuffer.frag): llvmpipe converts to half floats in software, and an RGBA16F
  // target cost ~10 ms more a frame at 1024² (measured side by side).
  gbuffer_ = Framebuffer(width, height, {GL_RGBA16, GL_RGBA8}, true);
  if (scene_.hasAnimation()) static_gbuffer_ = Framebuffer(width, height, {GL_RGBA16, GL_RGBA8}, true);
  static_layer_key_.clear();
  std::vector<GLenum> out{GL_RGBA8};
  if (debug_outputs_) out.insert(out.end(), {GL_RG16F, GL_R16F});
  final_ = Framebuffer(width, height, out, false);
  if (diffusion_) diffused_ = Framebuffer(width, height, {GL_RGBA8}, false);
  last_key_.clear();
}

void InkRenderer::uploadObjectParams(const OrbitCamera& camera, int height) {
  std::vector<gpu::ObjectParams> params(objects_.size());
  const double pixels_per_unit_at_1 = 0.5 * height / std::tan(glm::radians(camera.fov_y_deg) * 0.5);
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const scene::Object& o = scene_.objects[i];
    const GpuObject& g = objects_[i];
    const scene::LineParams& l = o.lines;
    const scene::ShadingParams& sh = o.shading;
    // Projected area of the bounding sphere decides the small-object path.
    const double d = std::max(glm::length(camera.eye() - g.centre), 1e-12);
    const double r_px = g.radius / d * pixels_per_unit_at_1;
    const bool small = std::numbers::pi * r_px * r_px < l.small_object_px;
    gpu::ObjectParams& p = params[i];
    p.line_color = glm::vec3(l.line_color);
    p.curve_factor = static_cast<float>(l.curve_factor);
    p.bg_color = glm::vec3(l.bg_color);
    p.line_threshold = static_cast<float>(l.threshold);
    p.soft_width = static_cast<float>(l.soft_width);
    p.silhouette = static_cast<float>(l.silhouette);
    p.depth_edges = static_cast<float>(l.depth_edges);
    p.line_flags = (l.enabled ? gpu::kLinesOn : 0u) | (small ? gpu::kNormalOnly : 0u);
    p.tones = glm::vec4(sh.tones[0], sh.tones[1], sh.tones[2], sh.tones[3]);
    p.thresholds = glm::vec4(sh.thresholds[0], sh.thresholds[1], sh.thresholds[2], sh.thresholds[3]);
    p.tone5 = static_cast<float>(sh.tones[4]);
    p.sigma = static_cast<float>(sh.sigma);
    p.beta = static_cast<float>(sh.beta);
    p.erosion = static_cast<float>(sh.erosion);
    p.noise = static_cast<float>(sh.noise);
    p.inv_inner_tex_factor = static_cast<float>(1.0 / o.wrinkle.inner_tex_factor);
    p.shade_flags = (sh.enabled ? gpu::kShadingOn : 0u) | (sh.half_lambert ? gpu::kHalfLambert : 0u) |
                    (sh.line_value ? gpu::kLineValue : 0u) | (wrinkled(o) ? gpu::kWrinkled : 0u);
  }
  const std::size_t bytes = params.size() * sizeof(gpu::ObjectParams);
  if (bytes > params_capacity_) {
    glDeleteBuffers(1, &params_buffer_);
    glCreateBuffers(1, &params_buffer_);
    glNamedBufferStorage(params_buffer_, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    params_capacity_ = bytes;
  }
  glNamedBufferSubData(params_buffer_, 0, static_cast<GLsizeiptr>(bytes), params.data());
  // One object: a uniform block (see shaders/ink_objects.glsl); more: a storage buffer.
  if (objects_.size() == 1) glBindBufferBase(GL_UNIFORM_BUFFER, 0, params_buffer_);
  else glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, params_buffer_);
}

std::string InkRenderer::requestKey(const OrbitCamera& c, int width, int height) const {
  std::ostringstream k;
  k.precision(17);
  k << width << "x" << height << "|" << c.target.x << "," << c.target.y << "," << c.target.z << "," << c.distance << ","
    << c.azimuth_deg << "," << c.elevation_deg << "," << c.fov_y_deg << "," << c.near_plane << "," << c.far_plane << "|"
    << scene::parameterHash(scene_);
  return k.str();
}

void InkRenderer::drawObjects(const Framebuffer& target, bool clear, int which, const OrbitCamera& camera,
                              const glm::mat4& view_projection, double time) {
  target.bind();
  if (clear) {
    // Only depth: the ink pass reads the colour targets where something was drawn (depth
    // below 1), so clearing them would be wasted bandwidth.
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(target.id(), GL_DEPTH, 0, &far_depth);
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const scene::Object& o = scene_.objects[i];
    if ((which == kStaticObjects && o.animated()) || (which == kAnimatedObjects && !o.animated())) continue;
    const GpuObject& g = objects_[i];
    const glm::dmat4 model = modelAt(i, time);
    const Program& p = gbuffer_programs_[static_cast<std::size_t>(g.program)].program;
    p.use();
    p.set("u_model", glm::mat4(model));
    p.set("u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(glm::dmat3(model)))));
    p.set("u_view_projection", view_projection);
    p.set("u_object_id", static_cast<float>(i + 1) / 255.0f);
    if (o.lines.enabled && o.lines.curvature == scene::CurvatureSource::Screen) {
      p.set("u_feature_size", static_cast<float>(g.feature_size));
    }
    if (shading_) {
      glBindTextureUnit(0, noise_->id());
      p.set("u_noise", 0);
      const double model_radius = 0.5 * glm::length(g.model_bounds.size());
      const double tile = noise::kErosionCells * o.shading.noise_scale * model_radius;
      p.set("u_noise_frequency", static_cast<float>(1.0 / std::max(tile, 1e-30)));
    }
    if (g.wrinkle) {
      glBindTextureUnit(1, g.wrinkle->id());
      p.set("u_wrinkle", 1);
      p.set("u_repeat", static_cast<float>(o.wrinkle.repeat));
    }
    // Front to back, so hidden fragments fail the depth test before they are shaded.
    const glm::dvec3 forward = glm::inverse(glm::dmat3(model)) * (camera.target - camera.eye());
    g.mesh.drawFrontToBack(glm::vec3(forward));
  }
}

glm::dmat4 InkRenderer::modelAt(std::size_t i, double time) const {
  // A spinning object turns about the vertical axis through its centre (the origin of its
  // uploaded coordinates).
  const scene::Object& o = scene_.objects[i];
  const glm::dmat4& model = objects_[i].model;
  return o.animated() ? glm::rotate(model, glm::radians(o.spin_deg_per_s * time), glm::dvec3(0, 0, 1)) : model;
}

const Framebuffer& InkRenderer::render(const OrbitCamera& camera, int width, int height, FrameStats* stats,
                                       bool timing, double time) {
  const auto start = std::chrono::steady_clock::now();
  ensureTargets(width, height);
  const bool animated = scene_.hasAnimation();
  const std::string static_key = requestKey(camera, width, height);
  std::string key = static_key;
  if (animated) key += "|t=" + std::to_string(time);
  if (key == last_key_) {
    if (stats) *stats = FrameStats{true, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(), {}};
    return diffusion_ ? diffused_ : final_;
  }
  const double aspect = static_cast<double>(width) / height;
  const glm::mat4 view_projection = camera.projection(aspect) * camera.view();
  const glm::vec3 eye(camera.eye());
  uploadObjectParams(camera, height);

  // G-buffer: normal + curvature, surface detail + object id, depth. With animated
  // objects the static ones are drawn once into their own layer (again only when the
  // camera, size or parameters change) and copied under the animated ones each frame.
  if (!animated) {
    if (timing) timer_.begin("gbuffer");
    drawObjects(gbuffer_, true, kAllObjects, camera, view_projection, time);
    if (timing) timer_.end();
  } else {
    if (static_key != static_layer_key_) {
      if (timing) timer_.begin("gbuffer_static");
      drawObjects(static_gbuffer_, true, kStaticObjects, camera, view_projection, time);
      if (timing) timer_.end();
      static_layer_key_ = static_key;
    }
    if (timing) timer_.begin("gbuffer_animated");
    for (int i = 0; i < 2; ++i) {
      glCopyImageSubData(static_gbuffer_.colour(i).id(), GL_TEXTURE_2D, 0, 0, 0, 0, gbuffer_.colour(i).id(), GL_TEXTURE_2D,
                         0, 0, 0, 0, width, height, 1);
    }
    glCopyImageSubData(static_gbuffer_.depth().id(), GL_TEXTURE_2D, 0, 0, 0, 0, gbuffer_.depth().id(), GL_TEXTURE_2D, 0, 0,
                       0, 0, width, height, 1);
    drawObjects(gbuffer_, false, kAnimatedObjects, camera, view_projection, time);
    if (timing) timer_.end();
  }
  SHANSHUI_GL_CHECK("gbuffer pass");

  if (canvas_) {
    std::vector<CanvasPass::Item> items;
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      const GpuObject& g = objects_[i];
      items.push_back({&g.mesh, modelAt(i, time), g.max_triangle_area, 0.5 * glm::length(g.model_bounds.size())});
    }
    canvas_noise_ = &canvas_->run(items, gbuffer_.depth(), camera, width, height, timing ? &timer_ : nullptr);
  }

  // One image pass: lines, shading and composite.
  if (timing) timer_.begin("ink");
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(empty_vao_);
  glBindImageTexture(0, gbuffer_.colour(0).id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16);
  glBindImageTexture(1, gbuffer_.colour(1).id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
  glBindTextureUnit(2, gbuffer_.depth().id());
  final_.bind();
  const Program& ink = ink_program_;
  ink.use();
  last_inverse_view_projection_ = glm::inverse(glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view()));
  ink.set("u_inverse_view_projection", glm::mat4(last_inverse_view_projection_));
  ink.set("u_eye", eye);
  ink.set("u_near_far", glm::vec2(static_cast<float>(camera.near_plane), static_cast<float>(camera.far_plane)));
  ink.set("u_light_dir", glm::vec3(glm::normalize(scene_.light.direction)));
  ink.set("u_paper", glm::vec3(scene_.output.paper));
  ink.set("u_fade", static_cast<float>(scene_.output.fade));
  const double to_centre = glm::length(camera.eye() - world_bounds_.centre());
  const double radius = 0.5 * glm::length(world_bounds_.size());
  ink.set("u_fade_range", glm::vec2(static_cast<float>(to_centre - 0.5 * radius), static_cast<float>(to_centre + radius)));
  if (canvas_ && !diffusion_) {
    glBindImageTexture(2, canvas_noise_->id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    ink.set("u_canvas_contrast", static_cast<float>(scene_.canvas.contrast));
  }
  glDrawArrays(GL_TRIANGLES, 0, 3);
  if (timing) timer_.end();
  SHANSHUI_GL_CHECK("ink pass");

  if (diffusion_) {
    PaperTexture paper{absorbency_ ? &*absorbency_ : nullptr};
    if (canvas_) {
      // Absorbency 0.75 + 0.25 · absorbency · noise: the unit-variance canvas keeps most
      // pixels within [0.5, 1] at full strength, like the value noise it replaces.
      paper = {canvas_noise_, glm::vec2(0.25 * scene_.canvas.absorbency, 0.75), canvas_noise_,
               static_cast<float>(scene_.canvas.contrast)};
    }
    diffusion_->run(final_.colour(0), paper, scene_.diffusion, glm::vec3(scene_.output.paper), diffused_.colour(0),
                    timing ? &timer_ : nullptr);
  }

  FrameStats out;
  if (timing) out.passes = timer_.collect();
  else glFlush();
  out.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = std::move(out);
  last_key_ = std::move(key);
  return diffusion_ ? diffused_ : final_;
}

image::Image InkRenderer::worldPositions() const {
  const image::Image depth = gbuffer_.depth().download(1);
  image::Image out(depth.width, depth.height, 4);
  for (int y = 0; y < depth.height; ++y) {
    for (int x = 0; x < depth.width; ++x) {
      const double d = depth.at(x, y, 0);
      if (d >= 1.0) continue;
      // Row 0 of the image is the top: GL's y counts from the bottom.
      const glm::dvec4 ndc((x + 0.5) / depth.width * 2 - 1, 1 - (y + 0.5) / depth.height * 2, d * 2 - 1, 1);
      const glm::dvec4 w = last_inverse_view_projection_ * ndc;
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = static_cast<float>(w[c] / w.w);
      out.at(x, y, 3) = 1.0f;
    }
  }
  return out;
}

image::Image InkRenderer::normalsAndCurvature() const {
  image::Image out = gbuffer_.colour(0).download(4);
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {  // as shaders/ink_gbuffer.frag encodes
    for (std::size_t c = 0; c < 3; ++c) out.pixels[i + c] = out.pixels[i + c] * 2.0f - 1.0f;
    const float w = std::min(out.pixels[i + 3], 65534.0f / 65535.0f);
    out.pixels[i + 3] = w / (1.0f - w);
  }
  return out;
}

image::Image InkRenderer::renderImage(const scene::CameraKey& key, FrameStats* stats, double time) {
  const int w = scene_.output.width, h = scene_.output.height;
  const OrbitCamera cam = sceneCamera(scene_, world_bounds_, static_cast<double>(w) / h, key);
  const Framebuffer& fb = render(cam, w, h, stats, true, time);
  return fb.colour(0).download(3);
}

}  // namespace shanshui::render
