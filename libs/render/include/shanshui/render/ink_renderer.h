// The ink-wash renderer (SPEC.md sections 6, 7, 10): the passes of render_pass.h's list
// that the scene wants (G-buffer, canvas, ink, diffusion), each built with only the shader
// variants the scene uses. The headless renderer and the viewer both draw through it.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shanshui/render/camera.h"
#include "shanshui/render/canvas_pass.h"
#include "shanshui/render/frame_params.h"
#include "shanshui/render/gl_resources.h"
#include "shanshui/render/gpu_mesh.h"
#include "shanshui/render/gpu_timer.h"
#include "shanshui/render/ink_diffusion_pass.h"
#include "shanshui/render/render_pass.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/grounding.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::render {

//! CPU wall time of one pass's run(): its submission, and any wait of the CPU on the GPU in it.
struct PassSubmit {
  std::string name;
  double cpu_ms = 0.0;
};

//! What one call of InkRenderer::render did.
struct FrameStats {
  bool cached = false;             //!< nothing changed: the previous image was presented
  double frame_ms = 0.0;           //!< CPU wall time of the call (including the wait when timing)
  std::vector<PassTime> passes;    //!< passes that ran, in order, with GPU milliseconds
  double redrawn = 1.0;            //!< share of the picture the passes drew (less when only animated objects changed)
  std::vector<PassSubmit> submit;  //!< each built pass's run(), in list order; empty when cached
  //! Uniform values the passes sent to the driver one call at a time (Program::set: a value
  //! the program already holds is not sent), besides the frame's block; 0 when cached.
  std::uint64_t uniforms_set = 0;
};

//! The camera of a scene for one view: orbit parameters from the scene (or a path key),
//! target and distance framed on the world bounds when the scene leaves them out, the
//! preset's elevation, field of view and framing when it has one. The high-distance preset
//! stands on the ground of `relief` (without one: on the bounds' floor, aiming at the top
//! of their centre); `fill` framing frames `inked` (the part of the bounds that is not
//! dissolved into paper; default: all of them), `drawn` framing the points `drawn` (what is
//! drawn of the land; without them, as `fill`).
OrbitCamera sceneCamera(const scene::Scene& s, const mesh::Bounds& world_bounds, double aspect,
                        const scene::CameraKey& key, const Relief* relief = nullptr,
                        const mesh::Bounds* inked = nullptr, const std::vector<glm::dvec3>* drawn = nullptr);

//! The elevation of the view the scene is composed for: its camera's, or its preset's.
double composedElevation(const scene::Scene& s);

//! The camera key of frame `index` of `count`: along camera.path when the scene has one,
//! else the scene camera turned by orbit_deg · index / count around +Z.
//! A fractional index gives the camera between frames (or, below 0, before the first).
scene::CameraKey frameKey(const scene::Scene& s, double index, int count, double orbit_deg);

class InkRenderer {
 public:
  //! Uploads the objects and compiles the programs the scene needs. `objects` come from
  //! scene::AssetCache::getAll(s). Needs a current GL 4.5 context.
  InkRenderer(const scene::Scene& s, const std::vector<scene::LoadedObject>& objects);

  //! A string that changes exactly when a scene change needs a new InkRenderer (files,
  //! object count, passes, shader variants); other changes go through setScene().
  static std::string structureKey(const scene::Scene& s);

  //! Takes new parameters; the scene must have the same structureKey.
  void setScene(const scene::Scene& s);
  const scene::Scene& scene() const { return scene_; }

  //! Renders the view at `time` (seconds, for spinning objects) and returns the target of
  //! the last pass that drew the picture (colour 0, RGBA8). Seed 002's render states: an identical request (camera,
  //! size, parameters, and time when something is animated) returns the cached image
  //! without running a pass; with animated objects the static ones are drawn into a cached
  //! layer ("gbuffer_static", only when the camera, size or parameters change) and the
  //! animated ones over a copy of it ("gbuffer_animated"). With timing, waits for the GPU and
  //! fills stats->passes with GPU times.
  //! `previous_camera`: where the camera was scene.motion_blur.interval earlier, for motion
  //! blur's velocities (null: where it is now).
  const Framebuffer& render(const OrbitCamera& camera, int width, int height, FrameStats* stats = nullptr,
                            bool timing = true, double time = 0.0, const OrbitCamera* previous_camera = nullptr);

  //! With late timing on, render() with timing does not wait for the GPU: it closes the
  //! frame's timestamps and returns (stats->passes empty), and lateTimes() reads them a few
  //! frames later, in order, so a benchmark can keep frames in flight. Turning it off waits
  //! for and drops the frames not read.
  void setLateTiming(bool on);
  //! The passes of the oldest frame rendered with late timing and not read yet: nothing
  //! when there is none, or (unless `wait`) when the GPU has not finished it.
  std::optional<std::vector<PassTime>> lateTimes(bool wait) { return timer_.collectLate(wait); }

  //! Renders a frame of the scene's own camera (key) at the scene's output size and reads it
  //! back: RGB, row 0 at the top.
  image::Image renderImage(const scene::CameraKey& key, FrameStats* stats = nullptr, double time = 0.0,
                           const scene::CameraKey* previous_key = nullptr);

  //! Recompiles every program from the current shader sources; on a compile error the old
  //! programs stay and the error is thrown.
  void reloadShaders();

  //! Pass names in execution order, and the defines each pass's programs were built with.
  const std::vector<std::string>& passesBuilt() const { return pass_names_; }
  const std::map<std::string, std::vector<std::string>>& variants() const { return variants_; }
  const mesh::Bounds& worldBounds() const { return world_bounds_; }
  //! The scene's relief (world coordinates, from up to 4096 points of each object).
  const Relief& relief() const { return relief_; }
  //! Object i's model-to-world matrix as drawn (grounded objects rest on their ground).
  const glm::dmat4& worldMatrix(std::size_t i) const { return world_[i]; }
  //! sceneCamera() for this scene, its bounds and relief.
  OrbitCamera camera(const scene::CameraKey& key, double aspect) const {
    return sceneCamera(scene_, world_bounds_, aspect, key, &relief_, &inked_bounds_, &drawn_);
  }
  std::size_t triangleCount() const;

  //! The last frame's images, for tests and debug views: "gbuffer" (colour 0: normal and
  //! dimensionless curvature, encoded — normalsAndCurvature() decodes them; 1: erosion
  //! noise, added noise, wrinkle luma, object id / 255; depth), "ink" (colour 0: the
  //! picture before diffusion; with debug outputs 1: line weight and col_i, 2: tone),
  //! "diffusion" (the picture after it, when the scene diffuses ink), "canvas" (colour 0:
  //! the canvas noise, R32F, unit variance; when the scene has one). Null for other names.
  const Framebuffer* passTarget(const std::string& pass) const;

  //! Tree and dot marks the last frame left out because the frame's buffer for them was full
  //! (RenderPass::marksDropped; which ones depends on the GPU's order, so a frame with any
  //! is not repeatable). Waits for the frame.
  std::size_t marksDropped() const;

  //! World positions of the last frame rebuilt from its depth buffer (as the ink pass does):
  //! RGBA, xyz and 1 where a surface was drawn, 0 on the background; row 0 at the top.
  image::Image worldPositions() const;

  //! The last frame's G-buffer normals (xyz, as interpolated and turned to the viewer) and
  //! dimensionless curvature (w), decoded from their 16-bit storage; row 0 at the top.
  //! Meaningful where worldPositions() has w = 1.
  image::Image normalsAndCurvature() const;

  //! The paper absorbency the diffusion uses when the scene has no canvas (value noise, one
  //! channel, tiled over the picture from GL's bottom-left); null otherwise.
  const Texture2D* absorbency() const;

  //! The canvas pass, when the scene has a canvas.
  const CanvasPass* canvas() const;

  //! Builds the ink pass with the DEBUG_OUTPUTS variant (line weight and tone as targets).
  void setDebugOutputs(bool on);

  InkRenderer(const InkRenderer&) = delete;
  InkRenderer& operator=(const InkRenderer&) = delete;
  ~InkRenderer();

 private:
  struct Built {
    const PassEntry* entry;
    std::unique_ptr<RenderPass> pass;
  };
  const RenderPass* find(const std::string& name) const;
  //! Model matrices, bounding spheres and the world bounds from the scene's transforms.
  void setObjects(const scene::Scene& s);
  void collectVariants();
  //! What a frame depends on besides its time: the size, the camera (and the one a frame
  //! ago, with motion blur) and `version_`. Compared field by field: nothing formatted or
  //! hashed per frame.
  struct Request {
    int width = 0, height = 0;
    std::array<double, 18> cameras{};  //!< this frame's camera, then the previous one's (or zeros)
    std::uint64_t version = 0;
    bool operator==(const Request&) const = default;
  };
  Request request(const OrbitCamera& camera, const OrbitCamera* previous, int width, int height) const;
  //! Something besides the camera and the size changed (the scene, the shaders, the debug
  //! outputs): the next frame is drawn in full.
  void invalidate() { ++version_; }
  //! Where the animated objects are, in GL pixels (x0, y0, x1, y1), grown by what the passes
  //! read around a pixel; none without animated objects.
  std::optional<glm::ivec4> animatedRegion(const FrameInputs& in) const;

  scene::Scene scene_;
  std::vector<SceneObjectGpu> objects_;
  mesh::Bounds world_bounds_;
  mesh::Bounds inked_bounds_;  //!< world bounds less the dissolving borders' falloff bands
  Relief relief_;
  //! Resolves where grounded objects stand (objects.N.ground); null when none is grounded.
  std::unique_ptr<scene::Grounding> grounding_;
  std::vector<glm::dvec3> drawn_;                       //!< relief samples inside the borders, above the water (world)
  std::vector<glm::dmat4> world_;                       //!< per object, model to world
  std::vector<std::vector<glm::dvec3>> relief_points_;  //!< per object, model coordinates
  std::vector<Built> passes_;
  std::vector<std::string> pass_names_;
  std::map<std::string, std::vector<std::string>> variants_;
  int width_ = 0, height_ = 0;
  const Framebuffer* last_output_ = nullptr;  //!< the picture's framebuffer
  GpuTimer timer_;
  bool late_timing_ = false;
  std::uint64_t version_ = 1;              //!< Request::version: bumped by invalidate()
  std::optional<Request> last_request_;    //!< the last frame's, none before the first
  double last_time_ = 0.0;                 //!< the last frame's time
  std::uint64_t static_key_ = 0;           //!< FrameInputs::static_key: counts the requests seen
  std::optional<glm::ivec4> last_moving_;  //!< the animated objects' region in the last frame
  glm::dmat4 last_inverse_view_projection_{1.0};
  Buffer frame_block_;                            //!< the frame's uniform block (frame_params.glsl)
  std::optional<gpu::FrameParams> frame_params_;  //!< what frame_block_ holds
};

}  // namespace shanshui::render
