#include "shanshui/render/ink_diffusion_pass.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shanshui/core/error.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"

namespace shanshui::render {

namespace {

void bindImage(GLuint unit, const Texture2D& t, GLenum access) {
  glBindImageTexture(unit, t.id(), 0, GL_FALSE, 0, access, t.format());
}

// Image stores made visible to the next dispatch, texel fetches and image copies.
void barrier() {
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

GLuint groups(int n, int size) {
  return static_cast<GLuint>((n + size - 1) / size);
}

// The ink and the capacity are packed two pixels to an RG32F texel, pixel x in channel
// x & 1 of texel x / 2: on llvmpipe a two-channel image load costs what a one-channel one
// does, so the boundary iterations read half the texels. The unused half of the last
// texel of an odd width holds 0 (no ink, no capacity: absent).
int packedWidth(int width) {
  return (width + 1) / 2;
}

// The boundary iterations' work groups (shaders/ink_diffusion/ink_diffusion_boundary.comp): 8
// invocations of kBlock columns each, walking kStripRows rows — an area of 64 × 16 pixels.
// Wider blocks and taller strips reload fewer neighbours ((kBlock + 6) / kBlock texel reads
// per pixel, (kStripRows + 6) / kStripRows rows) but hold more registers, give fewer work
// groups and coarser areas to leave out. On llvmpipe (1024², five iterations over ink
// everywhere, 15 alternating runs each) 8 columns cost half what 2 or 4 do with the ink
// packed two pixels to a texel, while with one pixel to a texel 8 and 2 cost the same.
//
// On a GPU (pixelPassesAsCompute) the same area is 32 invocations of 2 columns: 8-invocation
// groups leave three quarters of a 32-wide warp idle, and a GPU has the threads to spare.
// Each pixel's arithmetic is the same, in the same order, so the ink is the same to the bit.
constexpr int kBlock = 8;
constexpr int kGroupInvocations = 8;
constexpr int kGpuBlock = 2;
constexpr int kGpuGroupInvocations = 32;
constexpr int kAreaWidth = kBlock * kGroupInvocations;
static_assert(kGpuBlock * kGpuGroupInvocations == kAreaWidth, "both layouts share the work-group area");
constexpr int kStripRows = 16;
// The extraction marks ink above the residual and strokes per block of kMarkBlock²
// pixels: a boundary work group runs only if a block with ink lies within n + d pixels of
// its area, and the main region's sweeps skip blocks no stroke lies within d of.
constexpr int kMarkBlock = 8;
// The columns pass reads f^r from a table: one entry per ring, d ≤ 256 (ink::validate).
constexpr int kMaxRingSteps = 256;
// The per-pixel passes (extraction, output) and the row and column sweeps: one invocation
// per pair of columns (or per row), this many to a work group.
constexpr int kLineGroup = 64;
// On a GPU the main region for d up to this is one gather (ink_diffusion_rings.comp) instead
// of the row and column sweeps, which give a whole row or column to one invocation: 1024
// rows and 512 column pairs at 1024², a sliver of a GPU's threads, each walking its line
// end to end.
constexpr int kMaxGatherSteps = 8;
static_assert(kStripRows % kMarkBlock == 0, "the extraction marks whole blocks per strip");

std::vector<std::string> defines(bool gpu, std::vector<std::string> extra = {}) {
  extra.push_back("BLOCK=" + std::to_string(gpu ? kGpuBlock : kBlock));
  extra.push_back("GROUP_INVOCATIONS=" + std::to_string(gpu ? kGpuGroupInvocations : kGroupInvocations));
  extra.push_back("STRIP_ROWS=" + std::to_string(kStripRows));
  extra.push_back("AREA_W=" + std::to_string(kAreaWidth));
  extra.push_back("AREA_H=" + std::to_string(kStripRows));
  extra.push_back("BLOCK_SIZE=" + std::to_string(kMarkBlock));
  extra.push_back("LINE_GROUP=" + std::to_string(kLineGroup));
  return extra;
}

}  // namespace

glm::ivec2 InkDiffusionPass::workGroupArea() {
  return {kAreaWidth, kStripRows};
}

InkDiffusionPass::InkDiffusionPass() : gpu_layout_(pixelPassesAsCompute()) {
  const std::string ring_table = "RING_TABLE=" + std::to_string(kMaxRingSteps + 1);
  extract_ = Program({"ink_diffusion_extract.comp"}, defines(gpu_layout_));
  rows_ = Program({"ink_diffusion_rows.comp"}, defines(gpu_layout_));
  columns_ = Program({"ink_diffusion_columns.comp"}, defines(gpu_layout_, {ring_table}));
  if (gpu_layout_) rings_ = Program({"ink_diffusion_rings.comp"}, defines(gpu_layout_, {ring_table}));
  reach_ = Program({"ink_diffusion_reach.comp"}, defines(gpu_layout_));
  boundary_ = Program({"ink_diffusion_boundary.comp"}, defines(gpu_layout_));
  output_ = Program({"ink_diffusion_output.comp"}, defines(gpu_layout_));
}

void InkDiffusionPass::ensureSize(int width, int height) {
  if (out_.width() == width && out_.height() == height) return;
  for (Texture2D* t : {&capacity_, &main_, &next_}) *t = Texture2D(packedWidth(width), height, GL_RG32F);
  nearest_ = Texture2D(width, height, GL_R32UI);
  const int blocks_x = (width + kMarkBlock - 1) / kMarkBlock, blocks_y = (height + kMarkBlock - 1) / kMarkBlock;
  for (Texture2D* t : {&seeds_, &strokes_, &near_}) *t = Texture2D(blocks_x, blocks_y, GL_R8UI);
  active_tex_ = Texture2D((width + kAreaWidth - 1) / kAreaWidth, (height + kStripRows - 1) / kStripRows, GL_R8UI);
  out_ = Texture2D(width, height, GL_RGBA8);
}

const Texture2D& InkDiffusionPass::run(const Texture2D& colour, const Texture2D& absorbency,
                                       const ink::DiffusionOptions& o, const glm::vec3& paper, GpuTimer* timer) {
  ensureSize(colour.width(), colour.height());
  run(colour, absorbency, o, paper, out_, timer);
  return out_;
}

void InkDiffusionPass::run(const Texture2D& colour, const Texture2D& absorbency, const ink::DiffusionOptions& o,
                           const glm::vec3& paper, const Texture2D& output, GpuTimer* timer) {
  run(colour, PaperTexture{&absorbency}, o, paper, output, timer);
}

int InkDiffusionPass::dependence(const ink::DiffusionOptions& o) {
  // The main region takes a ring's ink from strokes within d. An iteration's new ink at a
  // pixel comes from its neighbours' supplies, a supply depends on the demands of the
  // donor's neighbours, and a demand on the excess around the receiver: three pixels.
  return o.ring_steps + 3 * o.iterations;
}

void InkDiffusionPass::run(const Texture2D& colour, const PaperTexture& texture, const ink::DiffusionOptions& o,
                           const glm::vec3& paper, const Texture2D& output, GpuTimer* timer, const glm::ivec4* region) {
  ink::validate(o);
  SHANSHUI_CHECK(texture.absorbency != nullptr);
  const int w = colour.width(), h = colour.height();
  // Read and written as images, which fixes their formats.
  SHANSHUI_CHECK_EQ(colour.format(), static_cast<GLenum>(GL_RGBA8));
  SHANSHUI_CHECK(output.width() == w && output.height() == h && output.format() == GL_RGBA8);
  SHANSHUI_CHECK(!texture.grain || texture.grain->format() == GL_RG16F);
  ensureSize(w, h);
  if (timer) timer->begin("diffusion");
  // The window the passes compute: the whole picture, or the region grown by how far the
  // result depends on the picture, on whole work-group areas. Everything this run reads
  // outside the window (the ink and capacity images) only moves results within that
  // distance of its edge, which are not written; the block marks outside it are still the
  // last runs' marks of a picture unchanged there.
  const glm::ivec2 area(kAreaWidth, kStripRows);
  glm::ivec2 lo(0), hi(w, h);
  glm::ivec4 store(0, 0, w, h);
  if (region) {
    store = glm::ivec4(glm::clamp(glm::ivec2(*region), glm::ivec2(0), glm::ivec2(w, h)),
                       glm::clamp(glm::ivec2(region->z, region->w), glm::ivec2(0), glm::ivec2(w, h)));
    const int margin = dependence(o);
    lo = glm::max(glm::ivec2(store) - margin, glm::ivec2(0)) / area * area;
    hi = glm::min((glm::ivec2(store.z, store.w) + margin + area - 1) / area * area, glm::ivec2(w, h));
  }
  last_window_ = glm::ivec4(lo, hi);
  if (store.z <= store.x || store.w <= store.y) {
    if (timer) timer->end();
    return;
  }
  const glm::ivec2 size = hi - lo;
  const glm::ivec2 blocks_lo = lo / kMarkBlock, blocks_hi = (hi + kMarkBlock - 1) / kMarkBlock;
  const auto window = [&](const Program& p) {
    p.set("u_lo", lo);
    p.set("u_hi", hi);
  };
  // Per-pixel passes: an invocation per pair of columns and kStripRows rows.
  const GLuint sx = groups(packedWidth(size.x), kLineGroup), sy = groups(size.y, kStripRows);

  // The ink goes straight into main_, which the main region then raises; the marks of ink
  // above the residual and of strokes per block go into seeds_ and strokes_.
  const GLubyte zero = 0;
  for (const Texture2D* marks : {&seeds_, &strokes_})
    glClearTexSubImage(marks->id(), 0, blocks_lo.x, blocks_lo.y, 0, blocks_hi.x - blocks_lo.x,
                       blocks_hi.y - blocks_lo.y, 1, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
  extract_.use();
  window(extract_);
  extract_.set("u_paper", paper);
  extract_.set("u_absorbency_map", texture.absorbency_map);
  extract_.set("u_absorb", static_cast<float>(o.iterations > 0 ? o.absorb / o.iterations : 0.0));
  extract_.set("u_threshold", static_cast<float>(o.threshold));
  extract_.set("u_residual", static_cast<float>(o.residual));
  glBindTextureUnit(1, texture.absorbency->id());
  bindImage(0, main_, GL_WRITE_ONLY);
  bindImage(1, capacity_, GL_WRITE_ONLY);
  bindImage(2, colour, GL_READ_ONLY);
  bindImage(3, seeds_, GL_WRITE_ONLY);
  bindImage(4, strokes_, GL_WRITE_ONLY);
  glDispatchCompute(sx, sy, 1);
  barrier();

  // f^r for r = 0 … d, the rings' ink.
  const auto setRingInk = [&](const Program& p) {
    std::vector<float> ring_ink(static_cast<std::size_t>(o.ring_steps) + 1);
    for (int r = 0; r <= o.ring_steps; ++r) ring_ink[r] = static_cast<float>(std::pow(o.attenuation, r));
    glProgramUniform1fv(p.id(), p.location("u_ring_ink"), o.ring_steps + 1, ring_ink.data());
  };
  if (o.ring_steps > 0 && gpu_layout_ && o.ring_steps <= kMaxGatherSteps) {
    // Main region on a GPU: one gather, into the other image, which then becomes main_.
    rings_.use();
    window(rings_);
    rings_.set("u_threshold", static_cast<float>(o.threshold));
    rings_.set("u_ring_steps", o.ring_steps);
    setRingInk(rings_);
    bindImage(0, main_, GL_READ_ONLY);
    bindImage(2, next_, GL_WRITE_ONLY);
    glDispatchCompute(groups(packedWidth(hi.x) - lo.x / 2, 8), groups(size.y, 8), 1);
    barrier();
    std::swap(main_, next_);
  } else if (o.ring_steps > 0) {
    // Main region (none when d = 0): the blocks within d of a stroke, then rows and columns.
    // Both store only strokes within d over an image cleared to "far" (a fill costs far
    // less than a store per pixel), and the columns raise the extracted ink only where a
    // ring does.
    reach(strokes_, near_, glm::ivec2(kMarkBlock), o.ring_steps, glm::ivec4(blocks_lo, blocks_hi));
    const GLuint far = 0xFFFFFFFFu;  // kFar of shaders/ink_diffusion/ink_diffusion_nearest.glsl
    glClearTexSubImage(nearest_.id(), 0, lo.x, lo.y, 0, size.x, size.y, 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &far);
    rows_.use();
    window(rows_);
    rows_.set("u_threshold", static_cast<float>(o.threshold));
    rows_.set("u_ring_steps", o.ring_steps);
    bindImage(0, main_, GL_READ_ONLY);
    bindImage(1, nearest_, GL_READ_WRITE);
    bindImage(3, near_, GL_READ_ONLY);
    glDispatchCompute(groups(size.y, kLineGroup), 1, 1);
    barrier();
    columns_.use();
    window(columns_);
    columns_.set("u_ring_steps", o.ring_steps);
    setRingInk(columns_);
    bindImage(3, main_, GL_READ_WRITE);
    bindImage(4, near_, GL_READ_ONLY);
    glDispatchCompute(groups(packedWidth(size.x), kLineGroup), 1, 1);
    barrier();
  }
  last_iterations_ = o.iterations;
  // The areas where anything can change: ink above the residual lies within d of a marked
  // block (a ring lies within d of its stroke, and holds no more ink than it) and moves
  // one pixel per iteration; rings lie within d of a stroke, which is marked too.
  const glm::ivec2 areas_lo = lo / area, areas_hi = (hi + area - 1) / area;
  reach(seeds_, active_tex_, area, o.iterations + o.ring_steps, glm::ivec4(areas_lo, areas_hi));
  if (o.iterations > 0) {
    // Both ping-pong images start as the main region, so areas left out hold it throughout.
    glCopyImageSubData(main_.id(), GL_TEXTURE_2D, 0, lo.x / 2, lo.y, 0, next_.id(), GL_TEXTURE_2D, 0, lo.x / 2, lo.y, 0,
                       packedWidth(hi.x) - lo.x / 2, size.y, 1);
    barrier();
  }

  // Boundary diffusion: n iterations, ping-pong between main_ and next_.
  Texture2D* cur = &main_;
  Texture2D* nxt = &next_;
  boundary_.use();
  boundary_.set("u_residual", static_cast<float>(o.residual));
  boundary_.set("u_areas_lo", areas_lo);
  bindImage(1, capacity_, GL_READ_ONLY);
  bindImage(3, active_tex_, GL_READ_ONLY);
  for (int it = 0; it < o.iterations; ++it) {
    bindImage(0, *cur, GL_READ_ONLY);
    bindImage(2, *nxt, GL_WRITE_ONLY);
    glDispatchCompute(areas_hi.x - areas_lo.x, areas_hi.y - areas_lo.y, 1);
    barrier();
    std::swap(cur, nxt);
  }
  after_ = cur;

  // With a canvas grain every pixel changes; without one the output starts as the picture
  // and only pixels whose ink changed are written (an image copy costs llvmpipe far less
  // than the stores).
  const Program* out = &output_;
  if (texture.grain) {
    if (!output_canvas_.id()) {
      output_canvas_ = Program({"ink_diffusion_output.comp"}, defines(gpu_layout_, {"CANVAS"}));
    }
    out = &output_canvas_;
    out->set("u_canvas_contrast", texture.contrast);
    bindImage(4, *texture.grain, GL_READ_ONLY);
  } else {
    if (output.id() != colour.id()) {
      glCopyImageSubData(colour.id(), GL_TEXTURE_2D, 0, store.x, store.y, 0, output.id(), GL_TEXTURE_2D, 0, store.x,
                         store.y, 0, store.z - store.x, store.w - store.y, 1);
      barrier();
    }
    bindImage(5, active_tex_, GL_READ_ONLY);
  }
  out->use();
  window(*out);
  out->set("u_store_lo", glm::ivec2(store));
  out->set("u_store_hi", glm::ivec2(store.z, store.w));
  out->set("u_paper", paper);
  bindImage(1, *cur, GL_READ_ONLY);
  bindImage(2, output, GL_WRITE_ONLY);
  bindImage(3, colour, GL_READ_ONLY);
  glDispatchCompute(sx, sy, 1);
  barrier();
  if (timer) timer->end();
  SHANSHUI_GL_CHECK("diffusion pass");
}

void InkDiffusionPass::reach(const Texture2D& marks, const Texture2D& reached, glm::ivec2 area, int pixels,
                             glm::ivec4 window) const {
  reach_.use();
  reach_.set("u_area", area);
  reach_.set("u_reach", pixels);
  reach_.set("u_lo", glm::ivec2(window));
  reach_.set("u_hi", glm::ivec2(window.z, window.w));
  bindImage(0, marks, GL_READ_ONLY);
  bindImage(1, reached, GL_WRITE_ONLY);
  glDispatchCompute(groups(window.z - window.x, 8), groups(window.w - window.y, 8), 1);
  barrier();
}
image::Image InkDiffusionPass::inkAfter() const {
  const image::Image packed = after_->download(2);
  image::Image ink(out_.width(), out_.height(), 1);
  for (int y = 0; y < ink.height; ++y)
    for (int x = 0; x < ink.width; ++x) ink.at(x, y) = packed.at(x / 2, y, x & 1);
  return ink;
}

double InkDiffusionPass::lastActiveFraction() const {
  if (last_iterations_ == 0) return 0.0;
  std::vector<GLubyte> flags(static_cast<std::size_t>(active_tex_.width()) * active_tex_.height());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(active_tex_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, static_cast<GLsizei>(flags.size()),
                    flags.data());
  SHANSHUI_GL_CHECK("diffusion active areas");
  return static_cast<double>(std::count(flags.begin(), flags.end(), GLubyte{1})) / static_cast<double>(flags.size());
}

}  // namespace shanshui::render

namespace shanshui::render {

namespace {

// The diffusion in the renderer's pass list: the picture so far diffused into the paper,
// whose absorbency is the canvas when the scene has one, else value noise.
class DiffusionStage final : public RenderPass {
 public:
  explicit DiffusionStage(const PassSetup& setup)
      : pass_(std::make_unique<InkDiffusionPass>()), has_canvas_(setup.scene.canvas.type != scene::CanvasType::None) {}
  std::string name() const override { return "diffusion"; }
  void buildPrograms() override { pass_ = std::make_unique<InkDiffusionPass>(); }  // the old one stays on a throw
  std::vector<std::string> variants() const override { return {""}; }
  void setScene(const scene::Scene& s) override {
    if (has_canvas_ || seed_ == s.seed) return;
    // Without a canvas the paper's absorbency is value noise in [0.5, 1].
    const image::Image noise = noise::erosionNoise(256, s.seed ^ 0xAB50Bull);
    image::Image a(noise.width, noise.height, 1);
    for (std::size_t i = 0; i < a.pixels.size(); ++i) a.pixels[i] = 0.5f + 0.5f * noise.pixels[2 * i];
    absorbency_ = Texture2D::fromImage(a, GL_R8);
    seed_ = s.seed;
  }
  void resize(int width, int height) override { target_ = Framebuffer(width, height, {GL_RGBA8}, false); }
  void run(const FrameInputs& in, FrameImages& images) override {
    PaperTexture paper{absorbency_ ? &*absorbency_ : nullptr};
    if (has_canvas_) {
      // Absorbency 0.75 + 0.25 · absorbency · noise: the unit-variance canvas keeps most
      // pixels within [0.5, 1] at full strength, like the value noise it replaces.
      paper = {images.canvas, glm::vec2(0.25 * in.scene.canvas.absorbency, 0.75), images.canvas,
               static_cast<float>(in.scene.canvas.contrast)};
    }
    pass_->run(*images.picture, paper, in.scene.diffusion, glm::vec3(in.scene.output.paper), target_.colour(0),
               in.timer, in.region);
    images.picture = &target_.colour(0);
  }
  const Framebuffer* target() const override { return &target_; }
  const Texture2D* absorbency() const { return absorbency_ ? &*absorbency_ : nullptr; }

 private:
  std::unique_ptr<InkDiffusionPass> pass_;
  bool has_canvas_;
  std::optional<Texture2D> absorbency_;
  std::optional<std::uint64_t> seed_;
  Framebuffer target_;
};

}  // namespace

std::unique_ptr<RenderPass> makeDiffusionPass(const PassSetup& setup) {
  return std::make_unique<DiffusionStage>(setup);
}

const Texture2D* absorbencyOf(const RenderPass& pass) {
  const auto* stage = dynamic_cast<const DiffusionStage*>(&pass);
  return stage ? stage->absorbency() : nullptr;
}

}  // namespace shanshui::render
