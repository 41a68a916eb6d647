// The renderer's passes behind one interface, and the one list of them (pass_list.cpp).
// The renderer builds the passes the scene wants, in list order, hands each frame's
// inputs and the images made so far to each, times them, and shows the last picture.
// Adding a pass: its shaders, one source file with a RenderPass, one line in passList(),
// its keys in the scene's parameter description, its tests (docs/render.md, "Adding a pass").
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shanshui/pigment/kubelka_munk.h"
#include "shanshui/render/camera.h"
#include "shanshui/render/gl_resources.h"
#include "shanshui/render/gpu_mesh.h"
#include "shanshui/render/gpu_timer.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::render {

//! One object of the scene on the GPU, shared by the passes.
struct SceneObjectGpu {
  GpuMesh mesh;  //!< uploaded relative to the centre of model_bounds
  mesh::Bounds model_bounds;
  double model_feature_size = 0.0;  //!< model units
  double max_triangle_area = 0.0;   //!< model units
  std::optional<Texture2D> wrinkle;
  glm::dmat4 model{1.0};      //!< uploaded coordinates to world (from the scene's transform)
  glm::dvec3 centre{0.0};     //!< world, of the bounding sphere
  double radius = 1.0;        //!< world bounding-sphere radius
  double feature_size = 0.0;  //!< world units
  //! The loaded mesh (model coordinates), kept for passes that work on the CPU (strokes).
  std::shared_ptr<const scene::ObjectAsset> asset;
  //! Trees and moss dots grown on it (model coordinates); null when it grows none.
  std::shared_ptr<const scene::ElementSet> elements;
};

//! What every pass of a frame reads.
struct FrameInputs {
  const scene::Scene& scene;
  const std::vector<SceneObjectGpu>& objects;
  const mesh::Bounds& world_bounds;
  const OrbitCamera& camera;
  int width = 0, height = 0;
  double time = 0.0;  //!< seconds, for spinning objects
  //! Changes when anything but the time changes (the camera, the size, the scene, the
  //! shaders); never 0, so a pass may keep 0 for "nothing drawn".
  std::uint64_t static_key = 0;
  GpuTimer* timer = nullptr;  //!< time each pass under its name when set
  //! The camera a frame ago (motion blur's velocities); null: the same as now.
  const OrbitCamera* previous_camera = nullptr;
  //! When set, only this region (GL pixels x0, y0, x1, y1; the scissor is set to it) changed
  //! since the last frame: passes may draw only there, their targets keep the rest.
  const glm::ivec4* region = nullptr;
  //! The pixels a pass draws: the region, or the whole frame (a compute shader's rectangle).
  glm::ivec4 drawn() const { return region ? *region : glm::ivec4(0, 0, width, height); }

  //! Model matrix of object i at the frame's time, or at time t.
  glm::dmat4 modelAt(std::size_t i) const { return modelAt(i, time); }
  glm::dmat4 modelAt(std::size_t i, double t) const;
  glm::mat4 viewProjection() const;
  //! The previous frame's camera's (scene.motion_blur.interval earlier).
  glm::dmat4 previousViewProjection() const;
};

//! The images the passes hand on; a pass reads what earlier passes wrote.
struct FrameImages {
  const Framebuffer* gbuffer = nullptr;  //!< normal + curvature, surface + id, depth
  //! A copy of the G-buffer's depth, made once a frame, for the image passes to attach: their
  //! depth test against it keeps each program to the surfaces or to the background, while
  //! they sample the G-buffer's own depth (sampling a texture that is attached would be a
  //! feedback loop).
  const Texture2D* attachable_depth = nullptr;
  //! With animated objects: the cached G-buffer of the static ones alone (null otherwise).
  const Framebuffer* static_gbuffer = nullptr;
  const Texture2D* canvas = nullptr;   //!< paper: unit-variance grain, marks (RG16F)
  const Texture2D* picture = nullptr;  //!< the picture so far (RGBA8)
  const Texture2D* shadow = nullptr;   //!< 0 lit .. 1 in shadow (R8), when the shadow pass ran
  //! The elements' ink (r; R8) and, with animated objects, nearness, 1 − window depth (g;
  //! RG32F), when the elements pass ran.
  const Texture2D* elements = nullptr;
};

class RenderPass {
 public:
  virtual ~RenderPass() = default;
  //! Name in statistics and debug views.
  virtual std::string name() const = 0;
  //! Compiles the programs from the current shader sources (also the hot reload); on an
  //! error the old programs stay and the error is thrown.
  virtual void buildPrograms() = 0;
  //! The defines of each program built.
  virtual std::vector<std::string> variants() const = 0;
  //! Takes the scene's live parameters (the structure is the same as at construction).
  virtual void setScene(const scene::Scene&) {}
  //! Makes the targets for an output size (called when it changes).
  virtual void resize(int width, int height) = 0;
  virtual void run(const FrameInputs& in, FrameImages& images) = 0;
  //! The pass's output, for tests and debug views.
  virtual const Framebuffer* target() const = 0;
  //! Extra debug targets (the ink pass's line weight and tone); false if not supported.
  virtual bool setDebugOutputs(bool) { return false; }
  //! Marks the last frame made but had no room for (the elements' buffer is bounded), so
  //! left out; 0 for passes without such a bound. Reads from the GPU: it waits for the frame.
  virtual std::size_t marksDropped() const { return 0; }
};

//! What a pass is built from.
struct PassSetup {
  const scene::Scene& scene;
  const std::vector<SceneObjectGpu>& objects;
  const mesh::Bounds& world_bounds;
};

//! One entry of the pass list: a name, whether a scene wants the pass, the compile-time
//! choices it makes for that scene (with the scene's rebuild keys, what decides when a new
//! renderer is needed), and how to build it.
struct PassEntry {
  const char* name;
  bool (*wanted)(const scene::Scene&);
  std::string (*structure)(const scene::Scene&);
  std::unique_ptr<RenderPass> (*make)(const PassSetup&);
};

//! Every pass, in execution order.
const std::vector<PassEntry>& passList();

// The passes (each in its own source file).
std::unique_ptr<RenderPass> makeGbufferPass(const PassSetup&);
std::string gbufferStructure(const scene::Scene&);
std::unique_ptr<RenderPass> makeCanvasPass(const PassSetup&);
std::string canvasStructure(const scene::Scene&);
std::unique_ptr<RenderPass> makeElementsPass(const PassSetup&);
std::string elementsStructure(const scene::Scene&);
//! Whether the elements' layer keeps the nearness of its ink (RG32F; else R8, ink only): with
//! animated objects, which may pass in front of its cached static layer.
bool elementsKeepNearness(const scene::Scene& s);
std::unique_ptr<RenderPass> makeInkPass(const PassSetup&);
std::string inkStructure(const scene::Scene&);
//! Whether object i's slope wrinkles are computed in the ink pass (planar UVs are a function
//! of the position it rebuilds: once per pixel, where the G-buffer shades every fragment a
//! triangle covers) rather than in the G-buffer pass: true for the first object with slope
//! wrinkles on planar UVs (the ink pass binds one wrinkle texture, with its filter).
bool wrinklesInInkPass(const scene::Scene& s, std::size_t i);
//! A slope wrinkle tile's size on screen in pixels at a picture `height` pixels high
//! (`tile_px` is given for 1024).
inline float wrinkleTilePixels(const scene::Object& o, int height) {
  return static_cast<float>(o.wrinkle.tile_px * height / 1024.0);
}
//! The shading's noise for a scene's seed (libs/noise's erosion noise), tiled and
//! mipmapped, one texel of the nearest level read when minified (the noise is smooth at
//! texel scale); magnified it is filtered. Erosion in r; the added noise in g is the same
//! coarse channel (the upload expands the two-channel image as grey + alpha, so the finer
//! channel sits unused in alpha), which is the look the samples were tuned with.
Texture2D erosionNoiseTexture(std::uint64_t seed);
//! The dissolving border's and the mist's noise for a scene's seed (the erosion noise's
//! coarse channel, 1024² R8, read by nearest image loads: shaders/common/border_noise.glsl).
Texture2D borderNoiseTexture(std::uint64_t seed);
//! Erosion-noise tiles per model unit of an object: its coarsest cell is `noise_scale`
//! times the model's radius.
float erosionNoiseFrequency(const scene::Object& o, const SceneObjectGpu& g);
std::unique_ptr<RenderPass> makeDiffusionPass(const PassSetup&);
std::unique_ptr<RenderPass> makeStrokesPass(const PassSetup&);
std::string strokesStructure(const scene::Scene&);
std::unique_ptr<RenderPass> makePigmentPass(const PassSetup&);
//! The pigment an object's wash is made of (a palette name, or its custom pair).
pigment::Pigment objectPigment(const scene::PigmentParams& p);
std::unique_ptr<RenderPass> makeShadowPass(const PassSetup&);
std::unique_ptr<RenderPass> makeSubstratePass(const PassSetup&);
std::unique_ptr<RenderPass> makeMotionBlurPass(const PassSetup&);
std::unique_ptr<RenderPass> makeEdgesPass(const PassSetup&);
std::string edgesStructure(const scene::Scene&);
//! The shadow map's view and projection: orthographic along the light (towards_light points
//! at it), framing the bounds' sphere.
glm::dmat4 lightViewProjection(const glm::dvec3& towards_light, const mesh::Bounds& world_bounds);

std::string joined(const std::vector<std::string>& v);

}  // namespace shanshui::render
