// The elements pass (issue 44): trees and moss dots, anchored at the surface points where
// they were placed on load (libs/elements), drawn as brush marks into an ink layer that the
// ink pass lays over the picture before the paper and the diffusion, so they get the same
// ink treatment as the slope they stand on.
//
// Each frame that the camera, size or parameters change, every element in view is expanded
// on the CPU into its marks for the levels of detail its size on screen asks for (far dab,
// middle strokes, full brushwork, cross-faded by elements::levelWeights), with the ink the
// distance fade, mist and border leave at its foot (atmosphere.h). The marks go to the GPU
// as one storage buffer; shaders/elements.vert stands each on an upright billboard through
// the element's foot, facing the camera, drawn depth-tested against the G-buffer (nudged
// towards the eye along each vertex's own ray, which keeps its place on screen, so the
// ground it stands on does not hide its foot). The layer keeps the largest ink and the
// nearness of what drew it: with animated objects it is drawn against the static objects'
// depth only when the static layer is, and the ink pass hides what an animated object
// covers by comparing nearness with its depth.
#include <algorithm>
#include <array>
#include <cmath>

#include "atmosphere.h"
#include "shanshui/core/error.h"
#include "shanshui/elements/brushwork.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

namespace {

// One mark on the GPU (std430, shaders/elements.vert's Mark).
struct GpuMark {
  glm::vec4 anchor_ink;  //!< the element's foot (world), the mark's ink
  glm::vec4 ab;          //!< its ends in the billboard's plane (world units: x right, y up)
  glm::vec4 shape;       //!< half width (world units), shape, seed, pixels per world unit at the foot
  glm::vec4 extra;       //!< how far it is drawn towards the eye (world units), unused ×3
};
static_assert(sizeof(GpuMark) == 64);

constexpr int kVariants = 16;           // grown brushwork per tree kind
constexpr double kLeastFarDabPx = 2.5;  // a far tree's dab is at least this wide (pixels at 1024 high)

class ElementsPass final : public RenderPass {
 public:
  explicit ElementsPass(const PassSetup& setup) : scene_(setup.scene), vao_(VertexArray::create()) {
    for (int k = 0; k < elements::kTreeKinds; ++k)
      for (int v = 0; v < kVariants; ++v)
        templates_[static_cast<std::size_t>(k * kVariants + v)] = elements::growBrushwork(
            static_cast<elements::Kind>(k), 0x5eedu * 977u + static_cast<std::uint32_t>(k * 131 + v));
    dot_ = elements::growBrushwork(elements::Kind::MossDot, 0);
    // Elements of a moving object move with it: then the layer is drawn every frame.
    for (std::size_t i = 0; i < setup.scene.objects.size(); ++i)
      if (setup.scene.objects[i].hasElements() && setup.scene.objects[i].animated()) every_frame_ = true;
    buildPrograms();
  }

  std::string name() const override { return "elements"; }
  void buildPrograms() override { program_ = Program({"elements.vert", "elements.frag"}); }
  std::vector<std::string> variants() const override { return {""}; }
  void setScene(const scene::Scene& s) override {
    scene_ = s;
    key_.clear();
  }
  void resize(int width, int height) override {
    target_ = Framebuffer(width, height, {GL_RG32F}, false);
    key_.clear();
  }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    images.elements = &target_.colour(0);
    const bool animated = images.static_gbuffer != nullptr;
    if (!every_frame_ && animated && in.static_key == key_) return;  // the cached static layer
    if (in.timer) in.timer->begin("elements");
    const std::size_t count = expand(in);
    glDisable(GL_SCISSOR_TEST);  // the layer is whole: a region redraw keeps it as it is
    const Texture2D& depth = animated && !every_frame_ ? images.static_gbuffer->depth() : *images.attachable_depth;
    glNamedFramebufferTexture(target_.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    target_.bind();
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(target_.id(), GL_COLOR, 0, clear);
    if (count > 0) {
      glEnable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glDepthFunc(GL_LESS);
      glEnable(GL_BLEND);
      glBlendEquation(GL_MAX);
      glBlendFunc(GL_ONE, GL_ONE);
      glBindVertexArray(vao_.id());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, marks_.id());
      program_.use();
      program_.set("u_view_projection", in.viewProjection());
      program_.set("u_eye", glm::vec3(in.camera.eye()));
      program_.set("u_right", right(in));
      glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(6 * count));
      glDisable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glDisable(GL_DEPTH_TEST);
      glDepthMask(GL_TRUE);
    }
    glNamedFramebufferTexture(target_.id(), GL_DEPTH_ATTACHMENT, 0, 0);
    if (in.region) {
      glEnable(GL_SCISSOR_TEST);
      const glm::ivec4& r = *in.region;
      glScissor(r.x, r.y, r.z - r.x, r.w - r.y);
    }
    if (in.timer) in.timer->end();
    SHANSHUI_GL_CHECK("elements pass");
    key_ = in.static_key;
    marks_drawn_ = count;
  }

 private:
  // The camera's right, level: billboards stand upright whatever the camera's pitch.
  static glm::vec3 right(const FrameInputs& in) {
    const glm::mat4 v = in.camera.view();
    glm::dvec3 r(v[0][0], v[1][0], 0.0);
    if (glm::length(r) < 1e-9) r = {1.0, 0.0, 0.0};
    return glm::vec3(glm::normalize(r));
  }

  // Every element in view, as marks in marks_; returns how many.
  std::size_t expand(const FrameInputs& in) {
    std::vector<GpuMark> out;
    const glm::dmat4 vp = glm::dmat4(in.viewProjection());
    const double pixels_at_1 = 0.5 * in.height / std::tan(glm::radians(in.camera.fov_y_deg) * 0.5);
    const double per_1024 = in.height / 1024.0;
    const glm::dvec2 fade = fadeRange(in);
    for (std::size_t i = 0; i < in.objects.size(); ++i) {
      const SceneObjectGpu& g = in.objects[i];
      if (!g.elements) continue;
      const scene::Object& o = scene_.objects[i];
      const glm::dmat4 model = in.modelAt(i);
      const glm::dmat4 to_model = glm::inverse(model);
      const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(model))));
      const glm::dvec3 centre = g.model_bounds.centre();
      for (const elements::Instance& e : g.elements->instances) {
        const glm::dvec4 world4 = model * glm::dvec4(glm::dvec3(e.position) - centre, 1.0);
        const glm::dvec3 world(world4);
        const glm::dvec4 clip = vp * glm::dvec4(world, 1.0);
        if (clip.w <= in.camera.near_plane) continue;
        const double ppu = pixels_at_1 / clip.w;  // pixels per world unit at the foot
        const bool dot = e.kind == elements::Kind::MossDot;
        const double height = dot ? o.dots.size_px * per_1024 * e.size / ppu : e.size * scale;
        // In view, with room for the element above its foot.
        const double reach = 2.0 * height * ppu / in.height + 0.05;
        const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
        if (std::abs(ndc.x) > 1.0 + reach || ndc.y > 1.0 + 0.05 || ndc.y < -1.0 - reach) continue;
        const double here = presence(in, i, to_model, world, fade);
        if (here < 0.004) continue;
        const double bias = std::min(dot ? 2.0 * height : 0.5 * height, 0.25 * clip.w);
        const float seed = static_cast<float>(e.seed & 0xffffu) / 65536.0f;
        auto emit = [&](const elements::Mark& m, double size, double ink) {
          glm::dvec2 a(m.a), b(m.b);
          if (e.mirrored) {
            a.x = -a.x;
            b.x = -b.x;
          }
          const double c = std::cos(e.lean), s = std::sin(e.lean);
          auto turn = [&](glm::dvec2 p) { return size * glm::dvec2(c * p.x + s * p.y, -s * p.x + c * p.y); };
          a = turn(a);
          b = turn(b);
          out.push_back({glm::vec4(glm::vec3(world), static_cast<float>(ink)), glm::vec4(a.x, a.y, b.x, b.y),
                         glm::vec4(static_cast<float>(0.5 * size * m.width), static_cast<float>(m.shape), seed,
                                   static_cast<float>(ppu)),
                         glm::vec4(static_cast<float>(bias), 0.0f, 0.0f, 0.0f)});
        };
        if (dot) {
          for (const elements::Mark& m : dot_) emit(m, height, o.dots.ink * here);
          continue;
        }
        const double px_1024 = height * ppu / per_1024;
        const std::array<float, 3> w = elements::levelWeights(px_1024);
        // A far tree stays a dab a painter can see: its far marks grow to the least width.
        const double far_size = height * std::max(1.0, kLeastFarDabPx / std::max(0.3 * px_1024, 1e-9));
        const auto& marks = templates_[static_cast<std::size_t>(static_cast<int>(e.kind) * kVariants +
                                                                static_cast<int>(e.seed % kVariants))];
        for (const elements::Mark& m : marks) {
          const double weight = ((m.levels & elements::kFar) ? w[0] : 0.0f) +
                                ((m.levels & elements::kMiddle) ? w[1] : 0.0f) +
                                ((m.levels & elements::kNear) ? w[2] : 0.0f);
          if (weight <= 0.0) continue;
          const bool far_only = m.levels == elements::kFar;
          emit(m, far_only ? far_size : height, std::min(1.0, m.ink * o.trees.ink * weight * here));
        }
      }
    }
    const std::size_t bytes = std::max<std::size_t>(out.size(), 1) * sizeof(GpuMark);
    if (bytes > capacity_) {
      marks_ = Buffer::create();
      capacity_ = std::max(bytes, 2 * capacity_);
      glNamedBufferStorage(marks_.id(), static_cast<GLsizeiptr>(capacity_), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    if (!out.empty())
      glNamedBufferSubData(marks_.id(), 0, static_cast<GLsizeiptr>(out.size() * sizeof(GpuMark)), out.data());
    return out.size();
  }

  scene::Scene scene_;
  std::array<std::vector<elements::Mark>, elements::kTreeKinds * kVariants> templates_;
  std::vector<elements::Mark> dot_;
  bool every_frame_ = false;
  Program program_;
  VertexArray vao_;
  Buffer marks_;
  std::size_t capacity_ = 0;
  std::size_t marks_drawn_ = 0;
  Framebuffer target_;
  std::string key_;
};

}  // namespace

std::unique_ptr<RenderPass> makeElementsPass(const PassSetup& setup) {
  return std::make_unique<ElementsPass>(setup);
}

}  // namespace shanshui::render
