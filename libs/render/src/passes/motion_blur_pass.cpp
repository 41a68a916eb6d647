// The motion blur pass (issue 26; seed 004): the G-buffer's velocity target (its VELOCITY
// variant, built only with motion blur) says how far each surface moved on screen since the
// previous frame; behind whatever moves, paint is dragged over the picture
// (shaders/motion_blur/motion_blur.frag has the equations and how the seed's garbled ones are read).
// Where to look for what passed over a pixel comes from the fastest velocity per 16 px tile
// and within reach of each tile (shaders/motion_blur/motion_blur_tiles.frag).
#include <algorithm>
#include <cmath>

#include "shanshui/core/error.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {
namespace {

// The farthest any point of the scene moved on screen in one interval, in pixels: the
// corners of each object's bounds now and an interval ago, each through its camera.
double fastestPixels(const FrameInputs& in) {
  const glm::dmat4 now = glm::dmat4(in.viewProjection()), before = in.previousViewProjection();
  const double dt = in.scene.motion_blur.interval;
  double fastest = 0.0;
  auto pixel = [&](const glm::dmat4& m, glm::dvec3 p) {
    const glm::dvec4 c = m * glm::dvec4(p, 1.0);
    return glm::dvec2(c) / std::max(std::abs(c.w), 1e-12) * 0.5 * glm::dvec2(in.width, in.height);
  };
  for (std::size_t i = 0; i < in.objects.size(); ++i) {
    const mesh::Bounds& b = in.objects[i].model_bounds;
    const glm::dvec3 half = 0.5 * b.size();
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner((c & 1 ? 1 : -1) * half.x, (c & 2 ? 1 : -1) * half.y, (c & 4 ? 1 : -1) * half.z);
      const glm::dvec3 a = glm::dvec3(in.modelAt(i) * glm::dvec4(corner, 1.0));
      const glm::dvec3 z = glm::dvec3(in.modelAt(i, in.time - dt) * glm::dvec4(corner, 1.0));
      fastest = std::max(fastest, glm::length(pixel(now, a) - pixel(before, z)));
    }
  }
  return fastest;
}

class MotionBlurPass final : public RenderPass {
 public:
  explicit MotionBlurPass(const PassSetup& setup)
      : from_canvas_(setup.scene.canvas.type != scene::CanvasType::None), vao_(VertexArray::create()) {
    buildPrograms();
  }

  std::string name() const override { return "motion_blur"; }
  void buildPrograms() override {
    const bool compute = pixelPassesAsCompute();
    Program tiles = pixelProgram("motion_blur_tiles.frag", {}, compute);
    Program neighbours = pixelProgram("motion_blur_tiles.frag", {"NEIGHBOURS"}, compute);
    program_ = pixelProgram("motion_blur.frag",
                            from_canvas_ ? std::vector<std::string>{"CANVAS"} : std::vector<std::string>{}, compute);
    compute_ = compute;
    tiles_program_ = std::move(tiles);
    neighbours_program_ = std::move(neighbours);
  }
  std::vector<std::string> variants() const override { return {from_canvas_ ? "CANVAS" : ""}; }

  void setScene(const scene::Scene& s) override {
    if (!from_canvas_ && seed_ != s.seed) {
      noise_ = Texture2D::fromImage(noise::erosionNoise(256, s.seed ^ 0x9A9E5ull), GL_RG8);
      seed_ = s.seed;
    }
  }

  void resize(int width, int height) override {
    target_ = Framebuffer(width, height, {GL_RGBA8}, false);
    const int tw = (width + kTile - 1) / kTile, th = (height + kTile - 1) / kTile;
    tile_max_ = Framebuffer(tw, th, {GL_RGBA16F}, false);
    neighbour_max_ = Framebuffer(tw, th, {GL_RGBA16F}, false);
  }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    if (in.timer) in.timer->begin("motion_blur");
    const scene::MotionBlurParams& m = in.scene.motion_blur;
    // The longest trail: how far from a pixel the surface that passed over it can be now.
    const double reach = std::clamp(m.length * fastestPixels(in), 0.0, kMaxReachTiles * kTile);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    if (reach < 0.5) {  // nothing moves: the picture as it is
      glCopyImageSubData(images.picture->id(), GL_TEXTURE_2D, 0, 0, 0, 0, target_.colour().id(), GL_TEXTURE_2D, 0, 0, 0,
                         0, in.width, in.height, 1);
    } else {
      glBindVertexArray(vao_.id());
      // The fastest motion per tile, then within reach of each tile: every tile, whatever
      // region the frame redraws (the scissor is in the picture's pixels, not the tiles').
      glDisable(GL_SCISSOR_TEST);
      const glm::ivec4 tiles(0, 0, tile_max_.width(), tile_max_.height());
      tiles_program_.use();
      glBindTextureUnit(0, images.gbuffer->colour(2).id());
      tiles_program_.set("u_tile", kTile);
      shadePixels(tiles_program_, compute_, tile_max_, {GL_RGBA16F}, tiles);
      neighbours_program_.use();
      glBindTextureUnit(0, tile_max_.colour().id());
      neighbours_program_.set("u_radius", static_cast<int>(std::ceil(reach / kTile)));
      shadePixels(neighbours_program_, compute_, neighbour_max_, {GL_RGBA16F}, tiles);
      if (in.region) glEnable(GL_SCISSOR_TEST);
      program_.use();
      glBindTextureUnit(0, images.picture->id());
      glBindTextureUnit(1, images.gbuffer->colour(2).id());
      glBindTextureUnit(2, from_canvas_ ? images.canvas->id() : noise_->id());
      glBindTextureUnit(3, neighbour_max_.colour().id());
      program_.set("u_tile", kTile);
      program_.set("u_length", static_cast<float>(m.length));
      program_.set("u_paint", static_cast<float>(m.paint));
      program_.set("u_water", static_cast<float>(m.water));
      program_.set("u_bristles", static_cast<float>(m.bristles));
      program_.set("u_bristle_px", static_cast<float>(std::max(1.0, 3.0 * in.height / 1024.0)));
      program_.set("u_granulation", static_cast<float>(m.granulation));
      shadePixels(program_, compute_, target_, {GL_RGBA8}, in.drawn());
    }
    SHANSHUI_GL_CHECK("motion blur pass");
    images.picture = &target_.colour();
    if (in.timer) in.timer->end();
  }

 private:
  static constexpr int kTile = 16;              //!< pixels per side of a velocity tile
  static constexpr double kMaxReachTiles = 16;  //!< longest trail, in tiles (256 px)
  bool from_canvas_;
  Program program_, tiles_program_, neighbours_program_;
  bool compute_ = false;  //!< the three are compute shaders (pixelPassesAsCompute)
  VertexArray vao_;
  std::optional<Texture2D> noise_;
  std::optional<std::uint64_t> seed_;
  Framebuffer target_, tile_max_, neighbour_max_;
};

}  // namespace

std::unique_ptr<RenderPass> makeMotionBlurPass(const PassSetup& setup) {
  return std::make_unique<MotionBlurPass>(setup);
}

}  // namespace shanshui::render
