// The paper canvas (seed 001 Eqs. 9-17, SPEC.md section 8): paper that moves with the scene
// yet keeps its grain size on screen. `tiles` (the default) pins copies of a precomputed
// noise tile to the surfaces in one full-screen pass; `splat` scatters seed 001's noise
// kernels on every visible triangle and a background dome with a geometry shader (the
// reference); `static` draws the same kernels fixed to the screen. The result is
// unit-variance noise in a float target that the ink pass turns into paper brightness and
// the diffusion into absorbency.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shanshui/noise/canvas.h"
#include "shanshui/render/camera.h"
#include "shanshui/render/gl_resources.h"
#include "shanshui/render/gpu_mesh.h"
#include "shanshui/render/gpu_timer.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/scene.h"

namespace shanshui::render {

class CanvasPass {
 public:
  //! One mesh to cover: the mesh, its model matrix (uploaded coordinates to world), its
  //! largest triangle's area and bounding radius about the origin (uploaded units; they
  //! size the geometry shader's work).
  struct Item {
    const GpuMesh* mesh = nullptr;
    glm::dmat4 model{1.0};
    double max_triangle_area = 0.0;
    double radius = 0.0;
  };

  //! Programs for the scene's canvas type and method (type not None) and its number of
  //! objects. The background dome is centred on `world_bounds` with 20 times its radius.
  CanvasPass(const scene::Canvas& canvas, std::uint64_t seed, const mesh::Bounds& world_bounds,
             std::size_t objects = 1);

  //! New parameters (same type and pattern) and scene seed.
  void setParams(const scene::Canvas& canvas, std::uint64_t seed);

  //! Recompiles the programs from the current shader sources (hot reload); on an error
  //! the old ones stay and the error is thrown.
  void reloadShaders();
  //! The defines of each program built.
  std::vector<std::string> variants() const;

  //! Draws the canvas of the view into the target (width × height, RG16F: the grain's unit-
  //! variance noise, and the paper's marks as a brightness change) and returns it. Half
  //! floats: the grain rounds by under 0.2 % of its σ, and the target costs the pass and each
  //! reader less memory traffic than RG32F (canvas −0.3 ms, ink pass −0.9 at 1024x768).
  //! `gbuffer` is the G-buffer of the frame (depth, and the object ids in colour 1), and
  //! `attachable_depth` the copy of its depth that the tiles canvas attaches for its depth
  //! test (FrameImages::attachable_depth). The static canvas is drawn only when the size or
  //! the parameters change.
  const Texture2D& run(const std::vector<Item>& items, const Framebuffer& gbuffer, const Texture2D& attachable_depth,
                       const OrbitCamera& camera, int width, int height, GpuTimer* timer);

  //! The last canvas drawn.
  const Framebuffer& target() const { return target_; }

  //! The noise options in pixels for an output `height` pixels tall.
  noise::CanvasNoiseOptions noiseOptions(int height) const;
  //! Pass name for statistics: "canvas" or "canvas_static".
  const char* passName() const { return method_ == Method::Static ? "canvas_static" : "canvas"; }
  //! The `tiles` canvas's tile as it is stored (8-bit steps of 1 / 127: zero mean, variance
  //! 1 / kTileRange²), row 0 at the top; empty before the first frame and for the other
  //! methods.
  image::Image tile() const;
  //! The noise options the tile was drawn with (texels of the tile).
  const noise::CanvasNoiseOptions& tileOptions() const { return tile_options_; }
  //! Kernel cells across the tile: kTileCells (twice that for silk), fewer for large N′.
  int tileCells() const { return tile_cells_; }
  bool usesTiles() const { return method_ == Method::Tiles; }

  //! Kernels one geometry-shader invocation can emit, and the per-triangle cap (splat).
  int quadsPerInvocation() const { return quads_; }
  int cap() const { return quads_ * kInvocations; }
  glm::dvec3 domeCentre() const { return dome_centre_; }
  double domeRadius() const { return dome_radius_; }

  static constexpr int kInvocations = 32;
  //! Kernel cells across the `tiles` canvas's square tile (twice that for silk): 16 (a 512²
  //! tile for the default rice paper) cost the sample scene's canvas 7 % less than 32, whose
  //! tile outgrows the caches; each copy shows under a quarter of it.
  static constexpr int kTileCells = 16;
  //! Most kernel evaluations (texels × N′) spent on drawing a tile: twice the default's.
  static constexpr double kTileWork = 2.0 * 1024 * 1024 * 32;
  //! Spacing of the rice paper mottle's lattice, pixels at 1024 high: patches about this big.
  static constexpr double kMottlePixels = 96.0;
  //! Screen area, in lattice spacings², over which a point's fibre or spot shows where its
  //! level's spacing is one (the shader scales it by the spacing²).
  static constexpr double kMarkRegion = 0.8;
  //! The tile stores v / kTileRange, clamped to [-1, 1] (σ = 1).
  static constexpr double kTileRange = 4.0;
  //! Rice paper's marks come in kMarkVariants shapes (a power of two), each a sprite of
  //! kMarkSprite² texels around its lattice point (a power of two).
  static constexpr int kMarkVariants = 64, kMarkSprite = 64;

  //! The fibre (signed: most darken) and spot of mark shape `variant`, each in [-1, 1], in a
  //! sprite of `size`² texels centred on the lattice point's projection, `texels_per_pixel`
  //! of them a pixel: rows from the bottom, two values a texel. Fibres' mean half length and
  //! half width, and spots' largest radius, in pixels.
  static std::vector<float> markSprite(int variant, int size, double texels_per_pixel, double half_length,
                                       double half_width, double spot_radius);
  //! The marks' sizes in pixels in frames `height` high: fibres' mean half length (from the
  //! mean length `fibre_length` at 1024 high) and half width, and spots' largest radius.
  struct MarkSizes {
    double half_length, half_width, spot_radius;
  };
  static MarkSizes markSizes(double fibre_length, int height);
  //! Texels per pixel of the sprites that hold marks of these sizes (pixels) whole.
  static double markTexelsPerPixel(int size, double half_length, double half_width, double spot_radius);

 private:
  enum class Method { Splat, Tiles, Static };
  void setKernel(const Program& p, const noise::CanvasNoiseOptions& o) const;
  //! Draws the tile for options `o` (pixels) unless it is already drawn for them.
  void updateTile(const noise::CanvasNoiseOptions& o);
  void runTiles(const std::vector<Item>& items, const Framebuffer& gbuffer, const Texture2D& attachable_depth,
                const OrbitCamera& camera, int width, int height, const noise::CanvasNoiseOptions& o);
  //! The rice paper marks' uniforms of `p`, for an output `height` tall whose grain lattice
  //! is `lattice_pixels` apart on screen.
  void setMarks(const Program& p, int height, double lattice_pixels) const;
  //! Draws the fibres' and spots' shapes for frames `height` pixels high, when they changed.
  void updateMarkSprites(int height);
  //! Draws rice paper's mottle into its small image, binds it to image unit 1 and returns
  //! the pixels of the view per texel.
  float drawMottle(const OrbitCamera& camera, int width, int height);
  void runSplat(const std::vector<Item>& items, const Texture2D& depth, const OrbitCamera& camera, int width,
                int height, const noise::CanvasNoiseOptions& o);
  std::vector<std::string> definesFor(int invocations) const;
  //! The tiles canvas's programs: the surfaces', or with `background` the background's.
  std::vector<std::string> tilesDefines(bool background) const;
  //! Writes the dome triangles the camera can see into the element buffer; index count.
  GLsizei uploadVisibleDome(const glm::dmat4& model_view_projection);

  scene::Canvas canvas_;
  std::vector<std::string> defines_;  //!< the pattern's
  std::size_t objects_ = 1;
  std::uint32_t seed_ = 0;
  Method method_ = Method::Tiles;
  int quads_ = 0;
  Program single_, multi_, static_;                    //!< geometry shader with 1 or kInvocations invocations; static
  Program tiles_, tiles_background_, tile_synthesis_;  //!< the tiles canvas (surfaces, background), and its tile
  bool compute_ = false;  //!< tiles_ and tiles_background_ are compute shaders (pixelPassesAsCompute)
  Program mottle_;        //!< rice paper's mottle (tiles)
  Framebuffer mottle_target_;
  Buffer tile_bytes_;         //!< the tile, rows from the bottom, one signed byte a texel
  BufferTexture tile_;        //!< tile_bytes_ as R8I texels (the shaders index it: y · size + x)
  int tile_size_ = 0;         //!< texels on a side
  Buffer mark_bytes_;         //!< kMarkVariants sprites of kMarkSprite² texels (fibre, spot: signed bytes)
  BufferTexture marks_;       //!< mark_bytes_ as RG8I texels
  double mark_texels_ = 1.0;  //!< sprite texels per pixel
  // What the sprites and the tile were drawn for, compared number by number each frame.
  std::optional<std::array<double, 3>> marks_key_;
  std::optional<std::array<double, 9>> tile_key_;
  noise::CanvasNoiseOptions tile_options_;
  int tile_cells_ = kTileCells;
  float texels_per_pixel_ = 1.0f;
  Buffer spaces_;                          //!< per object + background: clip ↔ model matrices (tiles)
  std::vector<glm::vec3> dome_positions_;  //!< relative to dome_centre_
  std::vector<glm::uvec3> dome_triangles_;
  VertexArray dome_vao_;
  Buffer dome_positions_buffer_, dome_visible_buffer_;
  glm::dvec3 dome_centre_{0.0};
  double dome_radius_ = 1.0;
  Framebuffer target_;
  Framebuffer splat_sums_;  //!< the splatted kernels' sums (RG32F), copied into target_
  VertexArray empty_vao_;
  std::optional<std::array<int, 2>> static_key_;  //!< the size the static canvas was drawn at

 public:
  CanvasPass(const CanvasPass&) = delete;
  CanvasPass& operator=(const CanvasPass&) = delete;
};

//! The CanvasPass of the renderer's canvas pass; null for any other pass.
const CanvasPass* canvasOf(const RenderPass& pass);

//! The largest triangle area of a mesh.
double maxTriangleArea(const mesh::Mesh& m);

//! The canvas kernels' 32-bit seed for a scene seed (decorrelated from the other noises
//! the scene seed draws).
std::uint32_t canvasSeed(std::uint64_t scene_seed);

}  // namespace shanshui::render
