// The ink-wash renderer (SPEC.md sections 6, 7, 10): a G-buffer pass, then one image pass
// for feature lines, interior shading (with wrinkles) and the composite on paper, built with
// only the shader variants the scene uses. The headless renderer and the viewer both draw through it.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shanshui/render/camera.h"
#include "shanshui/render/canvas_pass.h"
#include "shanshui/render/gl_resources.h"
#include "shanshui/render/gpu_mesh.h"
#include "shanshui/render/gpu_timer.h"
#include "shanshui/render/ink_diffusion_pass.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::render {

//! What one call of InkRenderer::render did.
struct FrameStats {
  bool cached = false;              //!< nothing changed: the previous image was presented
  double frame_ms = 0.0;            //!< CPU wall time of the call (including the wait when timing)
  std::vector<PassTime> passes;     //!< passes that ran, in order, with GPU milliseconds
};

//! The camera of a scene for one view: orbit parameters from the scene (or a path key),
//! target and distance framed on the world bounds when the scene leaves them out.
OrbitCamera sceneCamera(const scene::Scene& s, const mesh::Bounds& world_bounds, double aspect,
                        const scene::CameraKey& key);

//! The camera key of frame `index` of `count`: along camera.path when the scene has one,
//! else the scene camera turned by orbit_deg · index / count around +Z.
scene::CameraKey frameKey(const scene::Scene& s, int index, int count, double orbit_deg);

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

  //! Renders the view at `time` (seconds, for spinning objects) into an internal RGBA8
  //! framebuffer and returns it. Seed 002's render states: an identical request (camera,
  //! size, parameters, and time when something is animated) returns the cached image
  //! without running a pass; with animated objects the static ones are drawn into a cached
  //! layer ("gbuffer_static", only when the camera, size or parameters change) and the
  //! animated ones over a copy of it ("gbuffer_animated"). With timing, waits for the GPU and
  //! fills stats->passes with GPU times.
  const Framebuffer& render(const OrbitCamera& camera, int width, int height, FrameStats* stats = nullptr,
                            bool timing = true, double time = 0.0);

  //! Renders a frame of the scene's own camera (key) at the scene's output size and reads it
  //! back: RGB, row 0 at the top.
  image::Image renderImage(const scene::CameraKey& key, FrameStats* stats = nullptr, double time = 0.0);

  //! Recompiles every program from the current shader sources; on a compile error the old
  //! programs stay and the error is thrown.
  void reloadShaders();

  //! Pass names in execution order, and the defines each pass's programs were built with.
  const std::vector<std::string>& passesBuilt() const { return passes_; }
  const std::map<std::string, std::vector<std::string>>& variants() const { return variants_; }
  const mesh::Bounds& worldBounds() const { return world_bounds_; }
  std::size_t triangleCount() const;

  //! The last frame's images, for tests and debug views: "gbuffer" (colour 0: normal and
  //! dimensionless curvature, encoded — normalsAndCurvature() decodes them; 1: erosion
  //! noise, added noise, wrinkle luma, object id / 255; depth), "ink" (colour 0: the
  //! picture before diffusion; with debug outputs 1: line weight and col_i, 2: tone),
  //! "diffusion" (the picture after it, when the scene diffuses ink), "canvas" (colour 0:
  //! the canvas noise, R32F, unit variance; when the scene has one). Null for other names.
  const Framebuffer* passTarget(const std::string& pass) const;

  //! World positions of the last frame rebuilt from its depth buffer (as the ink pass does):
  //! RGBA, xyz and 1 where a surface was drawn, 0 on the background; row 0 at the top.
  image::Image worldPositions() const;

  //! The last frame's G-buffer normals (xyz, as interpolated and turned to the viewer) and
  //! dimensionless curvature (w), decoded from their 16-bit storage; row 0 at the top.
  //! Meaningful where worldPositions() has w = 1.
  image::Image normalsAndCurvature() const;

  //! The paper absorbency the diffusion uses when the scene has no canvas (value noise, one
  //! channel, tiled over the picture from GL's bottom-left); null otherwise.
  const Texture2D* absorbency() const { return absorbency_ ? &*absorbency_ : nullptr; }

  //! The canvas pass, when the scene has a canvas.
  const CanvasPass* canvas() const { return canvas_ ? &*canvas_ : nullptr; }

  //! Builds the ink pass with the DEBUG_OUTPUTS variant (line weight and tone as targets).
  void setDebugOutputs(bool on);

 private:
  struct GpuObject {
    GpuMesh mesh;                      //!< uploaded relative to the centre of model_bounds
    mesh::Bounds model_bounds;
    double model_feature_size = 0.0;   //!< model units
    glm::dmat4 model{1.0};             //!< uploaded coordinates to world (setScene)
    glm::dvec3 centre{0.0};            //!< world, of the bounding sphere
    double radius = 1.0;               //!< world bounding-sphere radius
    double feature_size = 0.0;         //!< world units
    double max_triangle_area = 0.0;    //!< model units, for the canvas
    int program = 0;                   //!< index into gbuffer_programs_
    std::optional<Texture2D> wrinkle;
  };
  struct GbufferProgram {
    std::vector<std::string> defines;
    Program program;
  };

  enum { kAllObjects, kStaticObjects, kAnimatedObjects };
  void drawObjects(const Framebuffer& target, bool clear, int which, const OrbitCamera& camera,
                   const glm::mat4& view_projection, double time);
  void buildPrograms();
  //! (Re)makes the textures drawn from the scene seed: erosion noise, paper absorbency.
  void seedNoise(const scene::Scene& s);
  void ensureTargets(int width, int height);
  void uploadObjectParams(const OrbitCamera& camera, int height);
  glm::dmat4 modelAt(std::size_t object, double time) const;
  std::string requestKey(const OrbitCamera& camera, int width, int height) const;

  scene::Scene scene_;
  std::vector<GpuObject> objects_;
  mesh::Bounds world_bounds_;
  std::vector<std::string> passes_;
  std::map<std::string, std::vector<std::string>> variants_;
  bool lines_ = false, shading_ = false, wrinkles_ = false, debug_outputs_ = false;

  std::vector<GbufferProgram> gbuffer_programs_;
  Program ink_program_;
  GLuint empty_vao_ = 0;
  GLuint params_buffer_ = 0;
  std::size_t params_capacity_ = 0;
  std::optional<Texture2D> noise_;
  std::optional<std::uint64_t> noise_seed_;  //!< the seed noise_ and absorbency_ were drawn from

  Framebuffer gbuffer_, static_gbuffer_, final_;
  Framebuffer diffused_;                        //!< the picture after ink diffusion
  std::optional<InkDiffusionPass> diffusion_;   //!< built only when the scene diffuses ink
  std::optional<Texture2D> absorbency_;
  std::optional<CanvasPass> canvas_;            //!< built only when the scene has a canvas
  const Texture2D* canvas_noise_ = nullptr;     //!< the last frame's canvas
  std::string static_layer_key_;  //!< request the static layer was drawn for
  GpuTimer timer_;
  std::string last_key_;
  glm::dmat4 last_inverse_view_projection_{1.0};

 public:
  InkRenderer(const InkRenderer&) = delete;
  InkRenderer& operator=(const InkRenderer&) = delete;
  ~InkRenderer();
};

}  // namespace shanshui::render
