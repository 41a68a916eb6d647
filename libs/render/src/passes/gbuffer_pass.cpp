// The G-buffer pass: every object's normal and curvature, surface detail (erosion noise,
// for the pigment wash only; wrinkle luma) and object id, and depth. Each object gets the
// program variant its parameters need (SURFACE, WRINKLE, OBJECT_CURVATURE /
// SCREEN_CURVATURE). The ink pass samples the erosion noise itself, once per pixel: here
// it cost a varying and a fetch for every fragment (~6 ms of ~43 at 1024², measured side
// by side), where the lines stage pays ~2 ms for it.
// With spinning objects the static ones are drawn into a cached layer (again only when
// the camera, size or parameters change) and copied under the animated ones each frame.
#include <algorithm>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/noise/value_noise.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

namespace {

std::vector<std::string> objectDefines(const scene::Scene& s, std::size_t i) {
  const scene::Object& o = s.objects[i];
  std::vector<std::string> d;
  if (s.usesPigment()) d.emplace_back("SURFACE");  // the wash's texture layer
  const bool here = o.wrinkled() && !wrinklesInInkPass(s, i);
  if (here) d.emplace_back("WRINKLE");
  if (here && o.wrinkle.mapping == scene::WrinkleMapping::Slope) d.emplace_back("WRINKLE_SLOPE");
  if (o.lines.enabled) d.emplace_back(scene::perVertex(o.lines.curvature) ? "OBJECT_CURVATURE" : "SCREEN_CURVATURE");
  if (s.motion_blur.enabled) d.emplace_back("VELOCITY");
  return d;
}

class GbufferPass final : public RenderPass {
 public:
  explicit GbufferPass(const PassSetup& setup)
      : surface_noise_(setup.scene.usesPigment()),
        animated_(setup.scene.hasAnimation()),
        velocity_(setup.scene.motion_blur.enabled) {
    for (std::size_t i = 0; i < setup.scene.objects.size(); ++i) {
      const std::vector<std::string> defines = objectDefines(setup.scene, i);
      const auto it =
          std::find_if(programs_.begin(), programs_.end(), [&](const Variant& v) { return v.defines == defines; });
      program_of_.push_back(static_cast<int>(it - programs_.begin()));
      if (it == programs_.end()) programs_.push_back({defines, Program()});
    }
    buildPrograms();
  }

  std::string name() const override { return "gbuffer"; }

  void buildPrograms() override {
    std::vector<Program> built;  // all first, so a failure keeps the old ones
    for (const Variant& v : programs_)
      built.emplace_back(std::vector<std::string>{"ink_gbuffer.vert", "ink_gbuffer.frag"}, v.defines);
    for (std::size_t i = 0; i < built.size(); ++i) programs_[i].program = std::move(built[i]);
  }

  std::vector<std::string> variants() const override {
    std::vector<std::string> out;
    for (const Variant& v : programs_) out.push_back(joined(v.defines));
    return out;
  }

  void setScene(const scene::Scene& s) override {
    if (surface_noise_ && seed_ != s.seed) {
      noise_ = erosionNoiseTexture(s.seed);
      seed_ = s.seed;
    }
  }

  void resize(int width, int height) override {
    // Normal and curvature in 16-bit unsigned normalised channels (encoded in
    // shaders/gbuffer/ink_gbuffer.frag): llvmpipe converts to half floats in software, and an
    // RGBA16F target cost ~10 ms more a frame at 1024² (measured side by side).
    // Motion blur adds the velocity (pixels per interval, and 1 where a surface is).
    std::vector<GLenum> formats{GL_RGBA16, GL_RGBA8};
    if (velocity_) formats.push_back(GL_RGBA16F);
    gbuffer_ = Framebuffer(width, height, formats, true);
    attachable_depth_ = Texture2D(width, height, GL_DEPTH_COMPONENT32F);
    if (animated_) static_gbuffer_ = Framebuffer(width, height, formats, true);
    static_key_ = 0;
  }

  void run(const FrameInputs& in, FrameImages& images) override {
    if (!animated_) {
      if (in.timer) in.timer->begin("gbuffer");
      draw(in, gbuffer_, true, Which::All);
      if (in.timer) in.timer->end();
    } else {
      if (in.static_key != static_key_) {
        if (in.timer) in.timer->begin("gbuffer_static");
        draw(in, static_gbuffer_, true, Which::Static);
        if (in.timer) in.timer->end();
        static_key_ = in.static_key;
      }
      if (in.timer) in.timer->begin("gbuffer_animated");
      for (int i = 0; i < (velocity_ ? 3 : 2); ++i) copy(static_gbuffer_.colour(i), gbuffer_.colour(i), in);
      copy(static_gbuffer_.depth(), gbuffer_.depth(), in);
      draw(in, gbuffer_, false, Which::Animated);
      if (in.timer) in.timer->end();
      images.static_gbuffer = &static_gbuffer_;
    }
    // The copy the passes after it attach (canvas, ink pass), in no pass's time: llvmpipe
    // waits for the G-buffer's rasterisation and copies the depth on the CPU (~0.9 ms at
    // 1024x768), which would otherwise count in the next pass's.
    copy(gbuffer_.depth(), attachable_depth_, in);
    if (in.timer) in.timer->gap();
    SHANSHUI_GL_CHECK("gbuffer pass");
    images.gbuffer = &gbuffer_;
    images.attachable_depth = &attachable_depth_;
  }

  const Framebuffer* target() const override { return &gbuffer_; }

 private:
  struct Variant {
    std::vector<std::string> defines;
    Program program;
  };
  enum class Which { All, Static, Animated };

  static void copy(const Texture2D& from, const Texture2D& to, const FrameInputs& in) {
    glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.id(), GL_TEXTURE_2D, 0, 0, 0, 0, in.width, in.height,
                       1);
  }

  void draw(const FrameInputs& in, const Framebuffer& target, bool clear, Which which) const {
    target.bind();
    if (clear) {
      // Only depth: the ink pass reads the colour targets where something was drawn
      // (depth below 1), so clearing them would be wasted bandwidth.
      const float far_depth = 1.0f;
      glClearNamedFramebufferfv(target.id(), GL_DEPTH, 0, &far_depth);
      if (velocity_) {  // the blur reads it everywhere: alpha 0 is "no surface"
        const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearNamedFramebufferfv(target.id(), GL_COLOR, 2, none);
      }
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    for (std::size_t i = 0; i < in.objects.size(); ++i) {
      const scene::Object& o = in.scene.objects[i];
      if ((which == Which::Static && o.animated()) || (which == Which::Animated && !o.animated())) continue;
      const SceneObjectGpu& g = in.objects[i];
      const glm::dmat4 model = in.modelAt(i);
      const Program& p = programs_[static_cast<std::size_t>(program_of_[i])].program;
      p.use();
      p.set("u_model", glm::mat4(model));
      p.set("u_normal_matrix", glm::mat3(glm::transpose(glm::inverse(glm::dmat3(model)))));
      p.set("u_object_id", static_cast<float>(i + 1) / 255.0f);
      if (velocity_) {
        p.set("u_previous_model_view_projection",
              glm::mat4(in.previousViewProjection() * in.modelAt(i, in.time - in.scene.motion_blur.interval)));
      }
      if (o.lines.enabled && o.lines.curvature == scene::CurvatureSource::Screen) {
        p.set("u_feature_size", static_cast<float>(g.feature_size));
      }
      if (surface_noise_) {
        glBindTextureUnit(0, noise_->id());
        p.set("u_noise", 0);
        p.set("u_noise_frequency", erosionNoiseFrequency(o, g));
      }
      if (g.wrinkle && !wrinklesInInkPass(in.scene, i)) {
        glBindTextureUnit(1, g.wrinkle->id());
        p.set("u_wrinkle", 1);
        p.set("u_repeat", static_cast<float>(o.wrinkle.repeat));
        if (o.wrinkle.mapping == scene::WrinkleMapping::Slope) {
          p.set("u_tile_px", wrinkleTilePixels(o, in.height));
          p.set("u_angle", static_cast<float>(glm::radians(o.wrinkle.angle_deg)));
        }
      }
      // Front to back, so hidden fragments fail the depth test before they are shaded.
      const glm::dvec3 forward = glm::inverse(glm::dmat3(model)) * (in.camera.target - in.camera.eye());
      g.mesh.drawFrontToBack(glm::vec3(forward));
    }
  }

  bool surface_noise_, animated_, velocity_;
  std::vector<Variant> programs_;
  std::vector<int> program_of_;  //!< per object, index into programs_
  std::optional<Texture2D> noise_;
  std::optional<std::uint64_t> seed_;
  Framebuffer gbuffer_, static_gbuffer_;
  Texture2D attachable_depth_;    //!< FrameImages::attachable_depth
  std::uint64_t static_key_ = 0;  //!< FrameInputs::static_key the static layer was drawn for (0: none)
};

}  // namespace

Texture2D erosionNoiseTexture(std::uint64_t seed) {
  return Texture2D::tiledFromImage(noise::erosionNoise(256, seed), GL_RG8, GL_NEAREST_MIPMAP_NEAREST);
}

Texture2D borderNoiseTexture(std::uint64_t seed) {
  const image::Image coarse = noise::erosionNoiseCoarse(1024, seed ^ 0x5A17ull);
  Texture2D t(coarse.width, coarse.height, GL_R8);
  glTextureSubImage2D(t.id(), 0, 0, 0, coarse.width, coarse.height, GL_RED, GL_FLOAT, coarse.pixels.data());
  return t;
}

float erosionNoiseFrequency(const scene::Object& o, const SceneObjectGpu& g) {
  const double model_radius = 0.5 * glm::length(g.model_bounds.size());
  const double tile = noise::kErosionCells * o.shading.noise_scale * model_radius;
  return static_cast<float>(1.0 / std::max(tile, 1e-30));
}

std::string gbufferStructure(const scene::Scene& s) {
  std::string k = s.hasAnimation() ? "animated" : "static";
  for (std::size_t i = 0; i < s.objects.size(); ++i) k += "|" + joined(objectDefines(s, i));
  return k;
}

std::unique_ptr<RenderPass> makeGbufferPass(const PassSetup& setup) {
  return std::make_unique<GbufferPass>(setup);
}

}  // namespace shanshui::render
