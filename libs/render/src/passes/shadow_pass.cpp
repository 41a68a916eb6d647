// The shadow pass (issue 25; seed 003 lays shadows as a layer of paint): the scene's depth
// from the light into a shadow map, then a wash of the shadow's pigment wherever a visible
// surface is hidden from the light (shaders/shadow/shadow_wash.frag). The map is drawn again only
// when the light, the objects' poses or its size change. Built only when shadow.pigment
// names a pigment.

#include <array>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/core/error.h"
#include "shanshui/pigment/kubelka_munk.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

glm::dmat4 lightViewProjection(const glm::dvec3& towards_light, const mesh::Bounds& world_bounds) {
  const glm::dvec3 l = glm::normalize(towards_light);
  const glm::dvec3 centre = world_bounds.centre();
  const double radius = std::max(0.5 * glm::length(world_bounds.size()), 1e-9);
  const glm::dvec3 up = std::abs(l.z) > 0.99 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
  return glm::ortho(-radius, radius, -radius, radius, radius, 3.0 * radius) *
         glm::lookAt(centre + 2.0 * radius * l, centre, up);
}

namespace {

class ShadowPass final : public RenderPass {
 public:
  explicit ShadowPass(const PassSetup& setup) : scene_(setup.scene), vao_(VertexArray::create()) { buildPrograms(); }

  std::string name() const override { return "shadow"; }

  void buildPrograms() override {
    Program depth({"shadow_depth.vert", "shadow_depth.frag"});
    const bool compute = pixelPassesAsCompute();
    wash_ = pixelProgram("shadow_wash.frag", {}, compute);
    compute_ = compute;
    depth_ = std::move(depth);
  }

  std::vector<std::string> variants() const override { return {""}; }

  void setScene(const scene::Scene& s) override {
    scene_ = s;
    coefficients_ = pigment::coefficients(objectPigment(s.shadow.pigment), "shadow.pigment");
    map_key_.reset();  // transforms may have moved: draw the map again
    if (map_.width() != s.shadow.resolution) {
      map_ = Framebuffer(s.shadow.resolution, s.shadow.resolution, {}, true);
      const GLuint t = map_.depth().id();
      glTextureParameteri(t, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
      glTextureParameteri(t, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
      glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      map_key_.reset();
    }
  }

  void resize(int width, int height) override { target_ = Framebuffer(width, height, {GL_RGBA8, GL_R8}, false); }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    if (in.timer) in.timer->begin("shadow");
    const glm::dmat4 light = lightViewProjection(in.scene.light.direction, in.world_bounds);
    // The map depends on the light and the objects' poses, not on the camera.
    const glm::dvec3& l = in.scene.light.direction;
    const std::array<double, 4> key{l.x, l.y, l.z, in.scene.hasAnimation() ? in.time : 0.0};
    if (key != map_key_) {
      drawMap(in, light);
      map_key_ = key;
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_.id());
    wash_.use();
    glBindTextureUnit(0, images.picture->id());
    glBindTextureUnit(1, images.gbuffer->depth().id());
    glBindTextureUnit(2, map_.depth().id());
    wash_.set("u_light_view_projection", glm::mat4(light));
    const scene::ShadowParams& sh = in.scene.shadow;
    wash_.set("u_bias", static_cast<float>(sh.bias / sh.resolution));
    wash_.set("u_softness", static_cast<float>(sh.softness));
    wash_.set("u_s_thickness", glm::vec4(glm::vec3(coefficients_.S), static_cast<float>(sh.pigment.thickness)));
    wash_.set("u_a", glm::vec3(coefficients_.a));
    wash_.set("u_b", glm::vec3(coefficients_.b));
    shadePixels(wash_, compute_, target_, {GL_RGBA8, GL_R8}, in.drawn());
    SHANSHUI_GL_CHECK("shadow pass");
    images.picture = &target_.colour();
    images.shadow = &target_.colour(1);
    if (in.timer) in.timer->end();
  }

 private:
  void drawMap(const FrameInputs& in, const glm::dmat4& light) const {
    map_.bind();
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(map_.id(), GL_DEPTH, 0, &far_depth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    depth_.use();
    for (std::size_t i = 0; i < in.objects.size(); ++i) {
      depth_.set("u_light_model_view_projection", glm::mat4(light * in.modelAt(i)));
      in.objects[i].mesh.draw();
    }
    glDisable(GL_DEPTH_TEST);
    SHANSHUI_GL_CHECK("shadow map");
  }

  scene::Scene scene_;
  Program depth_, wash_;
  bool compute_ = false;  //!< wash_ is a compute shader (pixelPassesAsCompute)
  VertexArray vao_;
  pigment::Coefficients coefficients_;
  Framebuffer map_, target_;
  std::optional<std::array<double, 4>> map_key_;  //!< the light and time map_ was drawn for
};

}  // namespace

std::unique_ptr<RenderPass> makeShadowPass(const PassSetup& setup) {
  return std::make_unique<ShadowPass>(setup);
}

}  // namespace shanshui::render
