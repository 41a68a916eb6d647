// Texture atlases for meshes that no single map flattens well: closed meshes, handles,
// several components (SPEC.md section 5). The mesh is split into disc-like charts by
// clustering face normals (CGAL's variational shape approximation, Cohen-Steiner et al.
// 2004), each chart is flattened on its own (projection onto its plane or LSCM), a chart
// that is not a disc or stretches too much is split again, and the charts are packed into
// one atlas with padding in texels. Chart borders become seams: their vertices are split.
#pragma once

#include <string>
#include <vector>

#include "shanshui/mesh/mesh.h"
#include "shanshui/param/distortion.h"

namespace shanshui::param {

struct ChartOptions {
  //! A chart whose own L2 stretch is above this is split again. [1, inf)
  double max_chart_stretch = 1.5;
  //! A chart filling less than this of the least rectangle round it (a long strip, a
  //! branching shape) is cut across its long side, and two charts are merged only when
  //! their union fills at least this: what keeps the atlas well used. [0, 1]
  double min_fill = 0.45;
  //! Texels of empty atlas between two charts, for an atlas `atlas_resolution` texels along
  //! its longer side (bilinear filtering and two mip levels need about 4). [0, 64]
  double padding_texels = 4.0;
  int atlas_resolution = 1024;  //!< [64, 16384]
};

//! One chart of an atlas.
struct ChartReport {
  int faces = 0;
  double area = 0.0;      //!< surface area
  std::string method;     //!< "plane" (projection onto the chart's plane) or "lscm"
  Distortion distortion;  //!< of this chart alone
};

struct AtlasReport {
  std::vector<ChartReport> charts;
  std::vector<int> chart_of_face;    //!< per triangle of the input (and output) mesh
  double usage = 0.0;                //!< charts' UV area / the atlas rectangle's area
  double width = 0.0, height = 0.0;  //!< atlas rectangle in UV units (before normalisation)
  double texel = 0.0;                //!< UV units per texel at options.atlas_resolution
  int splits = 0;                    //!< charts that were split again after flattening
  int merges = 0;                    //!< neighbouring charts merged back afterwards
};

//! Returns `mesh` with one UV per vertex: each chart's vertices are copies (so a vertex on
//! a chart border appears once per chart), triangles keep their order, normals are those of
//! the unsplit mesh (so shading does not see the seams). UVs are in surface units (UV area
//! = surface area in every chart) and the charts lie side by side with at least the
//! padding between them. The mesh must be manifold (repair it first); any topology and any
//! number of components is accepted. Throws Error for bad options or a mesh without area.
mesh::Mesh parameterizeCharts(const mesh::Mesh& mesh, const ChartOptions& options, AtlasReport* report = nullptr,
                              const std::string& what = "mesh");

}  // namespace shanshui::param
