#include "shanshui/render/ink_diffusion_pass.h"

#include <utility>

#include "shanshui/core/error.h"
#include "shanshui/render/gl_check.h"

namespace shanshui::render {

namespace {

void bindImage(GLuint unit, const Texture2D& t, GLenum access) {
  glBindImageTexture(unit, t.id(), 0, GL_FALSE, 0, access, t.format());
}

void barrier() { glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT); }

GLuint groups(int n, int size) { return static_cast<GLuint>((n + size - 1) / size); }

}  // namespace

InkDiffusionPass::InkDiffusionPass()
    : extract_({"ink_diffusion_extract.comp"}),
      rows_({"ink_diffusion_rows.comp"}),
      columns_({"ink_diffusion_columns.comp"}),
      demand_({"ink_diffusion_demand.comp"}),
      supply_({"ink_diffusion_supply.comp"}),
      apply_({"ink_diffusion_apply.comp"}),
      output_({"ink_diffusion_output.comp"}) {}

void InkDiffusionPass::ensureSize(int width, int height) {
  if (out_.width() == width && out_.height() == height) return;
  for (Texture2D* t : {&ink0_, &main_, &next_, &demand_tex_, &supply_tex_, &source_}) *t = Texture2D(width, height, GL_R32F);
  distance_ = Texture2D(width, height, GL_R32I);
  out_ = Texture2D(width, height, GL_RGBA8);
}

const Texture2D& InkDiffusionPass::run(const Texture2D& colour, const Texture2D& absorbency,
                                       const ink::DiffusionOptions& o, const glm::vec3& paper, GpuTimer* timer) {
  ensureSize(colour.width(), colour.height());
  run(colour, absorbency, o, paper, out_, timer);
  return out_;
}

void InkDiffusionPass::run(const Texture2D& colour, const Texture2D& absorbency, const ink::DiffusionOptions& o,
                           const glm::vec3& paper, const Texture2D& output, GpuTimer* timer) {
  run(colour, PaperTexture{&absorbency}, o, paper, output, timer);
}

void InkDiffusionPass::run(const Texture2D& colour, const PaperTexture& texture, const ink::DiffusionOptions& o,
                           const glm::vec3& paper, const Texture2D& output, GpuTimer* timer) {
  ink::validate(o);
  SHANSHUI_CHECK(texture.absorbency != nullptr);
  const int w = colour.width(), h = colour.height();
  SHANSHUI_CHECK(output.width() == w && output.height() == h && output.format() == GL_RGBA8);
  ensureSize(w, h);
  if (timer) timer->begin("diffusion");
  const GLuint gx = groups(w, 16), gy = groups(h, 16);

  extract_.use();
  extract_.set("u_paper", paper);
  glBindTextureUnit(0, colour.id());
  bindImage(0, ink0_, GL_WRITE_ONLY);
  glDispatchCompute(gx, gy, 1);
  barrier();

  // Main region: rows, then columns (which also write the main-region ink).
  rows_.use();
  rows_.set("u_threshold", static_cast<float>(o.threshold));
  bindImage(0, ink0_, GL_READ_ONLY);
  bindImage(1, distance_, GL_READ_WRITE);
  bindImage(2, source_, GL_READ_WRITE);
  glDispatchCompute(groups(h, 64), 1, 1);
  barrier();
  columns_.use();
  columns_.set("u_ring_steps", o.ring_steps);
  columns_.set("u_attenuation", static_cast<float>(o.attenuation));
  bindImage(3, main_, GL_WRITE_ONLY);
  glDispatchCompute(groups(w, 64), 1, 1);
  barrier();

  // Boundary diffusion: n iterations, ping-pong between main_ and next_.
  Texture2D* cur = &main_;
  Texture2D* nxt = &next_;
  glBindTextureUnit(0, texture.absorbency->id());
  // Uniforms are program state: set once, not per iteration.
  if (o.iterations > 0) {
    demand_.set("u_capacity", static_cast<float>(o.absorb / o.iterations));
    demand_.set("u_residual", static_cast<float>(o.residual));
    demand_.set("u_threshold", static_cast<float>(o.threshold));
    demand_.set("u_absorbency_map", texture.absorbency_map);
    supply_.set("u_residual", static_cast<float>(o.residual));
  }
  for (int it = 0; it < o.iterations; ++it) {
    demand_.use();
    bindImage(0, *cur, GL_READ_ONLY);
    bindImage(1, ink0_, GL_READ_ONLY);
    bindImage(2, demand_tex_, GL_READ_WRITE);
    glDispatchCompute(gx, gy, 1);
    barrier();
    supply_.use();
    bindImage(3, supply_tex_, GL_READ_WRITE);
    glDispatchCompute(gx, gy, 1);
    barrier();
    apply_.use();
    bindImage(4, *nxt, GL_WRITE_ONLY);
    glDispatchCompute(gx, gy, 1);
    barrier();
    std::swap(cur, nxt);
  }
  after_ = cur;

  const Program* out = &output_;
  if (texture.grain) {
    if (!output_canvas_.id()) output_canvas_ = Program({"ink_diffusion_output.comp"}, {"CANVAS"});
    out = &output_canvas_;
    out->set("u_canvas_contrast", texture.contrast);
    glBindTextureUnit(1, texture.grain->id());
  }
  out->use();
  out->set("u_paper", paper);
  glBindTextureUnit(0, colour.id());
  bindImage(0, ink0_, GL_READ_ONLY);
  bindImage(1, *cur, GL_READ_ONLY);
  bindImage(2, output, GL_WRITE_ONLY);
  glDispatchCompute(gx, gy, 1);
  barrier();
  if (timer) timer->end();
  SHANSHUI_GL_CHECK("diffusion pass");
}

}  // namespace shanshui::render
