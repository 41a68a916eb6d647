// A simple ink-toned view of a mesh: the first picture of the pipeline (make demo) and a
// pixel-checkable render for tests. The ink-wash passes of libs/render build on the same
// platform pieces.
#pragma once

#include <memory>

#include "shanshui/image/image.h"
#include "shanshui/mesh/mesh.h"
#include "shanshui/render/camera.h"
#include "shanshui/render/gl_resources.h"
#include "shanshui/render/gpu_mesh.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

struct PreviewOptions {
  int width = 1024;                        //!< [1, 16384]
  int height = 768;                        //!< [1, 16384]
  double azimuth_deg = -60.0;              //!< camera around +Z
  double elevation_deg = 25.0;             //!< camera above the horizon, (-90, 90)
  double fov_y_deg = 35.0;                 //!< (0, 180)
  double zoom = 1.0;                       //!< > 1 moves the camera closer, (0, 1000]
  glm::vec3 light_dir{-0.5f, 0.3f, 0.8f};  //!< towards the light; normalised on use
  glm::vec3 paper{0.95f, 0.93f, 0.87f};    //!< background and lightest tone
  glm::vec3 ink{0.08f, 0.08f, 0.09f};      //!< darkest tone
  float rim_width = 0.3f;                  //!< N·V where the silhouette rim fades out
  //! Checkerboard squares per UV unit over the shading (paper Fig. 5), [0, 1e6]; 0 = none.
  //! Needs a mesh with UVs; the program is built with the CHECKER variant only then.
  float checker_squares = 0.0f;
};

//! Compiled program plus an uploaded mesh; render() can be called for many views.
class MeshPreview {
 public:
  //! `checker`: build the checkerboard variant (the mesh must have UVs).
  explicit MeshPreview(const mesh::Mesh& m, bool checker = false);
  //! Draws into `target` (bound by the call) with the camera framing the mesh.
  void render(const Framebuffer& target, const PreviewOptions& options) const;
  const mesh::Bounds& bounds() const { return bounds_; }

 private:
  mesh::Bounds bounds_;
  bool checker_;
  Program program_;
  GpuMesh gpu_;
};

//! Renders one image offscreen with the current context (RGB, row 0 at the top).
image::Image renderPreview(const mesh::Mesh& m, const PreviewOptions& options);

//! Checks the option ranges; throws Error naming the parameter.
void validate(const PreviewOptions& options);

}  // namespace shanshui::render
