// The elements pass (issue 44): trees and moss dots, anchored at the surface points where
// they were placed on load (libs/elements), drawn as brush marks into an ink layer that the
// ink pass lays over the picture before the paper and the diffusion, so they get the same
// ink treatment as the slope they stand on.
//
// The elements and the brushwork grown for each kind (16 variants a kind, marks sorted by
// level of detail) are uploaded once. Each frame that the camera, size or parameters change,
// shaders/elements/elements_expand.comp runs one thread per element: it culls what is out of view,
// weighs the levels of detail by the element's height on screen (far dab, middle strokes,
// full brushwork, cross-faded as elements::levelWeights), takes the ink the distance fade,
// mist and border leave at its foot, and appends an entry per mark of the active levels.
// One indirect draw then stands each mark on an upright billboard through the element's foot
// facing the camera (shaders/elements/elements.vert), depth-tested against the G-buffer and nudged
// towards the eye along each vertex's own ray, which keeps its place on screen, so the
// ground it stands on does not hide its foot. The layer (R8) keeps the largest ink. With
// animated objects it also keeps the nearness of what drew it (RG32F, NEARNESS): it is then
// drawn against the static objects' depth only when the static layer is, and the ink pass
// hides what an animated object covers by comparing nearness with its depth. Nothing per
// element runs on the CPU.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include <glm/gtc/matrix_access.hpp>

#include "frame/atmosphere.h"
#include "shanshui/core/error.h"
#include "shanshui/elements/brushwork.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/grounding.h"

namespace shanshui::render {

namespace {

// shaders/elements/elements_expand.comp's and elements.vert's blocks (std430).
struct GpuInstance {
  glm::vec4 position_size;  //!< uploaded coordinates; height (trees) or size factor (dots)
  glm::vec4 lean_seed;      //!< lean, seed in [0, 1), mirrored, template index
};
struct GpuMark {
  glm::vec4 ab;     //!< ends, in units of the element's height
  glm::vec4 shape;  //!< width, ink, shape, levels
};
constexpr std::size_t kFrameInstanceBytes = 48, kEntryBytes = 16;
static_assert(sizeof(GpuInstance) == 32 && sizeof(GpuMark) == 32);

constexpr int kVariants = 16;                   // grown brushwork per tree kind
constexpr double kLeastFarDabPx = 2.5;          // a far tree's dab is at least this wide (pixels at 1024 high)
constexpr std::size_t kMostEntries = 1u << 21;  // marks a frame (32 MiB of entries)

// The most marks a frame has room for: kMostEntries, or fewer where SHANSHUI_ELEMENT_MARKS
// asks (so a test can fill the buffer without drawing two million marks).
std::size_t mostEntries() {
  if (const char* asked = std::getenv("SHANSHUI_ELEMENT_MARKS")) {
    char* end = nullptr;
    const unsigned long long n = std::strtoull(asked, &end, 10);
    if (end != asked && *end == '\0' && n > 0) return std::min<std::size_t>(n, kMostEntries);
  }
  return kMostEntries;
}

// Marks in the order the expansion reads them: far only, middle only, middle and near, near
// only (a dot's one mark, at every level, counts as far).
int group(std::uint8_t levels) {
  if (levels == elements::kFar || levels == (elements::kFar | elements::kMiddle | elements::kNear)) return 0;
  if (levels == elements::kMiddle) return 1;
  if (levels == (elements::kMiddle | elements::kNear)) return 2;
  SHANSHUI_CHECK(levels == elements::kNear);
  return 3;
}

class ElementsPass final : public RenderPass {
 public:
  explicit ElementsPass(const PassSetup& setup)
      : scene_(setup.scene),
        nearness_(elementsKeepNearness(setup.scene)),
        vao_(VertexArray::create()),
        indirect_(Buffer::create()) {
    // The brushwork: 16 variants of each tree kind, then the dot.
    std::vector<GpuMark> marks;
    std::vector<glm::ivec4> groups;
    std::size_t largest = 0;
    auto add = [&](std::vector<elements::Mark> grown) {
      std::stable_sort(grown.begin(), grown.end(), [](const elements::Mark& x, const elements::Mark& y) {
        return group(x.levels) < group(y.levels);
      });
      // Where each group starts: the first mark of that group or a later one (the end if none).
      glm::ivec4 start(static_cast<int>(marks.size() + grown.size()));
      for (std::size_t k = grown.size(); k-- > 0;)
        for (int gi = 0; gi <= group(grown[k].levels); ++gi) start[gi] = static_cast<int>(marks.size() + k);
      for (const elements::Mark& m : grown)
        marks.push_back({glm::vec4(m.a, m.b), glm::vec4(m.width, m.ink, static_cast<float>(m.shape), m.levels)});
      groups.push_back(start);
      groups.emplace_back(static_cast<int>(marks.size()), 0, 0, 0);
      largest = std::max(largest, grown.size());
    };
    for (int k = 0; k < elements::kTreeKinds; ++k)
      for (int v = 0; v < kVariants; ++v)
        add(elements::growBrushwork(static_cast<elements::Kind>(k),
                                    0x5eedu * 977u + static_cast<std::uint32_t>(k * 131 + v)));
    dot_template_ = static_cast<std::uint32_t>(groups.size() / 2);
    add(elements::growBrushwork(elements::Kind::MossDot, 0));
    marks_ = upload(marks);
    templates_ = upload(groups);
    // The elements, each object's in a run.
    std::vector<GpuInstance> instances;
    for (std::size_t i = 0; i < setup.objects.size(); ++i) {
      const SceneObjectGpu& g = setup.objects[i];
      if (!g.elements || g.elements->instances.empty()) continue;
      runs_.push_back({i, instances.size(), g.elements->instances.size()});
      const glm::dvec3 centre = g.model_bounds.centre();
      for (const elements::Instance& e : g.elements->instances) {
        const bool dot = e.kind == elements::Kind::MossDot;
        const std::uint32_t t =
            dot ? dot_template_ : static_cast<std::uint32_t>(static_cast<int>(e.kind) * kVariants + e.seed % kVariants);
        instances.push_back({glm::vec4(glm::vec3(glm::dvec3(e.position) - centre), e.size),
                             glm::vec4(e.lean, static_cast<float>(e.seed & 0xffffu) / 65536.0f,
                                       e.mirrored ? 1.0f : 0.0f, static_cast<float>(t))});
      }
      // Elements of a moving object move with it: then the layer is drawn every frame.
      if (setup.scene.objects[i].animated()) every_frame_ = true;
    }
    count_ = instances.size();
    instances_ = upload(instances);
    frame_instances_ = Buffer::create();
    glNamedBufferStorage(frame_instances_.id(),
                         static_cast<GLsizeiptr>(std::max<std::size_t>(count_, 1) * kFrameInstanceBytes), nullptr, 0);
    capacity_ = std::clamp<std::size_t>(count_ * largest, 1, mostEntries());
    entries_ = Buffer::create();
    glNamedBufferStorage(entries_.id(), static_cast<GLsizeiptr>(capacity_ * kEntryBytes), nullptr, 0);
    const GLuint draw[4] = {4, 0, 0, 0};  // a strip of four corners, one instance a mark (counted each frame)
    glNamedBufferStorage(indirect_.id(), sizeof draw, draw, 0);
    buildPrograms();
  }

  std::string name() const override { return "elements"; }
  std::size_t marksDropped() const override {
    // The expansion counts every mark it makes, stored or not (elements_expand.comp).
    GLuint made = 0;
    glGetNamedBufferSubData(indirect_.id(), sizeof made, sizeof made, &made);
    return made > capacity_ ? made - capacity_ : 0;
  }
  void buildPrograms() override {
    Program expand({"elements_expand.comp"}, {"MAX_CLEARINGS=" + std::to_string(kMaxClearings)});
    draw_ = Program({"elements.vert", "elements.frag"}, defines());
    expand_ = std::move(expand);
  }
  std::vector<std::string> variants() const override { return {joined(defines())}; }
  void setScene(const scene::Scene& s) override {
    scene_ = s;
    key_ = 0;
    if (s.dissolvesBorders() && noise_seed_ != s.seed) {  // where a ragged border leaves a tree's ground
      border_noise_ = borderNoiseTexture(s.seed);
      noise_seed_ = s.seed;
    }
  }
  void resize(int width, int height) override {
    target_ = Framebuffer(width, height, {nearness_ ? GLenum(GL_RG32F) : GLenum(GL_R8)}, false);
    attached_ = 0;
    key_ = 0;
  }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    images.elements = &target_.colour(0);
    const bool cached = nearness_ && !every_frame_ && images.static_gbuffer != nullptr;
    if (cached && in.static_key == key_) return;  // the cached static layer
    if (in.timer) in.timer->begin("elements");
    glDisable(GL_SCISSOR_TEST);  // the layer is whole: a region redraw keeps it as it is
    expand(in);
    const Texture2D& depth = cached ? images.static_gbuffer->depth() : *images.attachable_depth;
    if (depth.id() != attached_) {  // a new attachment makes the driver check the framebuffer again
      glNamedFramebufferTexture(target_.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
      attached_ = depth.id();
    }
    target_.bind();
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(target_.id(), GL_COLOR, 0, clear);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LESS);
    glEnable(GL_BLEND);
    glBlendEquation(GL_MAX);
    glBlendFunc(GL_ONE, GL_ONE);
    glBindVertexArray(vao_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, marks_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, frame_instances_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, entries_.id());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, indirect_.id());
    draw_.use();
    draw_.set("u_right", pictureHorizontal(in));
    draw_.set("u_capacity", static_cast<unsigned>(capacity_));
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, nullptr);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    if (in.region) {
      glEnable(GL_SCISSOR_TEST);
      const glm::ivec4& r = *in.region;
      glScissor(r.x, r.y, r.z - r.x, r.w - r.y);
    }
    if (in.timer) in.timer->end();
    SHANSHUI_GL_CHECK("elements pass");
    key_ = in.static_key;
  }

 private:
  std::vector<std::string> defines() const {
    if (nearness_) return {"NEARNESS"};
    return {};
  }

  struct Run {
    std::size_t object, first, count;
  };

  template <typename T>
  static Buffer upload(const std::vector<T>& v) {
    Buffer b = Buffer::create();
    glNamedBufferStorage(b.id(), static_cast<GLsizeiptr>(std::max<std::size_t>(v.size(), 1) * sizeof(T)),
                         v.empty() ? nullptr : v.data(), 0);
    return b;
  }

  // The camera's right, level: billboards stand upright whatever the camera's pitch.

  // Every element in view, as entries for the indirect draw.
  void expand(const FrameInputs& in) {
    // The instance count back to 0 on the GPU (an upload could wait for the last frame's draw).
    const GLuint zero = 0;
    glClearNamedBufferSubData(indirect_.id(), GL_R32UI, sizeof zero, sizeof zero, GL_RED_INTEGER, GL_UNSIGNED_INT,
                              &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, instances_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, templates_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, frame_instances_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, entries_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, indirect_.id());
    if (border_noise_) glBindImageTexture(0, border_noise_->id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    expand_.use();
    const double per_1024 = in.height / 1024.0;
    expand_.set("u_near", static_cast<float>(in.camera.near_plane));
    expand_.set("u_pixels_at_1",
                static_cast<float>(0.5 * in.height / std::tan(glm::radians(in.camera.fov_y_deg) * 0.5)));
    expand_.set("u_per_1024", static_cast<float>(per_1024));
    expand_.set("u_height_px", static_cast<float>(in.height));
    expand_.set("u_capacity", static_cast<unsigned>(capacity_));
    expand_.set("u_least_far_px", static_cast<float>(kLeastFarDabPx));
    expand_.set("u_level_bands", glm::vec4(elements::kLevelBands[0], elements::kLevelBands[1], elements::kLevelBands[2],
                                           elements::kLevelBands[3]));
    expand_.set("u_dot_template", dot_template_);
    // The camera, the fade, the mist and the water's level: the frame's block.
    for (const Run& r : runs_) {
      const scene::Object& o = scene_.objects[r.object];
      const glm::dmat4 model = in.modelAt(r.object);
      const glm::dmat4 to_model = glm::inverse(model);
      expand_.set("u_model", glm::mat4(model));
      expand_.set("u_scale", static_cast<float>(std::cbrt(std::abs(glm::determinant(glm::dmat3(model))))));
      expand_.set("u_first", static_cast<unsigned>(r.first));
      expand_.set("u_count", static_cast<unsigned>(r.count));
      expand_.set("u_tree_ink", static_cast<float>(o.trees.ink));
      expand_.set("u_dot_ink", static_cast<float>(o.dots.ink));
      expand_.set("u_dot_px", static_cast<float>(o.dots.size_px));
      const glm::dvec3 half = 0.5 * in.objects[r.object].model_bounds.size();
      expand_.set("u_to_model_x", glm::vec4(glm::row(to_model, 0)));
      expand_.set("u_to_model_y", glm::vec4(glm::row(to_model, 1)));
      expand_.set("u_half_extent", glm::vec2(half));
      expand_.set("u_border_width",
                  o.dissolvesBorder() ? static_cast<float>(o.border.width * std::min(half.x, half.y)) : 0.0f);
      expand_.set("u_border_roughness", static_cast<float>(o.border.roughness));
      setClearings(in, r.object);
      glDispatchCompute(static_cast<GLuint>((r.count + 63) / 64), 1, 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  }

  // The objects standing on `ground` (the shader's u_clearing): where each stands now and
  // its horizontal radius, so its clearing follows a live change of its transform.
  void setClearings(const FrameInputs& in, std::size_t ground) const {
    // The array's element names, made once, not each frame.
    static const std::array<std::string, kMaxClearings> names = [] {
      std::array<std::string, kMaxClearings> a;
      for (int k = 0; k < kMaxClearings; ++k) a[k] = "u_clearing[" + std::to_string(k) + "]";
      return a;
    }();
    int n = 0;
    for (std::size_t j = 0; j < scene_.objects.size() && n < kMaxClearings; ++j) {
      if (scene::groundOf(scene_, j) != ground) continue;
      const glm::dmat4 model = in.modelAt(j);
      const glm::dvec3 centre(model * glm::dvec4(0.0, 0.0, 0.0, 1.0));  // uploaded about the bounds' centre
      const glm::dvec3 size = in.objects[j].model_bounds.size();
      const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(model))));
      const double radius = 0.5 * std::hypot(size.x, size.y) * scale;
      expand_.set(names[n].c_str(), glm::vec4(glm::vec3(centre), radius));
      ++n;
    }
    expand_.set("u_clearings", n);
  }

  // The most objects that stand on one ground and clear its trees (elements_expand.comp's
  // u_clearing, sized by this).
  static constexpr int kMaxClearings = 16;

  scene::Scene scene_;
  std::vector<Run> runs_;
  std::size_t count_ = 0, capacity_ = 1;
  std::uint32_t dot_template_ = 0;
  bool every_frame_ = false;
  bool nearness_ = false;  //!< the layer keeps nearness (animated scenes)
  GLuint attached_ = 0;    //!< the depth texture attached to target_
  Program expand_, draw_;
  VertexArray vao_;
  Buffer marks_, templates_, instances_, frame_instances_, entries_, indirect_;
  Framebuffer target_;
  std::uint64_t key_ = 0;                  //!< FrameInputs::static_key of the cached layer (0: none)
  std::optional<Texture2D> border_noise_;  //!< the dissolving border's noise (borderNoiseTexture)
  std::optional<std::uint64_t> noise_seed_;
};

}  // namespace

bool elementsKeepNearness(const scene::Scene& s) {
  return s.usesElements() && s.hasAnimation();
}

std::string elementsStructure(const scene::Scene& s) {
  return elementsKeepNearness(s) ? "NEARNESS" : "";
}

std::unique_ptr<RenderPass> makeElementsPass(const PassSetup& setup) {
  return std::make_unique<ElementsPass>(setup);
}

}  // namespace shanshui::render
