// The ink pass: feature lines (seed 001 Eq. 1, or strokes from the centres that
// shaders/ink/ink_lines.frag finds first), interior shading (Eqs. 2, 3, 5) and the composite on
// paper in one image pass over the G-buffer (shaders/ink/ink.frag), with the per-object
// parameters in the block of shaders/ink/ink_object_params.glsl.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include <glm/gtc/matrix_access.hpp>

#include "shanshui/render/gl_check.h"
#include "shanshui/render/ink_object_params.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

namespace {

// A cell of the noise that breaks strokes (objects.N.lines.break), in stroke widths at the
// object's centre: a gap is a few widths long, and lifts come every few cells.
constexpr double kLineBreakWidths = 8.0;

// The paper grain goes on last: here, or after the diffusion when there is one.
bool grainHere(const scene::Scene& s) {
  return s.canvas.type != scene::CanvasType::None && !s.diffusion.enabled();
}

// Variants both image passes share: how objects are indexed and what the atmosphere needs.
void addSurfaceDefines(const scene::Scene& s, std::vector<std::string>& d) {
  if (s.objects.size() == 1)
    d.emplace_back("SINGLE_OBJECT");
  else
    d.push_back("OBJECTS=" + std::to_string(s.objects.size()));
  if (s.dissolvesBorders()) d.emplace_back("BORDER");
  if (s.mist.enabled()) d.emplace_back("MIST");
}

// The object whose slope wrinkles the ink pass computes, or none.
std::optional<std::size_t> wrinkledHere(const scene::Scene& s) {
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const scene::Object& o = s.objects[i];
    if (o.wrinkled() && o.wrinkle.mapping == scene::WrinkleMapping::Slope && o.wrinkle.uv == scene::UvSource::Planar)
      return i;
  }
  return std::nullopt;
}

std::vector<std::string> inkDefines(const scene::Scene& s, bool debug_outputs) {
  std::vector<std::string> d;
  if (s.usesLines()) d.emplace_back("LINES");
  if (s.usesStrokes()) d.emplace_back("STROKES");
  // Eq. 1's bands, silhouettes and outlines in this pass: only when some object draws its
  // lines without strokes (a software rasteriser runs a branch's code even when no pixel
  // takes it).
  if (std::any_of(s.objects.begin(), s.objects.end(),
                  [](const scene::Object& o) { return o.lines.enabled && !o.lines.strokes(); }))
    d.emplace_back("BAND_LINES");
  if (s.usesShading()) d.emplace_back("SHADING");
  if (s.usesWrinkles()) d.emplace_back("WRINKLE");
  if (wrinkledHere(s)) d.emplace_back("WRINKLE_SLOPE");
  if (grainHere(s)) d.emplace_back("CANVAS");
  if (s.usesPigment() || s.usesShadow()) d.emplace_back("PIGMENT");
  if (s.usesElements()) d.emplace_back("ELEMENTS");
  if (s.usesElements() && elementsKeepNearness(s)) d.emplace_back("ELEMENT_NEARNESS");
  if (s.usesWater()) d.emplace_back("WATER");
  if (s.usesMarks()) d.emplace_back("MARKS");
  if (s.usesWash()) d.emplace_back("WASH");
  addSurfaceDefines(s, d);
  if (debug_outputs) d.emplace_back("DEBUG_OUTPUTS");
  return d;
}

class InkPass final : public RenderPass {
 public:
  explicit InkPass(const PassSetup& setup)
      : scene_(setup.scene), vao_(VertexArray::create()), params_(Buffer::create()) {
    buildPrograms();
  }

  std::string name() const override { return "ink"; }

  void buildPrograms() override {
    std::vector<std::string> defines = inkDefines(scene_, debug_outputs_);
    // The objects' parameters in a uniform block when they fit this driver's (ink_objects.glsl).
    GLint max_block = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &max_block);
    const bool in_storage = scene_.objects.size() * sizeof(gpu::ObjectParams) > static_cast<std::size_t>(max_block);
    auto toStorage = [&](std::vector<std::string>& d) {
      if (in_storage) std::erase_if(d, [](const std::string& w) { return w.starts_with("OBJECTS="); });
    };
    toStorage(defines);
    // On a GPU compute shaders (the debug outputs' extra targets stay a fragment pass's).
    const bool compute = pixelPassesAsCompute() && !debug_outputs_;
    // The strokes gathered by each pixel instead of stamped with atomics (compute only).
    const bool gather = scene_.usesStrokes() && strokesGathered() && compute;  // a bad value is an error anywhere
    if (gather) defines.emplace_back("STROKE_GATHER");
    auto build = [compute](const std::string& frag, std::vector<std::string> d, const char* test) {
      if (compute) d.emplace_back(test);  // the depth test the fragment stage gets from the depth buffer
      return pixelProgram(frag, d, compute);
    };
    std::optional<Program> lines;
    std::vector<std::string> line_defines;
    if (scene_.usesStrokes()) {
      addSurfaceDefines(scene_, line_defines);
      toStorage(line_defines);
      if (scene_.usesShading()) line_defines.emplace_back("SHADING");  // it samples the shading's noise
      if (scene_.usesSuggestiveContours()) line_defines.emplace_back("SUGGESTIVE");
      if (scene_.usesWater()) line_defines.emplace_back("WATER");  // the atmosphere over hidden land
      if (gather) line_defines.emplace_back("STROKE_GATHER");
      lines.emplace(build("ink_lines.frag", line_defines, "PIXEL_SURFACES"));
    }
    std::vector<std::string> paper_defines = defines;
    paper_defines.emplace_back("PAPER");
    Program paper = build("ink.frag", paper_defines, "PIXEL_BACKGROUND");
    // A fragment pass draws the surfaces that a dissolved border leaves bare apart, with what
    // remains of the program once nothing of the land stands (BARE): a software rasteriser
    // runs every branch for a whole group of pixels, but skips a group the depth test
    // rejects. The lines pass finds them (the border's presence), so only with strokes.
    std::optional<Program> bare, classes;
    if (!compute && !debug_outputs_ && scene_.usesStrokes() && scene_.dissolvesBorders()) {
      std::vector<std::string> bare_defines = defines;
      bare_defines.emplace_back("BARE");
      bare.emplace(build("ink.frag", bare_defines, "PIXEL_SURFACES"));
      classes.emplace(pixelProgram("ink_classes.frag", {}, false));
    }
    program_ = build("ink.frag", defines, "PIXEL_SURFACES");  // a throw keeps the old programs
    compute_ = compute;
    gather_ = gather;
    paper_ = std::move(paper);
    bare_ = std::move(bare);
    classes_ = std::move(classes);
    lines_ = std::move(lines);
    defines_ = std::move(defines);
    line_defines_ = std::move(line_defines);
    objects_in_storage_ = in_storage;
  }

  std::vector<std::string> variants() const override {
    // The background's half of the same variant (PAPER) is not listed apart.
    const std::string stage = compute_ ? " PIXEL_COMPUTE" : "";
    std::vector<std::string> v{joined(defines_) + stage};
    if (lines_) v.push_back("lines: " + joined(line_defines_) + stage);
    if (bare_) v.emplace_back("bare land: BARE");
    return v;
  }

  void setScene(const scene::Scene& s) override {
    scene_ = s;
    if (s.usesShading() && surface_noise_seed_ != s.seed) {
      surface_noise_ = erosionNoiseTexture(s.seed);
      surface_noise_seed_ = s.seed;
    }
    if ((s.dissolvesBorders() || s.mist.enabled()) && noise_seed_ != s.seed) {
      value_noise_ = borderNoiseTexture(s.seed);
      noise_seed_ = s.seed;
    }
  }

  void resize(int width, int height) override {
    std::vector<GLenum> out{GL_RGBA8};
    if (debug_outputs_) out.insert(out.end(), {GL_RG16F, GL_RG16F});
    target_ = Framebuffer(width, height, out, false);
    kinds_ = Framebuffer();    // made at the next frame that draws bare land apart
    strokes_ = Framebuffer();  // both made at the next frame that draws strokes
    stroke_ink_ = Texture2D();
  }

  bool setDebugOutputs(bool on) override {
    if (on != debug_outputs_) {
      debug_outputs_ = on;
      buildPrograms();
      if (target_.width() > 0) resize(target_.width(), target_.height());
    }
    return true;
  }

  void run(const FrameInputs& in, FrameImages& images) override {
    uploadObjectParams(in);
    const Framebuffer& g = *images.gbuffer;
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(vao_.id());
    glBindImageTexture(0, g.colour(0).id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16);
    glBindImageTexture(1, g.colour(1).id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
    glBindTextureUnit(2, g.depth().id());
    if (value_noise_) glBindImageTexture(5, value_noise_->id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    if (surface_noise_) glBindTextureUnit(3, surface_noise_->id());
    if (const std::optional<std::size_t> w = wrinkledHere(in.scene)) glBindTextureUnit(4, in.objects[*w].wrinkle->id());
    // The pixels drawn: the region redrawn, or all (a compute shader's rectangle; a fragment
    // pass has the frame's scissor).
    const glm::ivec4 rect = in.drawn(), whole{0, 0, in.width, in.height};
    if (compute_) {
      glBindTextureUnit(7, g.depth().id());  // the programs' own depth test
    } else {
      // The frame's attachable depth on this pass's targets: the depth test keeps each draw
      // to the surfaces or to the background, and llvmpipe skips the other pixels' shading
      // (with fill framing about half the picture is background).
      glNamedFramebufferTexture(target_.id(), GL_DEPTH_ATTACHMENT, images.attachable_depth->id(), 0);
      glEnable(GL_DEPTH_TEST);
      glDepthMask(GL_FALSE);
      glDepthFunc(GL_GREATER);  // the triangle lies at depth 1: surfaces only
    }
    if (lines_) {  // built exactly when some object draws strokes
      // The strokes' ink by atomic max, or (gather_) each centre's ink and reach.
      const GLenum stroke_format = gather_ ? GL_RG32F : GL_R32UI;
      if (stroke_ink_.width() != target_.width() || stroke_ink_.height() != target_.height() ||
          stroke_ink_.format() != stroke_format) {
        strokes_ = Framebuffer(target_.width(), target_.height(), {GL_RGBA16}, false);
        stroke_ink_ = Texture2D(target_.width(), target_.height(), stroke_format);
      }
      if (in.timer) in.timer->begin("lines");
      const GLuint zero[2] = {0, 0};
      glClearTexImage(stroke_ink_.id(), 0, gather_ ? GL_RG : GL_RED_INTEGER, gather_ ? GL_FLOAT : GL_UNSIGNED_INT,
                      zero);
      glBindImageTexture(3, stroke_ink_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, stroke_format);
      if (compute_) {
        glBindImageTexture(7, strokes_.colour(0).id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16);
      } else {
        glNamedFramebufferTexture(strokes_.id(), GL_DEPTH_ATTACHMENT, images.attachable_depth->id(), 0);
        strokes_.bind();
        if (classes_) {  // alpha 1 where no surface is: the background, for ink_classes.frag
          const float background[4] = {0.0f, 0.0f, 0.0f, 1.0f};
          glClearNamedFramebufferfv(strokes_.id(), GL_COLOR, 0, background);
        }
      }
      glm::ivec4 line_rect = rect;
      if (in.region) {
        // A stroke's centre stamps ink up to its width around it: centres just outside the
        // redrawn region reach into it, so they are stamped too.
        double widest = 0.0;
        for (const scene::Object& o : in.scene.objects) widest = std::max(widest, o.lines.width);
        const int grow = 2 * (static_cast<int>(std::ceil(widest * in.height / 1024.0)) / 2) + 4;  // whole quads
        const glm::ivec4& r = *in.region;
        line_rect = glm::clamp(r + glm::ivec4(-grow, -grow, grow, grow), glm::ivec4(0),
                               glm::ivec4(whole.z, whole.w, whole.z, whole.w));
        if (!compute_) glScissor(r.x - grow, r.y - grow, r.z - r.x + 2 * grow, r.w - r.y + 2 * grow);
      }
      lines_->use();  // its uniforms: the frame's block (frame_params.glsl) and the objects'
      if (compute_) {
        dispatchPixels(*lines_, line_rect);
      } else {
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (in.region) {
          const glm::ivec4& r = *in.region;
          glScissor(r.x, r.y, r.z - r.x, r.w - r.y);
        }
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      }
      if (in.timer) in.timer->end();
      SHANSHUI_GL_CHECK("ink lines");
      glBindImageTexture(3, stroke_ink_.id(), 0, GL_FALSE, 0, GL_READ_ONLY, stroke_format);
      glBindImageTexture(4, strokes_.colour(0).id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16);
    }
    if (in.timer) in.timer->begin("ink");
    if (classes_) {
      // Each pixel's kind as its depth (ink_classes.frag: 0 shade, 0.5 bare, 1 background),
      // for the three draws below to test for equality.
      if (kinds_.width() != target_.width() || kinds_.height() != target_.height())
        kinds_ = Framebuffer(target_.width(), target_.height(), {}, true);
      kinds_.bind();
      glDepthMask(GL_TRUE);
      glDepthFunc(GL_ALWAYS);
      classes_->use();
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDepthMask(GL_FALSE);
      glNamedFramebufferTexture(target_.id(), GL_DEPTH_ATTACHMENT, kinds_.depth().id(), 0);
    }
    if (compute_) {
      glBindImageTexture(7, target_.colour(0).id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    } else {
      target_.bind();
    }
    if (grainHere(in.scene)) glBindImageTexture(2, images.canvas->id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RG16F);
    if (images.elements)
      glBindImageTexture(6, images.elements->id(), 0, GL_FALSE, 0, GL_READ_ONLY,
                         elementsKeepNearness(in.scene) ? GL_RG32F : GL_R8);
    const Program* bare = bare_ ? &*bare_ : nullptr;
    for (const Program* ink : std::initializer_list<const Program*>{&program_, bare, &*paper_}) {
      if (!ink) continue;
      ink->use();
      if (images.elements) ink->set("u_element_colour", elementColour(in.scene));
      if (grainHere(in.scene)) ink->set("u_canvas_contrast", static_cast<float>(in.scene.canvas.contrast));
      if (gather_) ink->set("u_stroke_reach", stroke_reach_);
      if (compute_) {
        dispatchPixels(*ink, rect);
      } else if (classes_) {
        // The triangle at the depth of its kind: glDepthRange(v, v) puts every fragment at v.
        const float kind = ink == &program_ ? 0.0f : (ink == bare ? 0.5f : 1.0f);
        glDepthRangef(kind, kind);
        glDepthFunc(GL_EQUAL);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDepthRangef(0.0f, 1.0f);
      } else {
        glDepthFunc(ink == &program_ ? GL_GREATER : GL_EQUAL);  // surfaces, then the background
        glDrawArrays(GL_TRIANGLES, 0, 3);
      }
    }
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    if (in.timer) in.timer->end();
    SHANSHUI_GL_CHECK("ink pass");
    images.picture = &target_.colour(0);
  }

  const Framebuffer* target() const override { return &target_; }

 private:
  // The elements' ink colour: the line colour of the first object that grows them.
  static glm::vec3 elementColour(const scene::Scene& s) {
    for (const scene::Object& o : s.objects)
      if (o.hasElements()) return glm::vec3(o.lines.line_color);
    return glm::vec3(0.0f);
  }

  void uploadObjectParams(const FrameInputs& in) {
    std::vector<gpu::ObjectParams> params(in.objects.size());
    const double pixels_per_unit_at_1 = 0.5 * in.height / std::tan(glm::radians(in.camera.fov_y_deg) * 0.5);
    int reach = 0;
    for (std::size_t i = 0; i < in.objects.size(); ++i) {
      const scene::Object& o = in.scene.objects[i];
      const SceneObjectGpu& g = in.objects[i];
      const scene::LineParams& l = o.lines;
      const scene::ShadingParams& sh = o.shading;
      // Projected area of the bounding sphere decides the small-object path.
      const double d = std::max(glm::length(in.camera.eye() - g.centre), 1e-12);
      const double r_px = g.radius / d * pixels_per_unit_at_1;
      // Lengths are pixels at 1024 high (areas their square), so a frame of any height is the
      // same picture.
      const double per_1024 = in.height / 1024.0;
      const bool small = std::numbers::pi * r_px * r_px < l.small_object_px * per_1024 * per_1024;
      gpu::ObjectParams& p = params[i];
      p.line_color = glm::vec3(l.line_color);
      p.curve_factor = static_cast<float>(l.curve_factor);
      p.bg_color = glm::vec3(l.bg_color);
      p.line_threshold = static_cast<float>(l.threshold);
      p.soft_width = static_cast<float>(l.soft_width);
      p.silhouette = static_cast<float>(l.silhouette);
      p.depth_edges = static_cast<float>(l.depth_edges);
      p.line_flags = (l.enabled ? gpu::kLinesOn : 0u) | (small ? gpu::kNormalOnly : 0u) |
                     (l.thin ? gpu::kThinLines : 0u) | (l.strokes() ? gpu::kStrokes : 0u);
      p.stroke_half_width = l.strokes() ? static_cast<float>(0.5 * l.width * per_1024) : 0.0f;
      p.stroke_taper = static_cast<float>(l.taper);
      p.stroke_far = static_cast<float>(l.far_width);
      p.valley_ink = static_cast<float>(l.valley_ink);
      p.suggestive = l.suggestiveContours() ? static_cast<float>(l.suggestive) : 0.0f;
      p.line_break = l.strokes() ? static_cast<float>(l.line_break) : 0.0f;
      if (l.strokes()) {
        // ink_lines.frag's widest disc: its half-width at the strongest crest, far away and
        // pressed hardest (lines.break), plus half a pixel; a hair more, for float rounding.
        const double widest = p.stroke_half_width * std::max<double>(p.stroke_taper, 1.0) *
                              std::max<double>(p.stroke_far, 1.0) * (1.0 + 0.3 * std::max<double>(p.line_break, 0.0));
        reach = std::max(reach, static_cast<int>((widest + 0.5) * (1.0 + 1e-5)));
      }
      // At least a millionth of the object's radius: a camera at its centre gives no cell.
      p.line_break_cell = static_cast<float>(
          std::max(std::max(kLineBreakWidths * l.width, 1.0) * per_1024 * d / pixels_per_unit_at_1, 1e-6 * g.radius));
      p.tones = glm::vec4(sh.tones[0], sh.tones[1], sh.tones[2], sh.tones[3]);
      p.thresholds = glm::vec4(sh.thresholds[0], sh.thresholds[1], sh.thresholds[2], sh.thresholds[3]);
      p.tone5 = static_cast<float>(sh.tones[4]);
      p.sigma = static_cast<float>(sh.sigma);
      p.beta = static_cast<float>(sh.beta);
      p.erosion = static_cast<float>(sh.erosion);
      p.noise = static_cast<float>(sh.noise);
      p.inv_inner_tex_factor = static_cast<float>(1.0 / o.wrinkle.inner_tex_factor);
      p.shade_flags = (sh.enabled ? gpu::kShadingOn : 0u) | (sh.half_lambert ? gpu::kHalfLambert : 0u) |
                      (sh.line_value ? gpu::kLineValue : 0u) | (o.wrinkled() ? gpu::kWrinkled : 0u) |
                      (wrinklesInInkPass(in.scene, i) ? gpu::kWrinkleHere : 0u);
      p.wrinkle_tile_px = wrinkleTilePixels(o, in.height);
      p.wrinkle_angle = static_cast<float>(glm::radians(o.wrinkle.angle_deg));
      p.noise_frequency = erosionNoiseFrequency(o, g);
      const scene::MarksParams& mk = o.marks;
      p.marks_style = mk.style == scene::MarkStyle::Hemp ? 1u : mk.style == scene::MarkStyle::Axe ? 2u : 0u;
      p.marks_ink = static_cast<float>(mk.ink);
      p.marks_density = static_cast<float>(mk.density);
      // A mark spans at most a lattice cell (0.72-0.92 of one for a hemp fibre, 0.6-0.84 for
      // an axe cut): a cell per 0.82 of a fibre's length, per 0.72 of a cut's.
      p.marks_spacing_px =
          static_cast<float>(mk.size / (mk.style == scene::MarkStyle::Axe ? 0.72 : 0.82) * in.height / 1024.0);
      p.marks_lit = static_cast<float>(mk.lit);
      p.marks_ridge = static_cast<float>(mk.ridge);
      p.marks_seed =
          static_cast<std::uint32_t>((in.scene.seed * 0x9E3779B97F4A7C15ull + i * 0xBF58476D1CE4E5B9ull) >> 32);
      p.marks_angle = static_cast<float>(glm::radians(mk.angle_deg));
      // The wet strokes' cell in world units, one for the whole object: wash_size on screen at
      // the object's centre (a group is 0.48-0.68 of a cell long plus its start: 0.6 on
      // average), so they keep one lattice over the land, nearer strokes drawn larger, as
      // painted strokes on the land would be.
      p.wash_density = static_cast<float>(mk.wash);
      p.wash_ink = static_cast<float>(mk.wash_ink);
      p.wash_cell =
          static_cast<float>(std::log2(std::max(mk.wash_size / 0.6 * per_1024 * d / pixels_per_unit_at_1, 1e-30)));
      p.wash_lit = static_cast<float>(mk.wash_lit);
      p.wash_follow = static_cast<float>(mk.wash_follow);
      p.wash_width = static_cast<float>(mk.wash_width);
      // The dissolving border, in the coordinates the object was uploaded in (relative to
      // its bounding-box centre).
      const glm::dmat4 to_model = glm::inverse(in.modelAt(i));
      p.world_to_model_x = glm::vec4(glm::row(to_model, 0));
      p.world_to_model_y = glm::vec4(glm::row(to_model, 1));
      const glm::dvec3 half = 0.5 * g.model_bounds.size();
      p.half_extent = glm::vec3(half);
      p.border_width = o.dissolvesBorder() ? static_cast<float>(o.border.width * std::min(half.x, half.y)) : 0.0f;
      p.border_roughness = static_cast<float>(o.border.roughness);
    }
    stroke_reach_ = reach;
    const std::size_t bytes = params.size() * sizeof(gpu::ObjectParams);
    if (bytes > capacity_) {
      params_ = Buffer::create();
      glNamedBufferStorage(params_.id(), static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
      capacity_ = bytes;
    }
    glNamedBufferSubData(params_.id(), 0, static_cast<GLsizeiptr>(bytes), params.data());
    // A uniform block unless there are more objects than one holds (shaders/ink/ink_objects.glsl).
    glBindBufferBase(objects_in_storage_ ? GL_SHADER_STORAGE_BUFFER : GL_UNIFORM_BUFFER, 0, params_.id());
  }

  scene::Scene scene_;
  bool debug_outputs_ = false;
  std::vector<std::string> defines_;
  Program program_;
  std::optional<Program> paper_;    //!< the background's pixels (PAPER)
  std::optional<Program> lines_;    //!< the stroke centres, when some object draws strokes
  std::optional<Program> bare_;     //!< a fragment pass's surfaces where nothing of the land stands (BARE)
  std::optional<Program> classes_;  //!< sorts the pixels for bare_ (ink_classes.frag)
  Framebuffer kinds_;               //!< classes_'s depth: 0 shade, 0.5 bare, 1 background
  bool compute_ = false;            //!< the three are compute shaders (pixelPassesAsCompute)
  bool gather_ = false;             //!< strokes gathered, not stamped (strokesGathered)
  int stroke_reach_ = 0;            //!< the most pixels a stroke centre's ink reaches this frame
  std::vector<std::string> line_defines_;
  VertexArray vao_;
  Buffer params_;
  std::size_t capacity_ = 0;
  bool objects_in_storage_ = false;  //!< more objects than a uniform block holds
  Framebuffer target_;
  Framebuffer strokes_;   //!< the lines stage's target: RGBA16, presence and shading noise per surface pixel
  Texture2D stroke_ink_;  //!< R32UI: the strokes' ink × 255, by atomic max
  std::optional<Texture2D> value_noise_;  //!< the border's and mist's noise
  std::optional<std::uint64_t> noise_seed_;
  std::optional<Texture2D> surface_noise_;  //!< the shading's erosion and added noise
  std::optional<std::uint64_t> surface_noise_seed_;
};

}  // namespace

std::string inkStructure(const scene::Scene& s) {
  // The lines stage's suggestive-contour variant too: turning them on or off rebuilds it
  // (the word means nothing to ink.frag, which the variant test compiles with these).
  return joined(inkDefines(s, false)) + (s.usesSuggestiveContours() ? " SUGGESTIVE" : "");
}

bool wrinklesInInkPass(const scene::Scene& s, std::size_t i) {
  return wrinkledHere(s) == i;
}

std::unique_ptr<RenderPass> makeInkPass(const PassSetup& setup) {
  return std::make_unique<InkPass>(setup);
}

}  // namespace shanshui::render
