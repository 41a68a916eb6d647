#include "shanshui/render/ink_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/core/error.h"
#include "shanshui/render/ink_diffusion_pass.h"

namespace shanshui::render {

namespace {

// The wrinkle texture's minification filter. Nearest is the default: on llvmpipe bilinear
// filtering cost ~5 ms a frame at 1024² on the sample scene, and a texel of the right mip
// level is about a pixel (bench/ink_tradeoff.cpp measures both against trilinear).
GLenum minFilter(scene::TextureFilter f) {
  switch (f) {
    case scene::TextureFilter::Nearest:
      return GL_NEAREST_MIPMAP_NEAREST;
    case scene::TextureFilter::Bilinear:
      return GL_LINEAR_MIPMAP_NEAREST;
    case scene::TextureFilter::Trilinear:
      return GL_LINEAR_MIPMAP_LINEAR;
  }
  return GL_NEAREST_MIPMAP_NEAREST;
}

// What a preset fixes: elevation, vertical field of view, framing. High distance has no
// elevation of its own: it stands on the ground and looks up.
struct PresetView {
  double elevation_deg, fov_y_deg;
  scene::Framing framing;
};

PresetView presetView(const scene::Scene& s, const scene::CameraKey& key) {
  const scene::Camera& c = s.camera;
  // A composition of ranges is framed by what is drawn of it: its boxes are mostly empty.
  const scene::Framing fill = s.isComposition() ? scene::Framing::Drawn : scene::Framing::Fill;
  switch (c.preset) {
    case scene::CameraPreset::High:
      return {0.0, 40.0, fill};
    case scene::CameraPreset::Deep:
      return {40.0, 35.0, fill};
    case scene::CameraPreset::Level:
      return {6.0, 22.0, fill};
    case scene::CameraPreset::None:
      break;
  }
  return {key.elevation_deg, c.fov_y_deg, c.framing};
}

// Up to 4096 of the mesh's vertices, evenly strided, and its highest one: enough for the
// relief's grid and its summit.
std::vector<glm::dvec3> reliefSample(const mesh::Mesh& m) {
  std::vector<glm::dvec3> out;
  if (m.positions.empty()) return out;
  const std::size_t stride = std::max<std::size_t>(1, m.positions.size() / 4096);
  for (std::size_t i = 0; i < m.positions.size(); i += stride) out.push_back(m.positions[i]);
  out.push_back(*std::max_element(m.positions.begin(), m.positions.end(),
                                  [](const glm::dvec3& p, const glm::dvec3& q) { return p.z < q.z; }));
  return out;
}

}  // namespace

double composedElevation(const scene::Scene& s) {
  return presetView(s, {s.camera.azimuth_deg, s.camera.elevation_deg, s.camera.zoom}).elevation_deg;
}

OrbitCamera sceneCamera(const scene::Scene& s, const mesh::Bounds& world_bounds, double aspect,
                        const scene::CameraKey& key, const Relief* relief, const mesh::Bounds* inked,
                        const std::vector<glm::dvec3>* drawn) {
  const scene::Camera& c = s.camera;
  const PresetView v = presetView(s, key);
  const mesh::Bounds& framed = inked ? *inked : world_bounds;
  OrbitCamera cam;
  if (c.preset == scene::CameraPreset::High) {
    const glm::dvec3 lo = world_bounds.min, hi = world_bounds.max, mid = world_bounds.centre();
    const Relief floor({lo, {hi.x, hi.y, lo.z}, {mid.x, mid.y, hi.z}});
    cam = highDistance(relief && !relief->empty() ? *relief : floor, key.azimuth_deg, v.fov_y_deg, key.zoom,
                       s.isComposition());
  } else if (v.framing == scene::Framing::Drawn && drawn && !drawn->empty()) {
    cam = fillPoints(*drawn, key.azimuth_deg, v.elevation_deg, v.fov_y_deg, aspect, key.zoom);
  } else if (v.framing != scene::Framing::Sphere) {
    cam = fillBounds(framed, key.azimuth_deg, v.elevation_deg, v.fov_y_deg, aspect, key.zoom);
  } else {
    cam = frameBounds(world_bounds, key.azimuth_deg, v.elevation_deg, v.fov_y_deg, aspect, key.zoom);
    cam.target += world_bounds.centre();
  }
  if (c.target) cam.target = *c.target;
  if (c.distance > 0) cam.distance = c.distance / key.zoom;
  // The whole scene, seen from wherever the camera now is: with what stands on the ground
  // (outside the world bounds, a pagoda's top above a summit), which `inked` holds.
  mesh::Bounds all = world_bounds;
  if (inked) all = {glm::min(all.min, inked->min), glm::max(all.max, inked->max)};
  cam.enclose(all);
  return cam;
}

scene::CameraKey frameKey(const scene::Scene& s, double index, int count, double orbit_deg) {
  const scene::Camera& c = s.camera;
  scene::CameraKey key{c.azimuth_deg, c.elevation_deg, c.zoom};
  if (count <= 1) return key;
  if (!c.path.empty()) {
    if (c.path.size() == 1) return c.path[0];
    // Between frames (motion blur's previous pose) too; before the first, along the first leg.
    const double x = index / (count - 1) * static_cast<double>(c.path.size() - 1);
    const std::size_t i = x <= 0.0 ? 0 : std::min(static_cast<std::size_t>(x), c.path.size() - 2);
    const double t = x - static_cast<double>(i);
    const scene::CameraKey &a = c.path[i], &b = c.path[i + 1];
    return {a.azimuth_deg + t * (b.azimuth_deg - a.azimuth_deg),
            a.elevation_deg + t * (b.elevation_deg - a.elevation_deg), a.zoom * std::pow(b.zoom / a.zoom, t)};
  }
  key.azimuth_deg += orbit_deg * index / count;
  return key;
}

std::optional<glm::ivec4> InkRenderer::animatedRegion(const FrameInputs& in) const {
  // The animated objects' bounds now (and, with motion blur, where their trails reach back
  // to), in pixels, grown by the farthest any pass reads around a pixel: line and stroke
  // widths, edge darkening's blur, how far the diffusion carries a change, the substrate's
  // distortion, a margin for the rest.
  const glm::dmat4 vp = glm::dmat4(in.viewProjection());
  const double px = in.height / 1024.0;
  double grow = 12.0 * px + 8.0;
  for (const scene::Object& o : in.scene.objects)
    grow = std::max(grow, 8.0 + 2.0 * std::max(o.lines.width, o.strokes.width) * px);
  if (in.scene.edges.enabled) grow += (in.scene.edges.radius + in.scene.edges.wobble) * px;
  if (in.scene.substrate.enabled) grow += in.scene.substrate.distortion * px;
  if (in.scene.diffusion.enabled()) grow += InkDiffusionPass::dependence(in.scene.diffusion);
  std::vector<double> times{in.time};
  if (in.scene.motion_blur.enabled)
    times.push_back(in.time - in.scene.motion_blur.length * in.scene.motion_blur.interval);
  glm::dvec2 lo(1e300), hi(-1e300);
  bool any = false;
  for (std::size_t i = 0; i < in.objects.size(); ++i) {
    if (!in.scene.objects[i].animated()) continue;
    const glm::dvec3 half = 0.5 * in.objects[i].model_bounds.size();
    for (double t : times) {
      const glm::dmat4 m = vp * in.modelAt(i, t);
      for (int c = 0; c < 8; ++c) {
        const glm::dvec4 q =
            m * glm::dvec4((c & 1 ? 1 : -1) * half.x, (c & 2 ? 1 : -1) * half.y, (c & 4 ? 1 : -1) * half.z, 1.0);
        if (q.w <= 1e-9) return glm::ivec4(0, 0, in.width, in.height);  // behind the eye: all of it
        const glm::dvec2 p = (glm::dvec2(q) / q.w * 0.5 + 0.5) * glm::dvec2(in.width, in.height);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        any = true;
      }
    }
  }
  if (!any) return std::nullopt;
  const glm::ivec2 a = glm::clamp(glm::ivec2(glm::floor(lo - grow)), glm::ivec2(0), glm::ivec2(in.width, in.height));
  const glm::ivec2 b = glm::clamp(glm::ivec2(glm::ceil(hi + grow)), glm::ivec2(0), glm::ivec2(in.width, in.height));
  return glm::ivec4(a, b);
}

std::string InkRenderer::structureKey(const scene::Scene& s) {
  // The scene's rebuild keys (files, object count, variant switches) and, per pass of the
  // list, whether the scene wants it and the compile-time choices it makes.
  std::ostringstream k;
  k << s.base_dir.string() << "|" << scene::parameterHash(s, scene::Effect::Rebuild);
  for (const PassEntry& e : passList()) {
    if (e.wanted(s)) k << "|" << e.name << ":" << e.structure(s);
  }
  return k.str();
}

InkRenderer::InkRenderer(const scene::Scene& s, const std::vector<scene::LoadedObject>& objects) : scene_(s) {
  SHANSHUI_CHECK_EQ(objects.size(), s.objects.size());
  if (objects.size() > 255) throw makeError("a scene holds at most 255 objects; this one has ", objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const scene::ObjectAsset& a = *objects[i].geometry;
    const scene::Object& o = s.objects[i];
    SceneObjectGpu g;
    const bool per_vertex = o.lines.enabled && scene::perVertex(o.lines.curvature);
    g.mesh = GpuMesh(a.mesh, a.bounds.centre(), per_vertex ? &a.curvature : nullptr, true);
    g.model_bounds = a.bounds;
    g.model_feature_size = a.feature_size;
    g.max_triangle_area = maxTriangleArea(a.mesh);
    if (o.strokes.enabled()) g.asset = objects[i].geometry;
    g.elements = objects[i].elements;
    relief_points_.push_back(reliefSample(a.mesh));
    if (o.wrinkled()) {
      SHANSHUI_CHECK(objects[i].wrinkle != nullptr);
      g.wrinkle = Texture2D::tiledFromImage(*objects[i].wrinkle, GL_R8);
    }
    objects_.push_back(std::move(g));
  }
  if (scene::usesGrounding(s)) grounding_ = std::make_unique<scene::Grounding>(objects);
  setObjects(s);
  const PassSetup setup{s, objects_, world_bounds_};
  for (const PassEntry& e : passList()) {
    if (!e.wanted(s)) continue;
    passes_.push_back({&e, e.make(setup)});
    passes_.back().pass->setScene(s);
    pass_names_.push_back(passes_.back().pass->name());
  }
  collectVariants();
}

InkRenderer::~InkRenderer() = default;

std::size_t InkRenderer::triangleCount() const {
  std::size_t n = 0;
  for (const SceneObjectGpu& o : objects_) n += o.mesh.triangleCount();
  return n;
}

const RenderPass* InkRenderer::find(const std::string& name) const {
  for (const Built& b : passes_) {
    if (name == b.entry->name || name == b.pass->name()) return b.pass.get();
  }
  return nullptr;
}

const Framebuffer* InkRenderer::passTarget(const std::string& pass) const {
  const RenderPass* p = find(pass);
  return p ? p->target() : nullptr;
}

std::size_t InkRenderer::marksDropped() const {
  std::size_t n = 0;
  for (const Built& b : passes_) n += b.pass->marksDropped();
  return n;
}

const Texture2D* InkRenderer::absorbency() const {
  const RenderPass* p = find("diffusion");
  return p ? absorbencyOf(*p) : nullptr;
}

const CanvasPass* InkRenderer::canvas() const {
  const RenderPass* p = find("canvas");
  return p ? canvasOf(*p) : nullptr;
}

void InkRenderer::collectVariants() {
  variants_.clear();
  for (const Built& b : passes_) variants_[b.pass->name()] = b.pass->variants();
  invalidate();
}

void InkRenderer::setDebugOutputs(bool on) {
  for (Built& b : passes_) b.pass->setDebugOutputs(on);
  collectVariants();  // the next frame draws everything again
}

void InkRenderer::reloadShaders() {
  for (Built& b : passes_) b.pass->buildPrograms();
  collectVariants();
}

void InkRenderer::setScene(const scene::Scene& s) {
  if (structureKey(s) != structureKey(scene_)) {
    throw makeError("InkRenderer::setScene: the scene's files, passes or variants changed; build a new renderer");
  }
  scene_ = s;
  setObjects(s);
  for (Built& b : passes_) b.pass->setScene(s);
  invalidate();
}

void InkRenderer::setObjects(const scene::Scene& s) {
  // Objects standing on others take the pose that rests them on their ground; the world
  // bounds (the water level, the mist's height, the fade) are those of what stands on
  // nothing, so a pagoda on a summit moves none of them.
  if (scene::usesGrounding(s) && !grounding_)
    throw makeError("InkRenderer::setObjects: the scene now grounds objects; build a new renderer");
  std::vector<glm::dmat4>& world = world_;
  world.clear();
  if (grounding_) {
    world = grounding_->worldMatrices(s);
  } else {
    for (const scene::Object& o : s.objects) world.push_back(o.transform.matrix());
  }
  world_bounds_ = {glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  inked_bounds_ = world_bounds_;
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    SceneObjectGpu& g = objects_[i];
    const glm::dmat4& t = world[i];
    g.model = t * glm::translate(glm::dmat4(1.0), g.model_bounds.centre());
    const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(t))));
    g.centre = glm::dvec3(t * glm::dvec4(g.model_bounds.centre(), 1.0));
    g.radius = std::max(0.5 * glm::length(g.model_bounds.size()) * scale, 1e-12);
    g.feature_size = g.model_feature_size * scale;
    if (g.wrinkle) {
      const GLint filter = static_cast<GLint>(minFilter(s.objects[i].wrinkle.filter));
      glTextureParameteri(g.wrinkle->id(), GL_TEXTURE_MIN_FILTER, filter);
    }
    // A dissolving border leaves paper over its falloff band: the inked part is the model
    // box with that band taken off its horizontal sides.
    const scene::Object& o = s.objects[i];
    const glm::dvec3 half = 0.5 * g.model_bounds.size();
    const double band = o.dissolvesBorder() ? o.border.width * std::min(half.x, half.y) : 0.0;
    const glm::dvec3 inset(band, band, 0.0);
    const mesh::Bounds inked{g.model_bounds.min + inset, g.model_bounds.max - inset};
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 w(t * glm::dvec4(g.model_bounds.corner(c), 1.0));
      if (!o.grounded()) {
        world_bounds_.min = glm::min(world_bounds_.min, w);
        world_bounds_.max = glm::max(world_bounds_.max, w);
      }
      const glm::dvec3 wi(t * glm::dvec4(inked.corner(c), 1.0));
      inked_bounds_.min = glm::min(inked_bounds_.min, wi);
      inked_bounds_.max = glm::max(inked_bounds_.max, wi);
    }
  }
  // What is drawn of the land: the relief samples inside each dissolving border's inner
  // edge and above the water (Framing::Drawn frames these).
  std::vector<glm::dvec3> points;
  drawn_.clear();
  const double water = scene::waterHeight(s, world_bounds_);
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const scene::Object& o = s.objects[i];
    const mesh::Bounds& mb = objects_[i].model_bounds;
    const glm::dvec3 half = 0.5 * mb.size(), centre = mb.centre();
    const double band = o.dissolvesBorder() ? o.border.width * std::min(half.x, half.y) : 0.0;
    for (const glm::dvec3& p : relief_points_[i]) {
      const glm::dvec3 w(world[i] * glm::dvec4(p, 1.0));
      points.push_back(w);
      const bool inside = std::abs(p.x - centre.x) <= half.x - band && std::abs(p.y - centre.y) <= half.y - band;
      if (inside && w.z >= water) drawn_.push_back(w);
    }
  }
  relief_ = Relief(points);
}

InkRenderer::Request InkRenderer::request(const OrbitCamera& camera, const OrbitCamera* previous, int width,
                                          int height) const {
  Request r;
  r.width = width;
  r.height = height;
  r.version = version_;
  std::size_t i = 0;
  for (const OrbitCamera* c : {&camera, previous}) {
    if (!c) break;
    for (const double v : {c->target.x, c->target.y, c->target.z, c->distance, c->azimuth_deg, c->elevation_deg,
                           c->fov_y_deg, c->near_plane, c->far_plane})
      r.cameras[i++] = v;
  }
  return r;
}

const Framebuffer& InkRenderer::render(const OrbitCamera& camera, int width, int height, FrameStats* stats, bool timing,
                                       double time, const OrbitCamera* previous_camera) {
  const auto start = std::chrono::steady_clock::now();
  if (width != width_ || height != height_) {
    for (Built& b : passes_) b.pass->resize(width, height);
    width_ = width;
    height_ = height;
    invalidate();
  }
  // With motion blur the velocities depend on where the camera was a frame ago too.
  const Request now = request(camera, scene_.motion_blur.enabled ? previous_camera : nullptr, width, height);
  const bool same_static = last_request_ && *last_request_ == now;
  if (same_static && (!scene_.hasAnimation() || time == last_time_)) {
    if (stats)
      *stats = FrameStats{true,
                          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                          {},
                          0.0,
                          {}};
    return *last_output_;
  }
  if (!same_static) ++static_key_;
  const FrameInputs in{scene_,
                       objects_,
                       world_bounds_,
                       camera,
                       width,
                       height,
                       time,
                       static_key_,
                       timing ? &timer_ : nullptr,
                       scene_.motion_blur.enabled ? previous_camera : nullptr};
  // Seed 002's state C for every pass: when only animated objects changed since the last
  // frame, the passes redraw only the region they cover now and covered then (each target
  // outside it still holds the last frame, which there shows the static objects as they
  // are), grown by how far a pass reads around a pixel.
  std::optional<glm::ivec4> region;
  const std::optional<glm::ivec4> moving = scene_.hasAnimation() ? animatedRegion(in) : std::nullopt;
  if (moving && same_static && last_moving_ && !scene_.usesShadow()) {
    const glm::ivec4 r(glm::min(glm::ivec2(*moving), glm::ivec2(*last_moving_)),
                       glm::max(glm::ivec2(moving->z, moving->w), glm::ivec2(last_moving_->z, last_moving_->w)));
    // On whole 2×2 quads: shaders that sample with implicit derivatives (the border's and the
    // mist's noise) need both pixels of a quad; at a scissor edge the rasteriser drops one.
    const glm::ivec4 quads(r.x & ~1, r.y & ~1, std::min((r.z + 1) & ~1, width), std::min((r.w + 1) & ~1, height));
    if (static_cast<double>(quads.z - quads.x) * (quads.w - quads.y) < 0.6 * width * height) region = quads;
  }
  FrameInputs scoped = in;
  if (region) {
    scoped.region = &*region;
    glEnable(GL_SCISSOR_TEST);
    glScissor(region->x, region->y, region->z - region->x, region->w - region->y);
  }
  // The uniforms every pass reads alike, in one block bound for the whole frame; uploaded
  // only when they change (a cached layer's frame, a still camera with moving objects).
  const gpu::FrameParams params = frameParams(in);
  if (!frame_block_) {
    frame_block_ = Buffer::create();
    glNamedBufferStorage(frame_block_.id(), sizeof params, &params, GL_DYNAMIC_STORAGE_BIT);
  } else if (!frame_params_ || std::memcmp(&*frame_params_, &params, sizeof params) != 0) {
    glNamedBufferSubData(frame_block_.id(), 0, sizeof params, &params);
  }
  frame_params_ = params;
  glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBlockBinding, frame_block_.id());
  const std::uint64_t uniforms_before = uniformsSet();
  FrameImages images;
  std::vector<PassSubmit> submit;
  for (Built& b : passes_) {
    const Texture2D* before = images.picture;
    const auto pass_start = std::chrono::steady_clock::now();
    b.pass->run(scoped, images);
    submit.push_back(
        {b.entry->name,
         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pass_start).count()});
    if (images.picture != before) last_output_ = b.pass->target();
  }
  glDisable(GL_SCISSOR_TEST);
  last_request_ = now;
  last_time_ = time;
  last_moving_ = moving;
  const double aspect = static_cast<double>(width) / height;
  last_inverse_view_projection_ = glm::inverse(glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view()));

  FrameStats out;
  out.submit = std::move(submit);
  out.uniforms_set = uniformsSet() - uniforms_before;
  out.redrawn = region ? static_cast<double>(region->z - region->x) * (region->w - region->y) / (width * height) : 1.0;
  if (timing && late_timing_) {
    timer_.endFrame();
    glFlush();
  } else if (timing) {
    out.passes = timer_.collect();
  } else {
    glFlush();
  }
  out.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = std::move(out);
  return *last_output_;
}

void InkRenderer::setLateTiming(bool on) {
  if (!on)
    while (timer_.collectLate(true)) {
    }
  late_timing_ = on;
}

image::Image InkRenderer::worldPositions() const {
  const image::Image depth = passTarget("gbuffer")->depth().download(1);
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
  image::Image out = passTarget("gbuffer")->colour(0).download(4);
  for (std::size_t i = 0; i < out.pixels.size(); i += 4) {  // as shaders/gbuffer/ink_gbuffer.frag encodes
    for (std::size_t c = 0; c < 3; ++c) out.pixels[i + c] = out.pixels[i + c] * 2.0f - 1.0f;
    const float w = std::min(out.pixels[i + 3], 65534.0f / 65535.0f);
    out.pixels[i + 3] = w / (1.0f - w);
  }
  return out;
}

image::Image InkRenderer::renderImage(const scene::CameraKey& key, FrameStats* stats, double time,
                                      const scene::CameraKey* previous_key) {
  const int w = scene_.output.pixelWidth(), h = scene_.output.pixelHeight();
  const OrbitCamera cam = camera(key, static_cast<double>(w) / h);
  std::optional<OrbitCamera> previous;
  if (previous_key) previous = camera(*previous_key, static_cast<double>(w) / h);
  const Framebuffer& fb = render(cam, w, h, stats, true, time, previous ? &*previous : nullptr);
  return fb.colour(0).download(3);
}

}  // namespace shanshui::render
