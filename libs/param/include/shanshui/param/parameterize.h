// UV parameterization of mountain meshes for wrinkle texture mapping (SPEC.md section 5;
// seed 001 uses CGAL's fixed-border mean value coordinates, Floater 2003).
#pragma once

#include <string>
#include <vector>

#include "shanshui/mesh/mesh.h"
#include "shanshui/param/charts.h"
#include "shanshui/param/distortion.h"

namespace shanshui::param {

enum class Method {
  Auto,      //!< the least-stretch valid result among the methods that fit the time budget
  Xy,        //!< planar projection onto x, y (near-isometric for a heightfield)
  Mvc,       //!< mean value coordinates, fixed border (the paper's choice)
  Dcm,       //!< discrete conformal map, fixed border
  Tutte,     //!< barycentric (Tutte) mapping, fixed border
  Lscm,      //!< least squares conformal maps, free border
  Arap,      //!< as-rigid-as-possible, free border (slow on large meshes)
  Authalic,  //!< iterative authalic, fixed border
  Charts,    //!< an atlas of disc-like charts (charts.h): any topology, seams split
};

enum class Border { Circle, Square };

const char* methodName(Method m);
Method parseMethod(const std::string& name);  //!< throws Error listing the names
const char* borderName(Border b);
Border parseBorder(const std::string& name);

struct ParamOptions {
  Method method = Method::Auto;
  Border border = Border::Circle;  //!< for the fixed-border methods (mvc, dcm, tutte, authalic)
  //! Auto: seconds it may spend. A method whose predicted time (from the mesh size and the
  //! speed the methods already run showed) does not fit in what is left is skipped, so the
  //! time stays within the budget and grows with size only up to it. The first method
  //! always runs. [0, inf)
  double budget_seconds = 5.0;
  //! Auto: stop at the first valid result with L2 stretch at or below this; the slower
  //! methods cannot do much better. [1, inf)
  double auto_accept_stretch = 1.02;
  //! Auto: an atlas (seams) is kept over a one-piece map only when the one-piece map's L2
  //! stretch is more than this factor above the atlas's. [1, inf)
  double one_piece_preference = 1.1;
  //! The kept map's L2 stretch must be at or below this, or parameterize() throws (naming
  //! every method's result) unless accept_over_stretch. [1, inf)
  double max_stretch = 2.0;
  bool accept_over_stretch = false;
  //! Auto: while the best one-piece map is above auto_accept_stretch, spend the budget on
  //! as-rigid-as-possible rounds from it (each result kept only if valid and less
  //! stretched): half of it after the projection, the rest after the other methods. The
  //! budget is used, not idled, so the time grows with size up to it.
  bool refine = true;
  int authalic_iterations = 15;  //!< [1, 1000]
  ChartOptions charts;
};

//! One method's try, as auto (or an explicit method) ran it.
struct MethodTrial {
  Method method = Method::Xy;
  double seconds = 0.0;
  double predicted_seconds = 0.0;  //!< auto's estimate before running it
  bool ran = false;                //!< false: skipped (budget, early stop) or failed (see note)
  std::string note;                //!< why skipped or failed, empty when it ran
  Distortion distortion;
};

//! One refinement of auto's best one-piece map (ParamOptions::refine).
struct Refinement {
  Method from = Method::Xy;  //!< the map it started from
  double seconds = 0.0;
  int rounds = 0;
  bool converged = false;  //!< stopped because a round gained too little
  bool enough = false;     //!< stopped at L2 stretch <= auto_accept_stretch; neither: the budget ran out
  Distortion distortion;   //!< of the refined map
  bool kept = false;       //!< valid and less stretched than the map it started from
};

struct ParamReport {
  Method method = Method::Xy;  //!< the method whose UVs were kept
  double seconds = 0.0;        //!< parameterization only (not I/O or repair)
  Distortion distortion;
  std::vector<MethodTrial> trials;
  std::vector<Refinement> refinements;  //!< auto's, in order
  int seam_vertices = 0;                //!< closed input: vertices on the seam it was cut along (0: no cut)
  AtlasReport atlas;                    //!< when the kept map is an atlas (method charts)
  std::string decision;                 //!< auto: why the kept map was kept
};

//! Returns `mesh` with one UV per vertex (raw method output; see uv_adjust.h for scaling).
//! The mesh must be a clean (repaired, manifold) triangle mesh. The one-piece methods need
//! one border loop and a disc, or a closed mesh of genus 0, which is cut open along one seam
//! (seam_cut.h; the seam's interior vertices appear twice); anything else is refused with
//! an Error that says why and points to charts. `charts` takes any topology and component
//! count; `auto` tries the one-piece methods the mesh allows and charts, within the budget,
//! and keeps the valid map with the least stretch. Throws Error when no method gives a
//! one-to-one map (flipped, degenerate or non-finite UV faces), or when the kept map's
//! stretch is above max_stretch and that is not accepted, naming each method's result;
//! `what` names the mesh in messages.
mesh::Mesh parameterize(const mesh::Mesh& mesh, const ParamOptions& opts, ParamReport* report = nullptr,
                        const std::string& what = "mesh");

//! The trials as a table (method, seconds, predicted, L2 or flips, or why skipped), one
//! line each, for the tool.
std::string trialTable(const ParamReport& report);

//! The trials that ran, on one line ("xy 6024 flipped, ...; mvc L2 5.51"), for errors.
std::string trialSummary(const ParamReport& report);

//! Number of border loops of a triangle mesh (edges used by one triangle), for the checks
//! above.
int borderLoops(const mesh::Mesh& mesh);

}  // namespace shanshui::param
