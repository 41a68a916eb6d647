// The brush strokes pass (seed 002, issue 24): each frame, the feature edges of every object
// with strokes are found on the CPU (strokes/edges.h), kept where the G-buffer's depth shows
// them (visibility.h), linked into chains and drawn as brush strips over the ink picture,
// so diffusion and the canvas act on them as on any ink. When something in the scene moves,
// the strokes of what stands still are kept as a layer (statistics: "strokes_static" when it
// is redrawn, "strokes_animated" each frame) and only the moving objects' are found again.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "frame/atmosphere.h"
#include "shanshui/core/error.h"
#include "shanshui/render/gl_check.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/strokes/brush.h"
#include "shanshui/strokes/chains.h"
#include "shanshui/strokes/edges.h"
#include "shanshui/strokes/visibility.h"

namespace shanshui::render {
namespace {

strokes::StrokeStyle brushStyle(scene::BrushStyle s) {
  switch (s) {
    case scene::BrushStyle::Qinxian:
      return strokes::StrokeStyle::Qinxian;
    case scene::BrushStyle::Liuye:
      return strokes::StrokeStyle::Liuye;
    case scene::BrushStyle::Zaohe:
      return strokes::StrokeStyle::Zaohe;
    case scene::BrushStyle::Jianbi:
      return strokes::StrokeStyle::Jianbi;
    case scene::BrushStyle::Zhuye:
      return strokes::StrokeStyle::Zhuye;
    case scene::BrushStyle::Mixed:
      return strokes::StrokeStyle::Mixed;
    case scene::BrushStyle::None:
      break;
  }
  return strokes::StrokeStyle::None;
}

// Per object with strokes: its mesh in uploaded coordinates and its edge graph (on load).
struct StrokeMesh {
  std::size_t object = 0;
  mesh::Mesh mesh;
  strokes::EdgeGraph graph;
};

// Per strip vertex: position (2), along, across, pressure, ink (the object's, times what the
// atmosphere and the border leave standing), colour (the object's line colour, 3).
constexpr int kFloats = 9;

class StrokesPass final : public RenderPass {
 public:
  explicit StrokesPass(const PassSetup& setup)
      : scene_(setup.scene), vao_(VertexArray::create()), vbo_(Buffer::create()) {
    for (std::size_t i = 0; i < setup.objects.size(); ++i) {
      if (!setup.scene.objects[i].strokes.enabled()) continue;
      SHANSHUI_CHECK(setup.objects[i].asset != nullptr);
      StrokeMesh s;
      s.object = i;
      s.mesh.positions = setup.objects[i].asset->mesh.positions;
      s.mesh.triangles = setup.objects[i].asset->mesh.triangles;
      const glm::dvec3 centre = setup.objects[i].model_bounds.centre();
      for (glm::dvec3& p : s.mesh.positions) p -= centre;
      s.graph = strokes::buildEdgeGraph(s.mesh);
      meshes_.push_back(std::move(s));
    }
    // The layer is worth keeping when something moves and something that stands still has strokes.
    static_strokes_ = setup.scene.hasAnimation() &&
                      std::any_of(meshes_.begin(), meshes_.end(),
                                  [&](const StrokeMesh& m) { return !setup.scene.objects[m.object].animated(); });
    buildPrograms();
  }

  std::string name() const override { return "strokes"; }
  void buildPrograms() override {
    Program strips({"brush_strokes.vert", "brush_strokes.frag"});
    if (static_strokes_) layer_program_ = Program({"fullscreen.vert", "brush_strokes_layer.frag"});
    program_ = std::move(strips);
  }
  std::vector<std::string> variants() const override { return {""}; }
  void setScene(const scene::Scene& s) override { scene_ = s; }
  void resize(int width, int height) override {
    target_ = Framebuffer(width, height, {GL_RGBA8}, false);
    if (static_strokes_) layer_ = Framebuffer(width, height, {GL_RGBA8}, false);
    layer_key_ = 0;
  }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    // Seed 002's render states: with animated objects, the static objects' strokes are drawn
    // into a layer only when the camera, size or parameters change, against the static
    // objects' own depth (so nothing that moves hides them in the layer), and composited
    // each frame under the animated objects' strokes.
    const bool animated = images.static_gbuffer != nullptr;
    if (animated && static_strokes_ && in.static_key != layer_key_) {
      if (in.timer) in.timer->begin("strokes_static");
      const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      glClearNamedFramebufferfv(layer_.id(), GL_COLOR, 0, clear);
      draw(strips(in, *images.static_gbuffer, Which::Static), layer_, true);
      layer_key_ = in.static_key;
      if (in.timer) in.timer->end();
    }
    if (in.timer) in.timer->begin(animated ? "strokes_animated" : "strokes");
    // Only the region that changed (copies ignore the scissor); the rest keeps its strokes.
    const glm::ivec4 r = in.region ? *in.region : glm::ivec4(0, 0, in.width, in.height);
    glCopyImageSubData(images.picture->id(), GL_TEXTURE_2D, 0, r.x, r.y, 0, target_.colour().id(), GL_TEXTURE_2D, 0,
                       r.x, r.y, 0, r.z - r.x, r.w - r.y, 1);
    if (animated && static_strokes_) composite(in, images);
    draw(strips(in, *images.gbuffer, animated ? Which::Animated : Which::All), target_, false);
    images.picture = &target_.colour();
    if (in.timer) in.timer->end();
  }

  enum class Which { All, Static, Animated };

  //! Strip vertices and the runs of each stroke.
  struct Strips {
    std::vector<float> vertices;
    std::vector<GLint> firsts;
    std::vector<GLsizei> counts;
  };

  //! The strokes of the chosen objects, visible against `gbuffer`'s depth.
  Strips strips(const FrameInputs& in, const Framebuffer& gbuffer, Which which) const {
    Strips out;
    const auto chosen = [&](const StrokeMesh& sm) {
      const bool moves = in.scene.objects[sm.object].animated();
      return which == Which::All || (which == Which::Animated) == moves;
    };
    if (std::none_of(meshes_.begin(), meshes_.end(), chosen)) return out;
    const int w = in.width, h = in.height;
    // The G-buffer's depth as the visibility reference (GL rows: bottom first).
    strokes::ReferenceImage ref;
    ref.width = w;
    ref.height = h;
    ref.depth.resize(static_cast<std::size_t>(w) * h);
    ref.id.assign(ref.depth.size(), -1);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(gbuffer.depth().id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(ref.depth.size() * sizeof(float)), ref.depth.data());
    const glm::dmat4 vp = glm::dmat4(in.camera.projection(static_cast<double>(w) / h)) * glm::dmat4(in.camera.view());
    const glm::dvec3 eye = in.camera.eye();
    const glm::dmat4 inverseVp = glm::inverse(vp);
    const glm::dvec2 fade = fadeRange(in);
    for (const StrokeMesh& sm : meshes_) {
      if (!chosen(sm)) continue;
      const scene::BrushStrokeParams& p = scene_.objects[sm.object].strokes;
      const glm::dmat4 model = in.modelAt(sm.object);
      const glm::dmat4 toModel = glm::inverse(model);
      const glm::dvec3 eyeModel = glm::dvec3(toModel * glm::dvec4(eye, 1.0));
      const auto edges = strokes::featureEdges(sm.graph, sm.mesh, eyeModel, p.crease_deg);
      strokes::VisibilityOptions vo;
      vo.near = in.camera.near_plane;
      vo.far = in.camera.far_plane;
      const auto seen = strokes::visibleSegments(edges, sm.graph, sm.mesh, vp * model, ref, vo);
      const auto chains = strokes::linkSegments(seen, {p.max_turn_deg, p.max_gap_px * h / 1024.0});
      const strokes::BrushOptions bo = brushOptions(p, h);
      const glm::vec3 colour(scene_.objects[sm.object].lines.line_color);
      for (std::size_t c = 0; c < chains.size(); ++c) {
        const double kept = strokes::lengthInk(chains[c].length_px, p.short_px * h / 1024.0);
        if (kept <= 0.0) continue;
        std::vector<double> depth;
        const auto path = strokes::cardinalSpline(strokes::subdivided(chains[c], std::max(4.0, 2.0 * bo.width_px)),
                                                  p.tension, 1.0, &depth);
        // The willow leaf's turn varies from stroke to stroke, the same each frame for a
        // stroke that starts at the same place.
        const glm::ivec2 start(glm::floor(chains[c].points.front() / 8.0));
        const std::uint64_t seed = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(start.x)) << 32) ^
                                   static_cast<std::uint32_t>(start.y) ^ (sm.object << 48);
        const auto strip = strokes::strokeStrip(path, brushStyle(p.style), seed, bo);
        if (strip.size() < 4) continue;
        out.firsts.push_back(static_cast<GLint>(out.vertices.size() / kFloats));
        out.counts.push_back(static_cast<GLsizei>(strip.size()));
        // Two strip vertices per path point; the ink at the point's 3D position.
        for (std::size_t k = 0; k < path.size(); ++k) {
          const glm::dvec4 ndc(path[k].x / w * 2.0 - 1.0, path[k].y / h * 2.0 - 1.0, depth[k] * 2.0 - 1.0, 1.0);
          const glm::dvec4 world = inverseVp * ndc;
          const auto ink =
              static_cast<float>(p.ink * kept * presence(in, sm.object, toModel, glm::dvec3(world) / world.w, fade));
          for (const strokes::StripVertex& v : {strip[2 * k], strip[2 * k + 1]}) {
            out.vertices.insert(out.vertices.end(), {static_cast<float>(v.position.x), static_cast<float>(v.position.y),
                                                     v.along, v.across, v.pressure, ink, colour.r, colour.g, colour.b});
          }
        }
      }
    }
    return out;
  }

  static strokes::BrushOptions brushOptions(const scene::BrushStrokeParams& p, int height) {
    strokes::BrushOptions bo;
    bo.width_px = std::clamp(p.width * height / 1024.0, 0.1, 256.0);
    bo.min_pressure = p.min_pressure;
    return bo;
  }

  //! Draws the strips over `target`; `premultiplied` accumulates them into an empty layer
  //! (colour times coverage, and coverage) that composite() lays over a picture later.
  void draw(const Strips& s, const Framebuffer& target, bool premultiplied) const {
    if (s.firsts.empty()) return;
    glNamedBufferData(vbo_.id(), static_cast<GLsizeiptr>(s.vertices.size() * sizeof(float)), s.vertices.data(),
                      GL_STREAM_DRAW);
    glBindVertexArray(vao_.id());
    glBindBuffer(GL_ARRAY_BUFFER, vbo_.id());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kFloats * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kFloats * sizeof(float),
                          reinterpret_cast<void*>(2 * sizeof(float)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 3, GL_FLOAT, GL_FALSE, kFloats * sizeof(float),
                          reinterpret_cast<void*>(6 * sizeof(float)));
    target.bind();
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, premultiplied ? GL_ONE : GL_ZERO,
                        premultiplied ? GL_ONE_MINUS_SRC_ALPHA : GL_ONE);
    program_.use();
    program_.set("u_size", glm::vec2(target.width(), target.height()));
    program_.set("u_bristle_px", static_cast<float>(std::max(2.0, 6.0 * target.height() / 1024.0)));
    glMultiDrawArrays(GL_TRIANGLE_STRIP, s.firsts.data(), s.counts.data(), static_cast<GLsizei>(s.firsts.size()));
    glDisable(GL_BLEND);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    SHANSHUI_GL_CHECK("strokes pass");
  }

  //! Lays the static strokes' layer over the picture (premultiplied "over"), except where an
  //! animated object now stands in front of the static surface a stroke lies on or overruns.
  void composite(const FrameInputs& in, const FrameImages& images) const {
    double width_px = 0.0;
    for (const StrokeMesh& sm : meshes_)
      if (!in.scene.objects[sm.object].animated())
        width_px = std::max(width_px, brushOptions(scene_.objects[sm.object].strokes, in.height).width_px);
    target_.bind();
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glBindVertexArray(vao_.id());
    layer_program_.use();
    glBindTextureUnit(0, layer_.colour().id());
    glBindTextureUnit(1, images.static_gbuffer->depth().id());
    glBindTextureUnit(2, images.gbuffer->depth().id());
    layer_program_.set("u_reach", static_cast<int>(std::ceil(0.5 * width_px)) + 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    SHANSHUI_GL_CHECK("strokes layer");
  }

 private:
  scene::Scene scene_;
  std::vector<StrokeMesh> meshes_;
  bool static_strokes_ = false;  //!< static objects' strokes are cached in layer_
  Program program_, layer_program_;
  VertexArray vao_;
  Buffer vbo_;
  Framebuffer target_, layer_;
  std::uint64_t layer_key_ = 0;  //!< FrameInputs::static_key layer_ was drawn for (0: none)
};

}  // namespace

std::unique_ptr<RenderPass> makeStrokesPass(const PassSetup& setup) {
  return std::make_unique<StrokesPass>(setup);
}

std::string strokesStructure(const scene::Scene& s) {
  std::string key = s.hasAnimation() ? "animated|" : "";
  for (const scene::Object& o : s.objects) key += std::to_string(static_cast<int>(o.strokes.style));
  return key;
}

}  // namespace shanshui::render
