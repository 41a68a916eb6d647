// The GPU pass of the empirical ink diffusion (seed 001, Eqs. 6-8; SPEC.md section 9), in
// compute shaders that follow the CPU reference in libs/ink step by step: ink of the
// picture; main region from a separable city-block distance transform (two sweeps per
// axis, cost independent of d); n boundary iterations, each one dispatch that fuses the
// reference's three gathers and leaves out the areas ink cannot reach; the picture with
// the ink change painted in.
#pragma once

#include <glm/glm.hpp>

#include "shanshui/image/image.h"
#include "shanshui/ink/diffusion.h"
#include "shanshui/render/gl_resources.h"
#include "shanshui/render/gpu_timer.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

//! The paper under the ink, beyond its colour: an absorbency image (one channel, tiled over
//! the picture) read through clamp(offset + scale · value, 0, 1), and optionally the
//! canvas (RG16F the size of the picture: unit-variance grain, and the paper's marks as a
//! brightness change) that multiplies the result by (1 + contrast · grain)(1 + marks).
struct PaperTexture {
  const Texture2D* absorbency = nullptr;
  glm::vec2 absorbency_map{1.0f, 0.0f};  //!< scale, offset
  const Texture2D* grain = nullptr;
  float contrast = 0.0f;
};

class InkDiffusionPass {
 public:
  //! Compiles the programs; needs a current GL 4.5 context.
  InkDiffusionPass();

  //! Diffuses the ink of `colour` (an RGBA8 picture on `paper`); `absorbency` (one channel
  //! in [0, 1], tiled over the picture) scales what each pixel absorbs. Returns the result
  //! (RGBA8, same size). With a timer, the pass is timed as "diffusion".
  const Texture2D& run(const Texture2D& colour, const Texture2D& absorbency, const ink::DiffusionOptions& options,
                       const glm::vec3& paper, GpuTimer* timer = nullptr);
  //! The same, writing into `output` (RGBA8, the size of `colour`; may be `colour` itself).
  void run(const Texture2D& colour, const Texture2D& absorbency, const ink::DiffusionOptions& options,
           const glm::vec3& paper, const Texture2D& output, GpuTimer* timer = nullptr);
  //! The same with a textured paper (PaperTexture::absorbency must be set). With a
  //! `region` (GL pixels x0, y0, x1, y1), only the pixels in it are computed and written,
  //! exactly as a whole run would: the caller promises that `colour` changed nowhere else
  //! since the last run (same size and options) and that `output` outside it holds that
  //! run's result. The work covers the region grown by dependence(options).
  void run(const Texture2D& colour, const PaperTexture& texture, const ink::DiffusionOptions& options,
           const glm::vec3& paper, const Texture2D& output, GpuTimer* timer = nullptr,
           const glm::ivec4* region = nullptr);
  //! How far (pixels, Chebyshev) a change of the picture can move the result: d + 3n.
  static int dependence(const ink::DiffusionOptions& options);
  //! The window the last run computed (pixels x0, y0, x1, y1).
  glm::ivec4 lastWindow() const { return last_window_; }

  //! The ink field after the last whole run (one channel, row 0 at the top), for tests.
  image::Image inkAfter() const;
  //! The share of the picture's work-group areas that the last whole run's boundary
  //! iterations computed: 1 when ink above the residual could reach every area, 0 without
  //! iterations (reads back a small image; for tests and benches; after a region run it
  //! mixes that run's window with older runs' areas).
  double lastActiveFraction() const;
  //! The pixels one work group of the boundary iterations covers (the unit left out).
  static glm::ivec2 workGroupArea();

 private:
  void ensureSize(int width, int height);
  //! Marks in `reached` (one texel per `area` of pixels) the areas within `pixels` of a
  //! block marked in `marks`.
  //! `window` is the range of `reached` texels to compute (x0, y0, x1, y1).
  void reach(const Texture2D& marks, const Texture2D& reached, glm::ivec2 area, int pixels, glm::ivec4 window) const;
  //! The GPU's layout (pixelPassesAsCompute): wider boundary work groups, and the main
  //! region gathered (rings_) for small d instead of swept; the same ink either way.
  bool gpu_layout_ = false;
  Program extract_, rows_, columns_, rings_, reach_, boundary_, output_;
  Program output_canvas_;  //!< built on first use with a canvas grain
  Texture2D capacity_, main_, next_, nearest_, out_;
  Texture2D seeds_, strokes_,
      near_;              //!< one texel per block: ink above the residual or a stroke, strokes, near a stroke
  Texture2D active_tex_;  //!< one texel per work-group area: where anything can change (iterations, output)
  const Texture2D* after_ = nullptr;
  int last_iterations_ = 0;  //!< n of the last run
  glm::ivec4 last_window_{0};
};

//! The paper absorbency of the renderer's diffusion pass when the scene has no canvas
//! (value noise, one channel, tiled over the picture from GL's bottom-left); null for any
//! other pass or with a canvas.
const Texture2D* absorbencyOf(const RenderPass& pass);

}  // namespace shanshui::render
