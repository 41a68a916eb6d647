// The brush strokes pass (seed 002, issue 24): each frame, the feature edges of every object
// with strokes are found on the CPU (strokes/edges.h), kept where the G-buffer's depth shows
// them (visibility.h), linked into chains and drawn as brush strips over the ink picture,
// so diffusion and the canvas act on them as on any ink.
#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

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

double smooth01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

// How much of a stroke at `world` stands against the paper: the distance fade, the mist and
// the dissolving border of ink_surface.glsl's presence(), with their noise at its mean (a
// stroke is thin; the surface beside it carries the noise).
double presence(const FrameInputs& in, std::size_t object, const glm::dmat4& toModel, glm::dvec3 world,
                glm::dvec2 fadeRange) {
  const scene::Scene& s = in.scene;
  double f = 1.0 - s.output.fade * smooth01((glm::length(world - in.camera.eye()) - fadeRange.x) /
                                            std::max(fadeRange.y - fadeRange.x, 1e-9));
  if (s.mist.enabled()) {
    const double z0 = in.world_bounds.min.z, extent = std::max(in.world_bounds.size().z, 1e-9);
    const double h0 = (world.z - (z0 + s.mist.height * extent)) / std::max(s.mist.softness * extent, 1e-9);
    f *= 1.0 - s.mist.density * (1.0 - smooth01(h0));
  }
  const scene::Object& o = s.objects[object];
  if (o.dissolvesBorder()) {
    const glm::dvec3 m = glm::dvec3(toModel * glm::dvec4(world, 1.0));
    const glm::dvec3 half = 0.5 * in.objects[object].model_bounds.size();
    const double width = o.border.width * std::min(half.x, half.y);
    const double t = std::min(half.x - std::abs(m.x), half.y - std::abs(m.y)) / std::max(width, 1e-12);
    f *= smooth01(t - 0.5 * o.border.roughness);
  }
  return std::clamp(f, 0.0, 1.0);
}

// Per object with strokes: its mesh in uploaded coordinates and its edge graph (on load).
struct StrokeMesh {
  std::size_t object = 0;
  mesh::Mesh mesh;
  strokes::EdgeGraph graph;
};

// Per strip vertex: position (2), along, across, pressure, ink (the object's, times what the
// atmosphere and the border leave standing).
constexpr int kFloats = 6;

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
    buildPrograms();
  }

  std::string name() const override { return "strokes"; }
  void buildPrograms() override { program_ = Program({"brush_strokes.vert", "brush_strokes.frag"}); }
  std::vector<std::string> variants() const override { return {""}; }
  void setScene(const scene::Scene& s) override { scene_ = s; }
  void resize(int width, int height) override { target_ = Framebuffer(width, height, {GL_RGBA8}, false); }
  const Framebuffer* target() const override { return &target_; }

  void run(const FrameInputs& in, FrameImages& images) override {
    SHANSHUI_CHECK(images.picture != nullptr && images.gbuffer != nullptr);
    if (in.timer) in.timer->begin("strokes");
    const int w = in.width, h = in.height;
    glCopyImageSubData(images.picture->id(), GL_TEXTURE_2D, 0, 0, 0, 0, target_.colour().id(), GL_TEXTURE_2D, 0, 0, 0,
                       0, w, h, 1);
    // The G-buffer's depth as the visibility reference (GL rows: bottom first).
    strokes::ReferenceImage ref;
    ref.width = w;
    ref.height = h;
    ref.depth.resize(static_cast<std::size_t>(w) * h);
    ref.id.assign(ref.depth.size(), -1);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(images.gbuffer->depth().id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(ref.depth.size() * sizeof(float)), ref.depth.data());
    const glm::dmat4 vp = glm::dmat4(in.camera.projection(static_cast<double>(w) / h)) * glm::dmat4(in.camera.view());
    const glm::dvec3 eye = in.camera.eye();
    const glm::dmat4 inverseVp = glm::inverse(vp);
    // The distance fade's range, as the ink pass sets it: the scene's nearest and farthest corners.
    glm::dvec2 fadeRange(1e300, 0.0);
    for (int c = 0; c < 8; ++c) {
      const double d = glm::length(in.world_bounds.corner(c) - eye);
      fadeRange = {std::min(fadeRange.x, d), std::max(fadeRange.y, d)};
    }
    std::vector<float> vertices;
    std::vector<GLint> firsts;
    std::vector<GLsizei> counts;
    for (const StrokeMesh& sm : meshes_) {
      const scene::BrushStrokeParams& p = scene_.objects[sm.object].strokes;
      const glm::dmat4 model = in.modelAt(sm.object);
      const glm::dmat4 toModel = glm::inverse(model);
      const glm::dvec3 eyeModel = glm::dvec3(toModel * glm::dvec4(eye, 1.0));
      const auto edges = strokes::featureEdges(sm.graph, sm.mesh, eyeModel, p.crease_deg);
      strokes::VisibilityOptions vo;
      vo.near = in.camera.near_plane;
      vo.far = in.camera.far_plane;
      const auto seen = strokes::visibleSegments(edges, sm.graph, sm.mesh, vp * model, ref, vo);
      const auto chains = strokes::linkSegments(seen, {p.max_turn_deg, p.max_gap_px});
      strokes::BrushOptions bo;
      bo.width_px = std::clamp(p.width * h / 1024.0, 0.1, 256.0);
      bo.min_pressure = p.min_pressure;
      for (std::size_t c = 0; c < chains.size(); ++c) {
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
        firsts.push_back(static_cast<GLint>(vertices.size() / kFloats));
        counts.push_back(static_cast<GLsizei>(strip.size()));
        // Two strip vertices per path point; the ink at the point's 3D position.
        for (std::size_t k = 0; k < path.size(); ++k) {
          const glm::dvec4 ndc(path[k].x / w * 2.0 - 1.0, path[k].y / h * 2.0 - 1.0, depth[k] * 2.0 - 1.0, 1.0);
          const glm::dvec4 world = inverseVp * ndc;
          const auto ink =
              static_cast<float>(p.ink * presence(in, sm.object, toModel, glm::dvec3(world) / world.w, fadeRange));
          for (const strokes::StripVertex& v : {strip[2 * k], strip[2 * k + 1]}) {
            vertices.insert(vertices.end(), {static_cast<float>(v.position.x), static_cast<float>(v.position.y),
                                             v.along, v.across, v.pressure, ink});
          }
        }
      }
    }
    if (!firsts.empty()) {
      glNamedBufferData(vbo_.id(), static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(),
                        GL_STREAM_DRAW);
      glBindVertexArray(vao_.id());
      glBindBuffer(GL_ARRAY_BUFFER, vbo_.id());
      glEnableVertexAttribArray(0);
      glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, kFloats * sizeof(float), nullptr);
      glEnableVertexAttribArray(1);
      glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, kFloats * sizeof(float),
                            reinterpret_cast<void*>(2 * sizeof(float)));
      glBindFramebuffer(GL_FRAMEBUFFER, target_.id());
      glViewport(0, 0, w, h);
      glDisable(GL_DEPTH_TEST);
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      program_.use();
      program_.set("u_size", glm::vec2(w, h));
      program_.set("u_bristle_px", static_cast<float>(std::max(2.0, 6.0 * h / 1024.0)));
      glMultiDrawArrays(GL_TRIANGLE_STRIP, firsts.data(), counts.data(), static_cast<GLsizei>(firsts.size()));
      glDisable(GL_BLEND);
      glBindBuffer(GL_ARRAY_BUFFER, 0);
      SHANSHUI_GL_CHECK("strokes pass");
    }
    images.picture = &target_.colour();
    if (in.timer) in.timer->end();
  }

 private:
  scene::Scene scene_;
  std::vector<StrokeMesh> meshes_;
  Program program_;
  VertexArray vao_;
  Buffer vbo_;
  Framebuffer target_;
};

}  // namespace

std::unique_ptr<RenderPass> makeStrokesPass(const PassSetup& setup) {
  return std::make_unique<StrokesPass>(setup);
}

std::string strokesStructure(const scene::Scene& s) {
  std::string key;
  for (const scene::Object& o : s.objects) key += std::to_string(static_cast<int>(o.strokes.style));
  return key;
}

}  // namespace shanshui::render
