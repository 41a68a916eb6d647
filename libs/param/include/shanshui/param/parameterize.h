// UV parameterization of mountain meshes for wrinkle texture mapping (SPEC.md section 5;
// seed 001 uses CGAL's fixed-border mean value coordinates, Floater 2003).
#pragma once

#include <string>
#include <vector>

#include "shanshui/mesh/mesh.h"
#include "shanshui/param/distortion.h"

namespace shanshui::param {

enum class Method {
  Auto,      //!< the least-stretch valid result among the methods affordable at this size
  Xy,        //!< planar projection onto x, y (near-isometric for a heightfield)
  Mvc,       //!< mean value coordinates, fixed border (the paper's choice)
  Dcm,       //!< discrete conformal map, fixed border
  Tutte,     //!< barycentric (Tutte) mapping, fixed border
  Lscm,      //!< least squares conformal maps, free border
  Arap,      //!< as-rigid-as-possible, free border (slow on large meshes)
  Authalic,  //!< iterative authalic, fixed border
};

enum class Border { Circle, Square };

const char* methodName(Method m);
Method parseMethod(const std::string& name);  //!< throws Error listing the names
const char* borderName(Border b);
Border parseBorder(const std::string& name);

struct ParamOptions {
  Method method = Method::Auto;
  Border border = Border::Circle;  //!< for the fixed-border methods (mvc, dcm, tutte, authalic)
  //! Auto: largest mesh (vertices) on which each method is still tried. ARAP took 97–298 s
  //! on a 230k-vertex grid (SPEC.md section 5), the linear solvers a few seconds.
  int auto_max_vertices_arap = 30000;
  int auto_max_vertices_linear = 120000;
  //! Auto: stop at the first method (planar projection first) whose result is valid with
  //! L2 stretch at or below this; the slower ones are skipped. [1, inf).
  double auto_accept_stretch = 1.02;
  int authalic_iterations = 15;  //!< [1, 1000]
};

//! One method's try, as auto (or an explicit method) ran it.
struct MethodTrial {
  Method method = Method::Xy;
  double seconds = 0.0;
  bool ran = false;  //!< false: skipped (size) or failed (see note)
  std::string note;  //!< why skipped or failed, empty when it ran
  Distortion distortion;
};

struct ParamReport {
  Method method = Method::Xy;  //!< the method whose UVs were kept
  double seconds = 0.0;        //!< parameterization only (not I/O or repair)
  Distortion distortion;
  std::vector<MethodTrial> trials;
  int seam_vertices = 0;  //!< closed input: vertices on the seam it was cut along (0: no cut)
};

//! Returns `mesh` with one UV per vertex (raw method output; see uv_adjust.h for scaling).
//! The mesh must be a clean, connected triangle mesh (run mesh::repairMesh with hole filling
//! first) with exactly one border loop, or closed and of genus 0, in which case it is cut
//! open along one seam (seam_cut.h) and the result has the seam's interior vertices twice.
//! Holes, several components and handles are refused with an Error that says so. Throws Error when the chosen method
//! fails or gives a result that is not one-to-one (flipped, degenerate or non-finite UV faces), naming the counts;
//! `what` names the mesh in messages.
mesh::Mesh parameterize(const mesh::Mesh& mesh, const ParamOptions& opts, ParamReport* report = nullptr,
                        const std::string& what = "mesh");

//! Number of border loops of a triangle mesh (edges used by one triangle), for the checks
//! above.
int borderLoops(const mesh::Mesh& mesh);

}  // namespace shanshui::param
