// The substrate pass (issue 25; seed 000): the paper's relief — a scanned paper when the
// scene names one, the canvas's grain when it has a canvas, else a tile of value noise — acts on the finished picture:
// dry brush, granulation, lighting and distortion (shaders/substrate/substrate.frag has the equations). Built when
// substrate.enabled; last in the list, on the dried paint.
#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/image/convert.h"
#include "shanshui/image/image_io.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {
namespace {

class SubstratePass final : public RenderPass {
 public:
  explicit SubstratePass(const PassSetup& setup)
      : from_canvas_(setup.scene.substrate.texture.empty() && setup.scene.canvas.type != scene::CanvasType::None),
        vao_(VertexArray::create()),
        weights_(Buffer::create()) {
    if (!setup.scene.substrate.texture.empty()) {
      // A scan of paper: its grey is the height, stretched to [0, 1] so that any scan's
      // exposure gives the same relief depth (roughness scales it).
      image::Image grey = image::toGrey(image::loadImage(setup.scene.resolve(setup.scene.substrate.texture)));
      const auto [lo, hi] = std::minmax_element(grey.pixels.begin(), grey.pixels.end());
      const float low = *lo, span = std::max(*hi - *lo, 1e-6f);
      for (float& v : grey.pixels) v = (v - low) / span;
      height_ = Texture2D::fromImage(grey, GL_R16);
    }
    glCreateSamplers(1, &sampler_);
    glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    buildPrograms();
  }
  ~SubstratePass() override {
    if (!memoryRanOut()) glDeleteSamplers(1, &sampler_);  // see memoryRanOut()
  }
  SubstratePass(const SubstratePass&) = delete;
  SubstratePass& operator=(const SubstratePass&) = delete;

  std::string name() const override { return "substrate"; }
  void buildPrograms() override {
    const bool compute = pixelPassesAsCompute();
    program_ = pixelProgram("substrate.frag",
                            from_canvas_ ? std::vector<std::string>{"CANVAS"} : std::vector<std::string>{}, compute);
    compute_ = compute;
  }
  std::vector<std::string> variants() const override { return {from_canvas_ ? "CANVAS" : ""}; }

  void setScene(const scene::Scene& s) override {
    std::vector<glm::vec4> w;
    for (const scene::Object& o : s.objects) {
      const scene::SubstrateWeights& k = o.substrate;
      w.emplace_back(static_cast<float>(k.dry_brush), static_cast<float>(k.granulation), static_cast<float>(k.lighting),
                     static_cast<float>(k.distortion));
    }
    glNamedBufferData(weights_.id(), static_cast<GLsizeiptr>(w.size() * sizeof(glm::vec4)), w.data(), GL_STATIC_DRAW);
    if (!from_canvas_ && !height_ && seed_ != s.seed) {
      noise_ = Texture2D::fromImage(noise::erosionNoise(256, s.seed ^ 0x9A9E5ull), GL_RG8);
      seed_ = s.seed;
    }
  }

  void resize(int width, int height) override { target_ = Framebuffer(width, height, {GL_RGBA8}, false); }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    SHANSHUI_CHECK(!from_canvas_ || images.canvas != nullptr);
    if (in.timer) in.timer->begin("substrate");
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_.id());
    program_.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, weights_.id());
    glBindTextureUnit(0, images.picture->id());
    glBindSampler(0, sampler_);
    glBindTextureUnit(1, from_canvas_ ? images.canvas->id() : height_ ? height_->id() : noise_->id());
    glBindTextureUnit(2, images.gbuffer->colour(1).id());
    glBindTextureUnit(3, images.gbuffer->depth().id());
    const scene::SubstrateParams& p = in.scene.substrate;
    const glm::dvec3 light = glm::dmat3(in.camera.view()) * glm::normalize(in.scene.light.direction);
    program_.set("u_light", glm::vec3(light));
    program_.set("u_roughness", static_cast<float>(p.roughness));
    program_.set("u_dry_brush", static_cast<float>(p.dry_brush));
    program_.set("u_dry_edge", static_cast<float>(p.dry_edge));
    program_.set("u_granulation", static_cast<float>(p.granulation));
    program_.set("u_lighting", static_cast<float>(p.lighting));
    program_.set("u_distortion", static_cast<float>(p.distortion * in.height / 1024.0));
    shadePixels(program_, compute_, target_, {GL_RGBA8}, in.drawn());
    glBindSampler(0, 0);
    SHANSHUI_GL_CHECK("substrate pass");
    images.picture = &target_.colour();
    if (in.timer) in.timer->end();
  }

 private:
  bool from_canvas_;
  Program program_;
  bool compute_ = false;  //!< program_ is a compute shader (pixelPassesAsCompute)
  VertexArray vao_;
  Buffer weights_;
  GLuint sampler_ = 0;
  std::optional<Texture2D> noise_;
  std::optional<Texture2D> height_;  //!< from the scanned paper
  std::optional<std::uint64_t> seed_;
  Framebuffer target_;
};

}  // namespace

std::unique_ptr<RenderPass> makeSubstratePass(const PassSetup& setup) {
  return std::make_unique<SubstratePass>(setup);
}

}  // namespace shanshui::render
