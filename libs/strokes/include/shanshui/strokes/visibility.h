// Hidden-line removal for feature edges (seed 002): a sample of an edge is visible where
// the face-id reference image shows one of the edge's own faces near it, or, where faces
// are smaller than a pixel, where its depth is within a tolerance of the image's.
#pragma once

#include <cstdint>
#include <vector>

#include "shanshui/mesh/mesh.h"
#include "shanshui/strokes/edges.h"

namespace shanshui::strokes {

//! Face ids and depths per pixel (row 0 at the bottom, as GL reads them back). id -1 = none.
struct ReferenceImage {
  int width = 0, height = 0;
  std::vector<std::int32_t> id;
  std::vector<float> depth;  //!< window depth in [0, 1] (GL's default depth range)
};

//! The reference on the CPU: a z-buffer of every triangle with w > 0 (pixel centres,
//! top-left fill rule not needed: ties keep the first). The renderer reads the same image
//! back from the GPU; this one is the tests' and the benches' reference.
ReferenceImage rasterizeReference(const mesh::Mesh& mesh, const glm::dmat4& view_projection, int width, int height);

//! A visible piece of a feature edge, in pixels (x right, y up, pixel centres at +0.5).
struct ScreenSegment {
  glm::dvec2 a, b;
  double za = 0.0, zb = 0.0;  //!< window depth at a and b
  std::uint32_t edge = 0;
  std::uint8_t kinds = 0;
};

struct VisibilityOptions {
  double samples_per_pixel = 2.0;  //!< along each edge on screen
  int search_px = 1;               //!< id match within this many pixels of the sample
  double depth_tolerance = 1e-4;   //!< window depth; a sample this close to the image is visible
  //! With near < far (a perspective projection's planes), depths are compared as distances
  //! from the eye instead, a sample within `relative_tolerance` of the image's being visible:
  //! the same tolerance near and far.
  double near = 0.0, far = 0.0;
  double relative_tolerance = 0.005;
  //! A visible piece that is not the whole edge and is shorter than this is dropped: near a
  //! visible corner a hidden edge passes the depth test for a pixel or two.
  double min_partial_px = 3.0;
};

//! Splits every edge into its visible pieces.
std::vector<ScreenSegment> visibleSegments(const std::vector<FeatureEdge>& edges, const EdgeGraph& graph,
                                           const mesh::Mesh& mesh, const glm::dmat4& view_projection,
                                           const ReferenceImage& reference, const VisibilityOptions& options = {});

}  // namespace shanshui::strokes
