// The edges pass (issue 25; seed 003 §4.2): where a wash ends — another object, a jump in
// depth, the edge of a cast shadow — its pigment is denser, and the edges wander with a
// smooth noise (shaders/edges/edge_darkening.frag). Built when edges.enabled, after the pigment
// and shadow washes it darkens.
#include "shanshui/core/error.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {
namespace {

std::vector<std::string> edgeDefines(const scene::Scene& s) {
  if (s.usesShadow()) return {"SHADOW"};
  return {};
}

class EdgesPass final : public RenderPass {
 public:
  explicit EdgesPass(const PassSetup& setup) : defines_(edgeDefines(setup.scene)), vao_(VertexArray::create()) {
    buildPrograms();
  }

  std::string name() const override { return "edges"; }
  void buildPrograms() override {
    const bool compute = pixelPassesAsCompute();
    program_ = pixelProgram("edge_darkening.frag", defines_, compute);
    compute_ = compute;
  }
  std::vector<std::string> variants() const override { return {joined(defines_)}; }

  void setScene(const scene::Scene& s) override {
    if (seed_ != s.seed) {
      noise_ = Texture2D::tiledFromImage(noise::erosionNoise(256, s.seed ^ 0xED6Eull), GL_RG8, GL_LINEAR_MIPMAP_LINEAR);
      seed_ = s.seed;
    }
  }

  void resize(int width, int height) override { target_ = Framebuffer(width, height, {GL_RGBA8}, false); }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    if (in.timer) in.timer->begin("edges");
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_.id());
    program_.use();
    glBindTextureUnit(0, images.picture->id());
    glBindTextureUnit(1, images.gbuffer->colour(1).id());
    glBindTextureUnit(2, images.gbuffer->depth().id());
    glBindTextureUnit(3, noise_->id());
    if (!defines_.empty()) {
      SHANSHUI_CHECK(images.shadow != nullptr);
      glBindTextureUnit(4, images.shadow->id());
    }
    const scene::EdgeParams& e = in.scene.edges;
    const double px = in.height / 1024.0;
    program_.set("u_strength", static_cast<float>(e.strength));
    program_.set("u_radius", static_cast<float>(e.radius * px));
    program_.set("u_samples", e.samples);
    program_.set("u_wobble", static_cast<float>(e.wobble * px));
    program_.set("u_wobble_scale", static_cast<float>(std::max(e.wobble_scale * px, 1e-3)));
    shadePixels(program_, compute_, target_, {GL_RGBA8}, in.drawn());
    SHANSHUI_GL_CHECK("edges pass");
    images.picture = &target_.colour();
    if (in.timer) in.timer->end();
  }

 private:
  std::vector<std::string> defines_;
  Program program_;
  bool compute_ = false;  //!< program_ is a compute shader (pixelPassesAsCompute)
  VertexArray vao_;
  std::optional<Texture2D> noise_;
  std::optional<std::uint64_t> seed_;
  Framebuffer target_;
};

}  // namespace

std::unique_ptr<RenderPass> makeEdgesPass(const PassSetup& setup) {
  return std::make_unique<EdgesPass>(setup);
}

std::string edgesStructure(const scene::Scene& s) {
  return joined(edgeDefines(s));
}

}  // namespace shanshui::render
