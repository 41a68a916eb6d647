#include "shanshui/render/canvas_pass.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/core/error.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/noise/gabor.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"

namespace shanshui::render {

namespace {

// Components of one vertex the geometry shader emits: gl_Position, g_offset, g_impulse.
constexpr int kComponentsPerVertex = 4 + 2 + 4;

// The background dome: 20 · 4⁶ = 81920 triangles keep one triangle's kernels within the
// geometry shader's cap at the default density for fields of view down to ~20°.
constexpr int kDomeLevels = 6;
constexpr double kDomeScale = 20.0;

int maxQuadsPerInvocation() {
  GLint vertices = 0, components = 0;
  glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &vertices);
  glGetIntegerv(GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, &components);
  return std::max(1, std::min(vertices / 4, components / (4 * kComponentsPerVertex)));
}

// The mottle's program: the background's matrices only.
const std::vector<std::string> kMottleDefines{"SPACES=1", "MOTTLE"};

// The tiles canvas's space of the background (world) or of an object (canvas_lattice.glsl's
// Space, std140).
struct Space {
  glm::mat4 to_model, to_clip;  // clip ↔ model
  glm::vec4 pixel;              // x: model units across a pixel at clip w 1
};

// The space whose model → clip matrix is `model_view_projection`, in a view `width` pixels
// wide.
Space spaceOf(const glm::dmat4& model_view_projection, int width) {
  const glm::dmat4 to_model = glm::inverse(model_view_projection);
  // One pixel along x at clip w 1 is a clip offset of 2 / width, taken by to_model's first
  // column.
  const double per_pixel = glm::length(glm::dvec3(to_model[0])) * 2.0 / width;
  return {glm::mat4(to_model), glm::mat4(model_view_projection), glm::vec4(static_cast<float>(per_pixel), 0, 0, 0)};
}

}  // namespace

std::uint32_t canvasSeed(std::uint64_t scene_seed) {
  return noise::noiseSeed32(scene_seed ^ 0xCA57A5ull);
}

double maxTriangleArea(const mesh::Mesh& m) {
  double best = 0;
  for (const glm::uvec3& f : m.triangles) {
    const glm::dvec3 a = m.positions[f.x], b = m.positions[f.y], c = m.positions[f.z];
    best = std::max(best, 0.5 * glm::length(glm::cross(b - a, c - a)));
  }
  return best;
}

CanvasPass::CanvasPass(const scene::Canvas& canvas, std::uint64_t seed, const mesh::Bounds& world_bounds,
                       std::size_t objects)
    : canvas_(canvas),
      objects_(objects),
      seed_(canvasSeed(seed)),
      method_(canvas.type == scene::CanvasType::Static      ? Method::Static
              : canvas.method == scene::CanvasMethod::Splat ? Method::Splat
                                                            : Method::Tiles) {
  SHANSHUI_CHECK(canvas.type != scene::CanvasType::None);
  if (canvas.pattern() == scene::CanvasPattern::Silk) defines_.emplace_back("CANVAS_SILK");
  if (method_ == Method::Splat) quads_ = maxQuadsPerInvocation();
  if (method_ == Method::Tiles) {
    GLint block = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block);
    const std::size_t needed = (objects + 1) * sizeof(Space);
    if (needed > static_cast<std::size_t>(block)) {
      throw makeError("canvas.method 'tiles' needs a ", needed, "-byte uniform block for ", objects,
                      " objects and this driver allows ", block, "; use canvas.method 'splat' or fewer objects");
    }
    spaces_ = Buffer::create();
    glNamedBufferStorage(spaces_.id(), static_cast<GLsizeiptr>(needed), nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  reloadShaders();
  dome_centre_ = world_bounds.centre();
  dome_radius_ = kDomeScale * std::max(0.5 * glm::length(world_bounds.size()), 1e-6);
  if (method_ == Method::Splat) {
    mesh::Mesh dome = mesh::icosphere(kDomeLevels);
    for (auto& p : dome.positions) {
      p *= dome_radius_;
      dome_positions_.emplace_back(p);
    }
    dome_triangles_ = std::move(dome.triangles);
    dome_vao_ = VertexArray::create();
    dome_positions_buffer_ = Buffer::create();
    dome_visible_buffer_ = Buffer::create();
    glNamedBufferStorage(dome_positions_buffer_.id(),
                         static_cast<GLsizeiptr>(dome_positions_.size() * sizeof(glm::vec3)), dome_positions_.data(),
                         0);
    glNamedBufferStorage(dome_visible_buffer_.id(),
                         static_cast<GLsizeiptr>(dome_triangles_.size() * sizeof(glm::uvec3)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(dome_vao_.id(), 0, dome_positions_buffer_.id(), 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(dome_vao_.id(), 0);
    glVertexArrayAttribFormat(dome_vao_.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(dome_vao_.id(), 0, 0);
    glVertexArrayElementBuffer(dome_vao_.id(), dome_visible_buffer_.id());
  } else {
    empty_vao_ = VertexArray::create();
  }
}

std::vector<std::string> CanvasPass::definesFor(int invocations) const {
  std::vector<std::string> d = defines_;
  if (method_ == Method::Splat) {
    d.push_back("INVOCATIONS=" + std::to_string(invocations));
    d.push_back("QUADS=" + std::to_string(quads_));
  }
  if (method_ == Method::Tiles) d.emplace_back("CANVAS_TILE");
  return d;
}

std::vector<std::string> CanvasPass::tilesDefines(bool background) const {
  // The block of clip ↔ model matrices holds the background and every object.
  std::vector<std::string> d{"SPACES=" + std::to_string(objects_ + 1)};
  if (background) {
    d.emplace_back("BACKGROUND");
  } else if (objects_ == 1) {
    d.emplace_back("SINGLE_OBJECT");
  }
  if (canvas_.hasFibresOrSpots()) d.emplace_back("PAPER_MARKS");
  if (canvas_.hasMottle()) d.emplace_back("MOTTLE");
  if (canvas_.grainOnSurface()) d.emplace_back("GRAIN_ON_SURFACE");
  return d;
}

std::vector<std::string> CanvasPass::variants() const {
  switch (method_) {
    case Method::Splat:
      return {joined(definesFor(1)), joined(definesFor(kInvocations))};
    case Method::Tiles: {
      // The tile's, the surfaces', the background's, and the mottle's when it is drawn.
      const std::string stage = compute_ ? " PIXEL_COMPUTE" : "";
      std::vector<std::string> v{joined(definesFor(1)), joined(tilesDefines(false)) + stage,
                                 joined(tilesDefines(true)) + stage};
      if (canvas_.hasMottle()) v.push_back(joined(kMottleDefines));
      return v;
    }
    case Method::Static:
      break;
  }
  return {joined(definesFor(1))};
}

void CanvasPass::reloadShaders() {
  switch (method_) {
    case Method::Static:
      static_ = Program({"fullscreen.vert", "canvas_static.frag"}, definesFor(1));
      static_key_.reset();
      return;
    case Method::Tiles: {
      Program synthesis({"fullscreen.vert", "canvas_static.frag"}, definesFor(1));
      // All built before any is replaced.
      // On a GPU the two are compute shaders, each testing the G-buffer's depth itself.
      const bool compute = pixelPassesAsCompute();
      std::vector<std::string> surface_defines = tilesDefines(false), background_defines = tilesDefines(true);
      if (compute) {
        surface_defines.emplace_back("PIXEL_SURFACES");
        background_defines.emplace_back("PIXEL_BACKGROUND");
      }
      Program surfaces = pixelProgram("canvas_tiles.frag", surface_defines, compute);
      Program background = pixelProgram("canvas_tiles.frag", background_defines, compute);
      compute_ = compute;
      tile_synthesis_ = std::move(synthesis);
      tiles_ = std::move(surfaces);
      tiles_background_ = std::move(background);
      if (canvas_.hasMottle()) mottle_ = Program({"fullscreen.vert", "canvas_mottle.frag"}, kMottleDefines);
      tile_key_.reset();
      return;
    }
    case Method::Splat:
      break;
  }
  const std::vector<std::string> files{"canvas.vert", "canvas.geom", "canvas.frag"};
  Program single(files, definesFor(1)), multi(files, definesFor(kInvocations));  // both built before either is replaced
  single_ = std::move(single);
  multi_ = std::move(multi);
}

GLsizei CanvasPass::uploadVisibleDome(const glm::dmat4& model_view_projection) {
  // Most of the dome is off screen, and every triangle costs kInvocations geometry-shader
  // runs: only those not wholly outside one clip plane are drawn.
  std::vector<glm::uvec3> visible;
  std::vector<glm::vec4> clip(dome_positions_.size());
  const glm::mat4 m(model_view_projection);
  for (std::size_t i = 0; i < clip.size(); ++i) clip[i] = m * glm::vec4(dome_positions_[i], 1.0f);
  for (const glm::uvec3& f : dome_triangles_) {
    const glm::vec4 a = clip[f.x], b = clip[f.y], c = clip[f.z];
    auto outside = [&](int axis, float sign) {
      return sign * a[axis] > a.w && sign * b[axis] > b.w && sign * c[axis] > c.w;
    };
    if (a.w <= 0 && b.w <= 0 && c.w <= 0) continue;
    if (outside(0, 1) || outside(0, -1) || outside(1, 1) || outside(1, -1)) continue;
    visible.push_back(f);
  }
  glNamedBufferSubData(dome_visible_buffer_.id(), 0, static_cast<GLsizeiptr>(visible.size() * sizeof(glm::uvec3)),
                       visible.data());
  return static_cast<GLsizei>(visible.size() * 3);
}

void CanvasPass::setParams(const scene::Canvas& canvas, std::uint64_t seed) {
  SHANSHUI_CHECK(canvas.type == canvas_.type);
  SHANSHUI_CHECK(canvas.pattern() == canvas_.pattern());
  SHANSHUI_CHECK(canvas.method == canvas_.method || method_ == Method::Static);
  canvas_ = canvas;
  seed_ = canvasSeed(seed);
  static_key_.reset();
}

noise::CanvasNoiseOptions CanvasPass::noiseOptions(int height) const {
  const double scale = height / 1024.0;
  noise::CanvasNoiseOptions o;
  o.silk = canvas_.pattern() == scene::CanvasPattern::Silk;
  o.radius = canvas_.grain * scale;
  o.F0 = canvas_.frequency / scale;
  o.omega0 = canvas_.orientation_deg * std::numbers::pi / 180;
  o.isotropic = canvas_.isotropic;
  o.mix = canvas_.mix;
  o.perlin_frequency = canvas_.perlin_frequency;
  o.impulses = canvas_.impulses;
  return o;
}

void CanvasPass::setKernel(const Program& p, const noise::CanvasNoiseOptions& o) const {
  // σ is a quadrature over the disc: computed once per parameter set.
  static std::map<std::array<double, 8>, double> sigmas;
  const std::array<double, 8> key{static_cast<double>(o.silk),
                                  o.radius,
                                  o.F0,
                                  o.omega0,
                                  static_cast<double>(o.isotropic),
                                  o.mix,
                                  o.perlin_frequency,
                                  static_cast<double>(o.impulses)};
  auto it = sigmas.find(key);
  if (it == sigmas.end()) it = sigmas.emplace(key, noise::canvasSigma(o)).first;
  p.set("u_kernel", glm::vec4(o.radius, noise::canvasBandwidth(o), o.F0, o.omega0));
  p.set("u_kernel_misc",
        glm::vec4(o.mix, o.perlin_frequency / o.radius, o.isotropic ? 1.0f : 0.0f, 1.0 / std::max(it->second, 1e-30)));
  p.set("u_density", static_cast<float>(o.impulses / (std::numbers::pi * o.radius * o.radius)));
  p.set("u_seed", seed_);
}

const Texture2D& CanvasPass::run(const std::vector<Item>& items, const Framebuffer& gbuffer,
                                 const Texture2D& attachable_depth, const OrbitCamera& camera, int width, int height,
                                 GpuTimer* timer) {
  if (target_.width() != width || target_.height() != height) {
    target_ = Framebuffer(width, height, {GL_RG16F}, false);
    static_key_.reset();
  }
  const noise::CanvasNoiseOptions o = noiseOptions(height);
  if (method_ == Method::Static) {
    const std::array<int, 2> key{width, height};
    if (key == static_key_) return target_.colour(0);
    if (timer) timer->begin(passName());
    target_.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    static_.use();
    setKernel(static_, o);
    glBindVertexArray(empty_vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (timer) timer->end();
    SHANSHUI_GL_CHECK("canvas_static pass");
    static_key_ = key;
    return target_.colour(0);
  }
  if (method_ == Method::Tiles) {  // before the timer: once per parameter set
    updateTile(o);
    if (canvas_.hasFibresOrSpots()) updateMarkSprites(height);
  }
  if (timer) timer->begin(passName());
  if (method_ == Method::Tiles) {
    runTiles(items, gbuffer, attachable_depth, camera, width, height, o);
  } else {
    runSplat(items, gbuffer.depth(), camera, width, height, o);
  }
  if (timer) timer->end();
  SHANSHUI_GL_CHECK("canvas pass");
  return target_.colour(0);
}

image::Image CanvasPass::tile() const {
  if (!tile_bytes_) return {};
  std::vector<std::int8_t> bytes(static_cast<std::size_t>(tile_size_) * tile_size_);
  glGetNamedBufferSubData(tile_bytes_.id(), 0, static_cast<GLsizeiptr>(bytes.size()), bytes.data());
  image::Image out(tile_size_, tile_size_, 1);
  for (int y = 0; y < tile_size_; ++y)
    for (int x = 0; x < tile_size_; ++x) {
      out.at(x, tile_size_ - 1 - y, 0) = bytes[static_cast<std::size_t>(y) * tile_size_ + x] / 127.0f;
    }
  return out;
}

void CanvasPass::updateTile(const noise::CanvasNoiseOptions& pixels) {
  // The tile holds kTileCells² cells of one kernel radius r_t texels: a power of two (the
  // shader wraps by a mask), 16 texels per cycle across a radius (silk threads, Perlin
  // octaves) so that reading the nearest texel moves the pattern by a small fraction of a
  // cycle (at 8 the warping error of an orbit or a pan doubled). It is read at r_t / r
  // texels per screen pixel.
  const double cycles = pixels.silk ? pixels.F0 * pixels.radius : pixels.perlin_frequency;
  const int radius =
      16 * static_cast<int>(std::bit_ceil(static_cast<unsigned>(std::ceil(std::clamp(cycles, 1.0, 4.0)))));
  noise::CanvasNoiseOptions texels = pixels;
  texels.radius = radius;
  texels.F0 = pixels.F0 * pixels.radius / radius;
  texels_per_pixel_ = static_cast<float>(radius / pixels.radius);
  const std::array<double, 9> key{static_cast<double>(texels.silk),
                                  texels.F0,
                                  texels.omega0,
                                  static_cast<double>(texels.isotropic),
                                  texels.mix,
                                  texels.perlin_frequency,
                                  static_cast<double>(texels.impulses),
                                  static_cast<double>(radius),
                                  static_cast<double>(seed_)};
  if (key == tile_key_) return;
  tile_options_ = texels;
  // The copies' spectrum is the tile's, lines 1 / size apart: silk's narrow ring gets twice
  // the cells (at 16 its peak wandered by 6 % through a dolly, CanvasGl.ContrastAndGrain-
  // HoldThroughADolly; rice paper's broad spectrum does not notice). The tile costs texels ×
  // N′ kernel evaluations to draw: past twice the default's, fewer cells (down to 8 across;
  // copies are read at random offsets, so a small tile does not show as a repeat).
  tile_cells_ = pixels.silk ? 2 * kTileCells : kTileCells;
  while (tile_cells_ > 8 &&
         static_cast<double>(tile_cells_ * radius) * (tile_cells_ * radius) * texels.impulses > kTileWork) {
    tile_cells_ /= 2;
  }
  const int size = tile_cells_ * radius;
  const Framebuffer canvas(size, size, {GL_R32F}, false);
  canvas.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  tile_synthesis_.use();
  setKernel(tile_synthesis_, texels);
  tile_synthesis_.set("u_cells", tile_cells_);
  glBindVertexArray(empty_vao_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  SHANSHUI_GL_CHECK("canvas tile");
  // Zero mean and unit variance over the tile exactly (the parameters' σ is that of an
  // infinite plane; a finite tile differs by a few per cent), stored as 8-bit signed
  // values of v / kTileRange: the shader's reads of random texels cost less the smaller
  // the tile is in memory, and the rounding (σ / 32 steps) adds under 0.01 % of variance.
  image::Image values = canvas.colour(0).download(1);
  double sum = 0, sum2 = 0;
  for (float v : values.pixels) {
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  const double n = static_cast<double>(values.pixels.size()), mean = sum / n;
  const double var = std::max(sum2 / n - mean * mean, 0.0);
  const double scale = var > 1e-30 ? 1.0 / std::sqrt(var) : 0.0;
  // Rows bottom first, as GL stores them (the download put the top first). A buffer
  // texture, read by index: a software rasteriser's reads of it skip the 2D image's second
  // bounds test and row multiply (~0.4 ms of the pass's ~19 at 1024x768).
  std::vector<std::int8_t> bytes(values.pixels.size());
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double v = (values.at(x, size - 1 - y, 0) - mean) * scale / kTileRange;
      bytes[static_cast<std::size_t>(y) * size + x] =
          static_cast<std::int8_t>(std::lround(127 * std::clamp(v, -1.0, 1.0)));
    }
  tile_bytes_ = Buffer::create();
  glNamedBufferStorage(tile_bytes_.id(), static_cast<GLsizeiptr>(bytes.size()), bytes.data(), 0);
  tile_ = BufferTexture::create();
  glTextureBuffer(tile_.id(), GL_R8I, tile_bytes_.id());
  tile_size_ = size;
  SHANSHUI_GL_CHECK("canvas tile upload");
  tile_key_ = key;
}

void CanvasPass::runTiles(const std::vector<Item>& items, const Framebuffer& gbuffer, const Texture2D& attachable_depth,
                          const OrbitCamera& camera, int width, int height, const noise::CanvasNoiseOptions& o) {
  // Clip ↔ model matrices of the background (world) and of each object, indexed by the
  // G-buffer's object id (the block sized in the constructor).
  SHANSHUI_CHECK(items.size() == objects_);
  const double aspect = static_cast<double>(width) / height;
  const glm::dmat4 view_projection = glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view());
  std::vector<Space> spaces{spaceOf(view_projection, width)};
  for (const Item& item : items) spaces.push_back(spaceOf(view_projection * item.model, width));
  glNamedBufferSubData(spaces_.id(), 0, static_cast<GLsizeiptr>(spaces.size() * sizeof(Space)), spaces.data());
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, spaces_.id());
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(empty_vao_.id());
  const float mottle_cell = canvas_.hasMottle() ? drawMottle(camera, width, height) : 1.0f;
  if (compute_) {
    glBindImageTexture(2, target_.colour(0).id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
    glBindTextureUnit(7, gbuffer.depth().id());
  } else {
    // The frame's attachable depth: the depth test keeps each program to the surfaces or to
    // the background, and llvmpipe skips the other's pixels before shading them.
    glNamedFramebufferTexture(target_.id(), GL_DEPTH_ATTACHMENT, attachable_depth.id(), 0);
    target_.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
  }
  glBindTextureUnit(0, gbuffer.depth().id());
  glBindTextureUnit(1, gbuffer.colour(1).id());
  glBindImageTexture(0, tile_.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8I);
  if (marks_) glBindImageTexture(3, marks_.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RG8I);
  for (const Program* p : {&tiles_, &tiles_background_}) {
    p->use();
    p->set("u_viewport", glm::vec2(width, height));
    p->set("u_ndc_per_pixel", glm::vec2(2.0 / width, 2.0 / height));
    p->set("u_texels_per_pixel", texels_per_pixel_);
    p->set("u_patch_pixels", static_cast<float>(canvas_.patch * o.radius));
    p->set("u_dome", glm::vec4(glm::vec3(dome_centre_), static_cast<float>(dome_radius_)));
    p->set("u_eye", glm::vec3(camera.eye()));
    p->set("u_seed", seed_);
    p->set("u_tile_scale", static_cast<float>(kTileRange / 127.0));
    p->set("u_tile_mask", tile_size_ - 1);
    p->set("u_tile_shift", std::countr_zero(static_cast<unsigned>(tile_size_)));
    setMarks(*p, height, canvas_.patch * o.radius);
    p->set("u_mottle_texels", 1.0f / mottle_cell);
    if (compute_) {
      dispatchPixels(*p, {0, 0, width, height});
    } else {
      glDepthFunc(p == &tiles_ ? GL_GREATER : GL_EQUAL);  // the triangle lies at depth 1: surfaces, then the background
      glDrawArrays(GL_TRIANGLES, 0, 3);
    }
  }
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

float CanvasPass::drawMottle(const OrbitCamera& camera, int width, int height) {
  // One texel per cell of `mottle_cell` pixels at 1024 high (at least one pixel), holding
  // the value at the cell's centre.
  const float cell = std::max(1.0f, static_cast<float>(canvas_.mottle_cell * height / 1024.0));
  const int columns = static_cast<int>(std::ceil(width / cell)), rows = static_cast<int>(std::ceil(height / cell));
  if (mottle_target_.width() != columns || mottle_target_.height() != rows) {
    mottle_target_ = Framebuffer(columns, rows, {GL_R32F}, false);
  }
  mottle_target_.bind();
  mottle_.use();
  mottle_.set("u_viewport", glm::vec2(width, height));
  mottle_.set("u_cell", cell);
  mottle_.set("u_dome", glm::vec4(glm::vec3(dome_centre_), static_cast<float>(dome_radius_)));
  mottle_.set("u_eye", glm::vec3(camera.eye()));
  mottle_.set("u_seed", seed_);
  mottle_.set("u_mottle", glm::vec2(canvas_.mottle, kMottlePixels * height / 1024.0));
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindImageTexture(1, mottle_target_.colour(0).id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  return cell;
}

double CanvasPass::markTexelsPerPixel(int size, double half_length, double half_width, double spot_radius) {
  // The farthest a mark reaches from its point: the centre's offset (up to half a mean
  // half length on each axis), the longest half length (1.4 means) and the widest half
  // width, or the largest spot; and a pixel for the edges' ramps.
  const double offset = 0.5 * std::numbers::sqrt2 * half_length;
  const double reach = offset + std::max(1.4 * half_length + 1.4 * half_width, spot_radius) + 1.0;
  return size / (2.0 * reach);
}

std::vector<float> CanvasPass::markSprite(int variant, int size, double texels_per_pixel, double half_length,
                                          double half_width, double spot_radius) {
  // Eight numbers in [0, 1] from the variant's hash: u places the centre and turns the
  // fibre, v sets its length, bend, width and whether it darkens (three in four) or lightens.
  const std::uint32_t seed = noise::noiseHash(static_cast<std::uint32_t>(variant) * 0x9E3779B1u + 0x3C6EF372u);
  double u[4], v[4];
  for (std::uint32_t k = 0; k < 4; ++k) {
    u[k] = (noise::noiseStream(seed, k) >> 8) / 16777216.0;
    v[k] = (noise::noiseStream(seed, 4 + k) >> 8) / 16777216.0;
  }
  const double cx = (u[0] - 0.5) * half_length, cy = (u[1] - 0.5) * half_length;
  double ax = u[2] - 0.5 + 1e-3, ay = u[3] - 0.5 + 1e-3;
  const double norm = std::hypot(ax, ay);
  ax /= norm, ay /= norm;
  const double length = half_length * (0.6 + 0.8 * v[0]), width = half_width * (0.6 + 0.8 * v[2]);
  const double sign = v[3] < 0.75 ? -1.0 : 0.6;
  const double radius = (0.2 + 0.8 * v[0] * v[0]) * spot_radius;
  auto smooth = [](double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3 - 2 * t);
  };
  std::vector<float> out(2 * static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // The texel's centre, pixels from the point's projection, less the mark's centre.
      const double qx = (x + 0.5 - size / 2) / texels_per_pixel - cx, qy = (y + 0.5 - size / 2) / texels_per_pixel - cy;
      const double s = (qx * ax + qy * ay) / length;  // −1 … 1 along the fibre
      const double across = (-qx * ay + qy * ax - (v[1] - 0.5) * 0.4 * length * (1 - s * s)) / width;
      const double fibre = std::max(1 - across * across, 0.0) * (1 - smooth(0.5, 1.0, std::abs(s)));
      const double spot = 1 - smooth(radius - 0.5, radius + 0.5, std::hypot(qx, qy));
      const std::size_t at = 2 * (static_cast<std::size_t>(y) * size + x);
      out[at] = static_cast<float>(sign * fibre);
      out[at + 1] = static_cast<float>(spot);
    }
  return out;
}

CanvasPass::MarkSizes CanvasPass::markSizes(double fibre_length, int height) {
  // Lengths are pixels at 1024 high; widths and spots no thinner than at 512.
  const double scale = height / 1024.0;
  return {0.5 * fibre_length * scale, 0.9 * std::max(scale, 0.5), 2.0 * std::max(scale, 0.5)};
}

void CanvasPass::updateMarkSprites(int height) {
  const auto [half_length, half_width, spot_radius] = markSizes(canvas_.fibre_length, height);
  const std::array<double, 3> key{half_length, half_width, spot_radius};
  if (key == marks_key_) return;
  mark_texels_ = markTexelsPerPixel(kMarkSprite, half_length, half_width, spot_radius);
  const std::size_t texels = static_cast<std::size_t>(kMarkSprite) * kMarkSprite;
  std::vector<std::int8_t> bytes(2 * texels * kMarkVariants);
  for (int variant = 0; variant < kMarkVariants; ++variant) {
    const std::vector<float> sprite =
        markSprite(variant, kMarkSprite, mark_texels_, half_length, half_width, spot_radius);
    for (std::size_t i = 0; i < sprite.size(); ++i) {
      bytes[2 * texels * variant + i] = static_cast<std::int8_t>(std::lround(127 * std::clamp(sprite[i], -1.0f, 1.0f)));
    }
  }
  mark_bytes_ = Buffer::create();
  glNamedBufferStorage(mark_bytes_.id(), static_cast<GLsizeiptr>(bytes.size()), bytes.data(), 0);
  marks_ = BufferTexture::create();
  glTextureBuffer(marks_.id(), GL_RG8I, mark_bytes_.id());
  SHANSHUI_GL_CHECK("canvas mark sprites");
  marks_key_ = key;
}

void CanvasPass::setMarks(const Program& p, int height, double lattice_pixels) const {
  // Fibres and spots hang on lattice points, and a point's chance of one is the density per
  // 100² pixels (at 1024 high) times the screen area its marks cover: the shader scales it
  // by that area in lattice spacings² (`lattice_pixels` apart on screen); kMarkRegion is the
  // area for one spacing², measured on a plane facing the camera
  // (CanvasGl.RicePaperIsQuietPaperWithFibresAndSpots). Their shapes are the sprites'.
  const double scale = height / 1024.0;
  const double per_point = (lattice_pixels / (100 * scale)) * (lattice_pixels / (100 * scale)) * kMarkRegion;
  p.set("u_mark_chance", glm::vec2(canvas_.fibres * per_point, canvas_.spots * per_point));
  p.set("u_mark_contrast", glm::vec2(canvas_.fibre_contrast, 0.35));
  p.set("u_mark_texels", static_cast<float>(mark_texels_));
  p.set("u_mark_sprite", kMarkSprite);
  p.set("u_mark_variants", kMarkVariants);
}

void CanvasPass::runSplat(const std::vector<Item>& items, const Texture2D& depth, const OrbitCamera& camera, int width,
                          int height, const noise::CanvasNoiseOptions& o) {
  // The kernels are summed in floats (the reference canvas, hundreds of kernels a pixel),
  // then copied into the half-float target.
  if (splat_sums_.width() != width || splat_sums_.height() != height) {
    splat_sums_ = Framebuffer(width, height, {GL_RG32F}, false);
  }
  splat_sums_.bind();
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // GL reads four components whatever the format
  glClearNamedFramebufferfv(splat_sums_.id(), GL_COLOR, 0, zero);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_CLAMP);  // the dome lies beyond the far plane
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  // The geometry shader reads the G-buffer's depth. GL orders rendering before sampling
  // without one, but llvmpipe runs geometry shaders while the previous pass may still be
  // rasterising, and kernels then vanish at random; the barrier makes it wait (cheap
  // elsewhere).
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  glBindTextureUnit(0, depth.id());
  const double aspect = static_cast<double>(width) / height;
  const glm::dmat4 view_projection = glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view());
  const double pixels_per_unit_at_1 = 0.5 * height / std::tan(glm::radians(camera.fov_y_deg) * 0.5);
  const double density = o.impulses / (std::numbers::pi * o.radius * o.radius);
  for (const Program* p : {&single_, &multi_}) {
    setKernel(*p, o);
    p->set("u_viewport", glm::vec2(width, height));
    p->set("u_radius", static_cast<float>(o.radius));
  }
  for (const Item& item : items) {
    // One invocation is enough when no triangle can need more kernels than it emits: the
    // largest triangle, facing the camera at the nearest point of the mesh's bounds.
    const glm::dvec3 centre(item.model * glm::dvec4(0, 0, 0, 1));
    const double scale2 = std::pow(std::abs(glm::determinant(glm::dmat3(item.model))), 2.0 / 3.0);
    const double nearest = std::max(glm::length(camera.eye() - centre) - item.radius, camera.near_plane);
    const double worst = density * item.max_triangle_area * scale2 * std::pow(pixels_per_unit_at_1 / nearest, 2);
    const Program& p = worst <= quads_ ? single_ : multi_;
    p.use();
    p.set("u_model_view_projection", glm::mat4(view_projection * item.model));
    p.set("u_background", 0);
    item.mesh->draw();
  }
  const glm::dmat4 dome_mvp = view_projection * glm::translate(glm::dmat4(1.0), dome_centre_);
  if (const GLsizei indices = uploadVisibleDome(dome_mvp)) {
    multi_.use();
    multi_.set("u_model_view_projection", glm::mat4(dome_mvp));
    multi_.set("u_background", 1);
    glBindVertexArray(dome_vao_.id());
    glDrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_CLAMP);
  glBlitNamedFramebuffer(splat_sums_.id(), target_.id(), 0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT,
                         GL_NEAREST);
}

}  // namespace shanshui::render

namespace shanshui::render {

namespace {

// The canvas in the renderer's pass list.
class CanvasStage final : public RenderPass {
 public:
  explicit CanvasStage(const PassSetup& setup)
      : canvas_(setup.scene.canvas, setup.scene.seed, setup.world_bounds, setup.objects.size()) {}
  std::string name() const override { return canvas_.passName(); }
  void buildPrograms() override { canvas_.reloadShaders(); }
  std::vector<std::string> variants() const override { return canvas_.variants(); }
  void setScene(const scene::Scene& s) override { canvas_.setParams(s.canvas, s.seed); }
  void resize(int, int) override {}  // the canvas sizes its target on each run
  void run(const FrameInputs& in, FrameImages& images) override {
    std::vector<CanvasPass::Item> items;
    for (std::size_t i = 0; i < in.objects.size(); ++i) {
      const SceneObjectGpu& g = in.objects[i];
      items.push_back({&g.mesh, in.modelAt(i), g.max_triangle_area, 0.5 * glm::length(g.model_bounds.size())});
    }
    images.canvas =
        &canvas_.run(items, *images.gbuffer, *images.attachable_depth, in.camera, in.width, in.height, in.timer);
  }
  const Framebuffer* target() const override { return &canvas_.target(); }
  const CanvasPass& canvas() const { return canvas_; }

 private:
  CanvasPass canvas_;
};

}  // namespace

std::string canvasStructure(const scene::Scene& s) {
  return std::to_string(static_cast<int>(s.canvas.type)) + std::to_string(static_cast<int>(s.canvas.pattern())) +
         std::to_string(static_cast<int>(s.canvas.method)) + (s.canvas.hasFibresOrSpots() ? "f" : "") +
         (s.canvas.hasMottle() ? "m" : "") + (s.canvas.grainOnSurface() ? "z" : "");
}

std::unique_ptr<RenderPass> makeCanvasPass(const PassSetup& setup) {
  return std::make_unique<CanvasStage>(setup);
}

const CanvasPass* canvasOf(const RenderPass& pass) {
  const auto* stage = dynamic_cast<const CanvasStage*>(&pass);
  return stage ? &stage->canvas() : nullptr;
}

}  // namespace shanshui::render
