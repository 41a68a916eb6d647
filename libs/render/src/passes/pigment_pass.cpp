// The pigment pass (issue 25; seeds 000 and 003): objects with a pigment get a wash of it,
// composited by Kubelka–Munk over the picture the ink and strokes passes made
// (shaders/pigment/pigment_wash.frag). Built only when some object has a pigment; a scene without
// one draws exactly as before.
#include "shanshui/core/error.h"
#include "shanshui/pigment/kubelka_munk.h"
#include "shanshui/pigment/palette.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {
namespace {

const char* paletteName(scene::PigmentName n) {
  switch (n) {
    case scene::PigmentName::Ochre:
      return "ochre";
    case scene::PigmentName::Indigo:
      return "indigo";
    case scene::PigmentName::Azurite:
      return "azurite";
    case scene::PigmentName::Malachite:
      return "malachite";
    case scene::PigmentName::Cinnabar:
      return "cinnabar";
    case scene::PigmentName::Gamboge:
      return "gamboge";
    case scene::PigmentName::Ink:
      return "ink";
    case scene::PigmentName::None:
    case scene::PigmentName::Custom:
      break;
  }
  return nullptr;
}

}  // namespace

pigment::Pigment objectPigment(const scene::PigmentParams& p) {
  if (const char* name = paletteName(p.name)) return pigment::named(name);
  return {p.on_white, p.on_black};
}

namespace {

class PigmentPass final : public RenderPass {
 public:
  explicit PigmentPass(const PassSetup& setup)
      : scene_(setup.scene),
        shading_(setup.scene.usesShading()),
        vao_(VertexArray::create()),
        washes_(Buffer::create()) {
    buildPrograms();
  }

  std::string name() const override { return "pigment"; }
  void buildPrograms() override {
    compute_ = pixelPassesAsCompute();
    program_ = pixelProgram("pigment_wash.frag", {}, compute_);
  }
  std::vector<std::string> variants() const override { return {""}; }

  void setScene(const scene::Scene& s) override {
    scene_ = s;
    // Per object: S, thickness; a, follow_ink; b, texture (the erosion noise it varies with
    // is in the G-buffer only when the scene shades).
    std::vector<glm::vec4> data;
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
      const scene::PigmentParams& p = s.objects[i].pigment;
      if (!p.enabled()) {
        data.insert(data.end(), {glm::vec4(0.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f), glm::vec4(0.0f)});
        continue;
      }
      const std::string what = "objects." + std::to_string(i) + ".pigment";
      const pigment::Coefficients c = pigment::coefficients(objectPigment(p), what.c_str());
      data.insert(data.end(), {glm::vec4(glm::vec3(c.S), static_cast<float>(p.thickness)),
                               glm::vec4(glm::vec3(c.a), static_cast<float>(p.follow_ink)),
                               glm::vec4(glm::vec3(c.b), shading_ ? static_cast<float>(p.texture) : 0.0f)});
    }
    glNamedBufferData(washes_.id(), static_cast<GLsizeiptr>(data.size() * sizeof(glm::vec4)), data.data(),
                      GL_STATIC_DRAW);
  }

  void resize(int width, int height) override { target_ = Framebuffer(width, height, {GL_RGBA8}, false); }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    if (in.timer) in.timer->begin("pigment");
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_.id());
    program_.use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, washes_.id());
    glBindTextureUnit(0, images.picture->id());
    glBindTextureUnit(1, images.gbuffer->colour(1).id());
    glBindTextureUnit(2, images.gbuffer->depth().id());
    shadePixels(program_, compute_, target_, {GL_RGBA8}, in.drawn());
    SHANSHUI_GL_CHECK("pigment pass");
    images.picture = &target_.colour();
    if (in.timer) in.timer->end();
  }

 private:
  scene::Scene scene_;
  bool shading_;
  Program program_;
  bool compute_ = false;  //!< program_ is a compute shader (pixelPassesAsCompute)
  VertexArray vao_;
  Buffer washes_;
  Framebuffer target_;
};

}  // namespace

std::unique_ptr<RenderPass> makePigmentPass(const PassSetup& setup) {
  return std::make_unique<PigmentPass>(setup);
}

}  // namespace shanshui::render
