// A landscape scene: objects with their line, shading and wrinkle parameters, light,
// camera (with an optional path), canvas, diffusion and output (SPEC.md section 10).
// Every key's default is its initialiser here; its range, unit and meaning are described
// once in src/scene_params.h, from which parsing, saving and docs/scene.md's tables come.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "shanshui/elements/placement.h"
#include "shanshui/ink/diffusion.h"

namespace shanshui::scene {

class AssetCache;  // scene_assets.h

//! Model to world: scale, then rotations about x, y, z (degrees), then translation.
struct Transform {
  glm::dvec3 translate{0.0};
  glm::dvec3 rotate_deg{0.0};
  glm::dvec3 scale{1.0};
  glm::dmat4 matrix() const;
};

enum class CurvatureSource {
  Quadric,    //!< per vertex, a quadric fitted to the two-ring (robust), precomputed on load
  Cotangent,  //!< per vertex, cotangent Laplacian and angle defect (fast, fragile on irregular meshes)
  Screen,     //!< per pixel |fwidth(N)| / |fwidth(P)|, as seed 001 does
};
inline bool perVertex(CurvatureSource s) {
  return s != CurvatureSource::Screen;
}

//! Feature lines from curvature (seed 001 Eq. 1; SPEC.md section 6).
struct LineParams {
  bool enabled = true;
  CurvatureSource curvature = CurvatureSource::Quadric;
  //! R_CurveFactor on dimensionless curvature k·feature_size (k = 1 at the mesh's 90th
  //! percentile of |k|), so the same value gives the same line density on any mesh.
  double curve_factor = 0.8;
  double threshold = 0.4;                   //!< Curv0: line where 1 − k·curve_factor < threshold
  double soft_width = 0.1;                  //!< smoothstep width around Curv0 (0 = hard binarisation)
  glm::dvec3 line_color{0.06, 0.06, 0.07};  //!< _LineColor
  glm::dvec3 bg_color{1.0, 1.0, 1.0};       //!< _BgColor, RGB in [0, 1]; multiplies the shading
  double silhouette = 0.18;                 //!< N·V below which the surface is drawn as silhouette
  double depth_edges = 0.03;                //!< relative depth jump between pixels drawn as a line
  //! Objects whose projected area is below this many pixels get N·V lines only (the
  //! paper's small-object path).
  double small_object_px = 2000.0;
  //! Keep only the crest of each band past the threshold (non-maximum suppression of the
  //! curvature across it): lines instead of filled regions.
  bool thin = false;
  //! One-ring smoothing sweeps of the per-vertex curvature on load: lines at the scale of
  //! landforms instead of the mesh's finest roughness.
  int smoothing = 0;
  //! Strokes instead of Eq. 1's bands: the curvature's crests, outlines and thinned
  //! silhouettes drawn as lines this many pixels wide (near, strongest); 0 = Eq. 1.
  double width = 0.0;
  double taper = 0.35;      //!< width of a crest just past the threshold, relative to a strong one
  double far_width = 0.45;  //!< width at the far side of the scene, relative to the near side
  double valley_ink = 0.5;  //!< ink of concave crests (valleys), relative to ridges and outlines
  //! Suggestive contours (DeCarlo et al. 2003) as strokes: where N·V has a local minimum
  //! along w, the view direction projected into the tangent plane, at least this much
  //! deeper than N·V a few pixels either side along w; 0 = off. Strokes only.
  double suggestive = 0.0;
  //! How far strokes break along their length as a brush lifts and presses: value noise
  //! fixed on the land, a cell 8 stroke widths across, leaves gaps where it is low and
  //! varies the ink and width of what stays; 0 = even lines. Strokes only.
  double line_break = 0.0;
  bool strokes() const { return enabled && width > 0; }
  bool suggestiveContours() const { return strokes() && suggestive > 0; }
};

//! Interior shading (seed 001 Eqs. 2, 3, 5; SPEC.md section 7).
struct ShadingParams {
  bool enabled = true;
  std::array<double, 5> tones{0.22, 0.42, 0.62, 0.82, 1.0};  //!< C1..C5 grey, [0, 1], dark to light
  std::array<double, 4> thresholds{0.12, 0.3, 0.5, 0.72};    //!< t1..t4, ascending
  //! σ of the Gaussian-smoothed steps (Φ((t − t_k)/σ) instead of a hard step); [0, 1],
  //! 0 gives Eq. 2 exactly.
  double sigma = 0.04;
  double beta = -1.0;  //!< β of Eq. 3, t_dw = clamp(t_d + t_w + β, 0, 1)
  //! Strength of the erosion noise: t_w = 1 − erosion·(1 − noise), noise in [0, 1].
  double erosion = 0.35;
  double noise = 0.06;  //!< amplitude of the noise added before quantisation
  //! Size of the erosion noise's coarsest cells as a fraction of the object's radius
  //! (finer octaves at 1/2 and 1/4 of it).
  double noise_scale = 0.03;
  bool half_lambert = false;  //!< t_d = (N·L)·0.5 + 0.5 instead of max(N·L, 0)
  bool line_value = true;     //!< multiply t_dw by the line pass's col_i (the paper's Fig. 4f)
};

enum class UvSource {
  Mesh,    //!< the mesh's own UVs (from shanshui-param)
  Planar,  //!< x and y over the object's larger horizontal extent (terrain)
};

//! How the wrinkle texture is sampled where it is minified (magnified it is always
//! bilinear): one texel of the nearest mip level, bilinear in it, or trilinear.
enum class TextureFilter { Nearest, Bilinear, Trilinear };

//! How the wrinkle texture lies on the surface: as the UVs put it (seed 001), or turned per
//! fragment so its strokes run down the fall line, at a size fixed on screen (two octaves
//! of it blended, so it stays on the surface as the camera moves).
enum class WrinkleMapping { Uv, Slope };

//! Wrinkle (cun) texture mapping (seed 001 Eq. 5). No texture: no wrinkle code is built.
struct WrinkleParams {
  std::string texture;            //!< image path relative to the scene file; empty = none
  double inner_tex_factor = 1.0;  //!< R_InnerTexFactor, t_w = luma(W) / factor
  double repeat = 4.0;            //!< texture repetitions per UV unit
  UvSource uv = UvSource::Mesh;
  TextureFilter filter = TextureFilter::Nearest;
  WrinkleMapping mapping = WrinkleMapping::Uv;
  double tile_px = 384.0;  //!< slope: a texture tile's size on screen, pixels at 1024 high
  double angle_deg = 0.0;  //!< slope: the texture's v axis turned this far from the fall line
};

//! How an object's horizontal border meets the paper: a DEM is a tile cut from a larger
//! land, so its four straight cut edges dissolve into paper through a noise-perturbed
//! falloff; a closed mesh keeps its silhouette.
enum class BorderMode { Auto, Dissolve, Keep };

struct BorderParams {
  BorderMode mode = BorderMode::Auto;  //!< auto: dissolve DEMs, keep meshes
  //! Falloff width as a fraction of the smaller horizontal half-extent of the object.
  double width = 0.35;
  //! How far the noise pushes the falloff inwards, as a fraction of the width.
  double roughness = 1.2;
};

//! Brush strokes along the object-space lines (seed 002): the five baimiao styles of the
//! thesis and their mix (strokes/brush.h has the pressure curves).
enum class BrushStyle { None, Qinxian, Liuye, Zaohe, Jianbi, Zhuye, Mixed };

struct BrushStrokeParams {
  BrushStyle style = BrushStyle::None;
  double crease_deg = 60.0;    //!< edges whose faces' normals differ more are creases; 180 = none
  double width = 3.0;          //!< full-pressure width, pixels at 1024 high
  double min_pressure = 0.15;  //!< width at pressure 0, relative to full
  double ink = 0.85;           //!< ink of a stroke's core, [0, 1]
  double max_turn_deg = 45.0;  //!< linking: the direction may turn this much where pieces join
  double max_gap_px = 5.0;     //!< linking: largest gap bridged, pixels
  double tension = 0.0;        //!< Cardinal spline tension: 0 Catmull-Rom, 1 straight
  double short_px = 16.0;      //!< strokes shorter are left out, pixels at 1024 high (0: none)
  bool enabled() const { return style != BrushStyle::None; }
};

//! A wash of colour over the object (seeds 000 and 003): a pigment from the landscape
//! painter's palette (pigment/palette.h), or `custom` by its colours on white and on black,
//! composited by Kubelka–Munk over the ink picture.
enum class PigmentName { None, Ochre, Indigo, Azurite, Malachite, Cinnabar, Gamboge, Ink, Custom };

struct PigmentParams {
  PigmentName name = PigmentName::None;
  glm::dvec3 on_white{0.80, 0.62, 0.42};  //!< custom: a unit layer over white
  glm::dvec3 on_black{0.20, 0.13, 0.07};  //!< custom: a unit layer over black
  double thickness = 0.5;                 //!< of the wash, in unit layers (seed 003: 0.5)
  double follow_ink = 0.5;                //!< 0 an even wash, 1 only where the ink is
  double texture = 0.3;                   //!< the wash's thickness varies by this much (seed 003's texture layer)
  bool enabled() const { return name != PigmentName::None; }
};

//! An object's share of the substrate effects (seed 000 paints them per vertex; per object here).
struct SubstrateWeights {
  double dry_brush = 1.0;
  double granulation = 1.0;
  double lighting = 1.0;
  double distortion = 1.0;
};

//! Which model axis points up. Terrain and shanshui's own files are Z-up; most modelling
//! tools write OBJ/PLY Y-up. Auto: Z for DEMs, Y for meshes.
enum class UpAxis { Auto, X, Y, Z };

//! An image heightfield carries no cell size; it gets one that makes its larger side this
//! many times its relief (Mount St Helens' tile is about 7, a 30 m Alps tile about 10).
inline constexpr double kImageReliefRatio = 8.0;

//! One key of an object's translation path: at `time` (seconds) the object stands
//! `offset` (world units) from where its transform puts it.
struct PathKey {
  double time = 0.0;
  glm::dvec3 offset{0.0};
};

//! Texture strokes (cun) as discrete brush marks (issue 45), beside the wrinkle texture:
//! hemp-fibre (long, thin, wavy) or axe-cut (short wedges) marks down the fall line, and
//! broad wet strokes (a loaded brush pulled down a shadowed slope, drying towards its tail).
enum class MarkStyle { None, Hemp, Axe };

struct MarksParams {
  MarkStyle style = MarkStyle::None;  //!< none: no marks code is built
  double density = 0.5;               //!< share of lattice cells holding a mark in shadow near a ridge, [0, 1]
  double size = 28.0;                 //!< a mark's length, pixels at 1024 high
  double ink = 0.6;                   //!< a mark's darkness, share of the line colour
  double lit = 0.2;                   //!< density on fully lit slopes relative to shadowed ones
  double ridge = 1.0;                 //!< extra density at ridges and creases, times the curvature
  double angle_deg = 0;               //!< turn from the fall line: 90 lays them along the contours
  //! Broad wet strokes on the shadowed slopes, on a lattice of their own beside the marks.
  double wash = 0.0;         //!< share of lattice cells holding one in full shadow; 0: none
  double wash_size = 70.0;   //!< a wet stroke's length, pixels at 1024 high
  double wash_ink = 0.6;     //!< its darkness at the head, share of the line colour
  double wash_lit = 0.3;     //!< density on fully lit slopes relative to shadowed ones
  double wash_follow = 1.0;  //!< 1: down the fall line as it looks; 0: straight down the picture
  double wash_width = 1.0;   //!< breadth: 1 three thin strokes apart, 2+ one broad side-brush stroke
  bool enabled() const { return style != MarkStyle::None; }
  bool washes() const { return wash > 0.0; }
};

//! Where a grounded object stands on its ground: at the transform's x, y, or at a spot the
//! ground's form suits (found on load, deterministic, away from objects grounded before).
enum class GroundSite {
  At,         //!< transform.translate's x and y (world)
  Summit,     //!< the highest point with ground flat enough to build on (a pagoda)
  Ridge,      //!< high on a ridge, on its crest (a pavilion looking out)
  WaterEdge,  //!< where the ground meets the water (boulders, a jetty)
  Bank,       //!< a flat spot a little above the water (a hut, a pavilion by the lake)
  SlopeFoot,  //!< where a slope flattens into a hollow or a valley floor (boulders, huts)
};

//! An object standing on another (objects.N.ground): a hut, a pavilion, a boulder on a
//! terrain. It is moved so its base rests on the ground's surface there, upright or
//! tilted to the slope.
struct GroundParams {
  std::string on;  //!< name of the object it stands on; empty: placed by its transform alone
  GroundSite site = GroundSite::At;
  double align = 0.0;  //!< 0 upright (buildings), 1 tilted to the ground's slope (boulders)
  double sink = 0.05;  //!< fraction of its height sunk into the ground (no gap under it on a slope)
};

struct Object {
  std::string name;
  std::string mesh;  //!< any mesh file (OBJ, PLY, OFF, glTF, FBX, ...) relative to the scene file (one of mesh, dem)
  std::string dem;   //!< heightfield (any GDAL raster, .dem, .asc, height map), meshed on load
  double z_scale = 1.0;  //!< dem only: vertical exaggeration
  //! dem only: metres between samples; 0 takes it from the file's header, and an image
  //! (which has none) gets cells that make its larger side kImageReliefRatio × its relief.
  double cell_size = 0.0;
  UpAxis up = UpAxis::Auto;           //!< the model axis that is up in the world
  std::size_t max_vertices = 250000;  //!< dem only: grid decimation limit
  bool fill_nodata = false;           //!< dem only: fill no-data samples instead of leaving holes
  //! dem only: heights stored in steps (whole metres, grey levels) smoothed within half a
  //! step (terrain::dequantize); false keeps the file's values (a terrace model).
  bool smooth_steps = true;
  //! dem only: the grid made this many times finer along each side by bicubic interpolation
  //! (terrain::upsample), within max_vertices, so a coarse DEM's coasts and ridges are
  //! curves rather than the grid's facets; 1 keeps the file's grid.
  int upsample = 1;
  //! dem only: the part kept, west, south, east, north as fractions of the grid.
  std::array<double, 4> crop{0.0, 0.0, 1.0, 1.0};
  //! mesh only: normals split across edges sharper than this (degrees); 180: smooth.
  double crease_angle = 40.0;
  //! mesh only: Loop subdivision steps after repair (mesh::subdivideLoop), so a low-poly
  //! land's facets are drawn as rounded ground; 0 keeps the file's triangles.
  int subdivide = 0;
  //! true: the mesh is moved so its bounding-box centre is the model origin.
  bool recentre = true;
  Transform transform;
  //! Degrees per second the object turns about the vertical axis through its centre; an
  //! object with a spin is animated and drawn over the cached static layer.
  double spin_deg_per_s = 0.0;
  //! World units per second the object moves along a straight path (from its transform's
  //! place at time 0); a moving object is animated like a spinning one.
  glm::dvec3 velocity{0.0};
  //! Keys of a translation path (none, or two or more with times strictly increasing):
  //! the offset is linear between
  //! keys and held before the first and after the last; added to the velocity's.
  std::vector<PathKey> path;
  bool animated() const { return spin_deg_per_s != 0.0 || velocity != glm::dvec3(0.0) || path.size() > 1; }
  //! Where the path puts the object at time t (world units, from its transform's place).
  glm::dvec3 pathOffset(double t) const;
  LineParams lines;
  ShadingParams shading;
  WrinkleParams wrinkle;
  BorderParams border;
  BrushStrokeParams strokes;
  PigmentParams pigment;
  SubstrateWeights substrate;
  elements::TreeOptions trees;  //!< trees grown on the surface (issue 44)
  elements::DotOptions dots;    //!< moss dots on ridges, rock edges and at the feet of trees
  GroundParams ground;          //!< standing on another object
  MarksParams marks;            //!< texture strokes as discrete marks
  bool grounded() const { return !ground.on.empty(); }
  //! Some element (a tree or a moss dot) is grown on this object.
  bool hasElements() const {
    const bool grows_trees = trees.enabled && trees.density > 0;
    return grows_trees || (dots.enabled && (dots.density > 0 || (grows_trees && dots.at_trees > 0)));
  }
  //! The wrinkle texture is drawn (a texture, and shading on).
  bool wrinkled() const { return !wrinkle.texture.empty() && shading.enabled; }
  bool dissolvesBorder() const {
    return border.width > 0 &&
           (border.mode == BorderMode::Dissolve || (border.mode == BorderMode::Auto && !dem.empty()));
  }
};

struct Light {
  glm::dvec3 direction{-0.5, 0.3, 0.8};  //!< towards the light, world space, non-zero
};

//! One key of a camera path; frames are spread evenly over the keys.
struct CameraKey {
  double azimuth_deg = -60.0;
  double elevation_deg = 25.0;
  double zoom = 1.0;
};

//! The three distances of landscape painting (Guo Xi): high distance looks up at a peak
//! from its foot, deep distance looks from above into ranges behind ranges, level distance
//! looks across far ranges from near the ground. A preset sets the elevation, field of
//! view and framing; the azimuth and zoom stay the scene's.
enum class CameraPreset { None, High, Deep, Level };

//! How distance 0 frames the scene: its bounding sphere (the whole scene from any angle,
//! with room around it), or its bounding box filling the frame from this angle.
//! Or (drawn) what is drawn of the land filling the frame: the surfaces inside their
//! dissolving borders and above the water, for a composition of several ranges whose boxes
//! are mostly empty.
enum class Framing { Sphere, Fill, Drawn };

//! An orbit camera. Without a target it looks at the centre of the scene's bounds;
//! distance 0 frames the bounds (zoom > 1 moves closer).
struct Camera {
  std::optional<glm::dvec3> target;
  double distance = 0.0;       //!< [0, 1e9], 0 = frame the scene
  double azimuth_deg = -60.0;  //!< around +Z, any finite value
  double elevation_deg = 25.0;
  double fov_y_deg = 35.0;
  double zoom = 1.0;
  CameraPreset preset = CameraPreset::None;
  Framing framing = Framing::Sphere;
  std::vector<CameraKey> path;  //!< optional; used by --frames
};

//! Paper (seed 001 Eqs. 9-17, SPEC.md section 8): none; rice paper (Perlin) or silk (two
//! Gabor noises, the second with swapped coordinates) attached to the scene, so it moves
//! with it and keeps a flat look; or `static`, the same pattern fixed to the screen (the
//! "shower door" baseline).
enum class CanvasType { None, RicePaper, Silk, Static };
enum class CanvasPattern { RicePaper, Silk };
//! How the moving canvas is drawn: a precomputed noise tile pinned to the surfaces in
//! patches (one full-screen pass), or seed 001's kernels splatted by a geometry shader on
//! every triangle (the reference the tiles are measured against).
enum class CanvasMethod { Tiles, Splat };
//! What the `tiles` grain keeps when the camera moves in or out: its place on the surface
//! (it grows and shrinks with it between octaves, two octaves mixed), or its exact size on
//! screen (it slides over the surface as that scales); `auto` is the surface for rice
//! paper and the screen for silk, whose narrow weave spectrum the octave mix widens.
enum class CanvasZoom { Auto, Surface, Screen };

//! Lengths are in pixels of a 1024-pixel-tall frame (they scale with the output height).
struct Canvas {
  CanvasType type = CanvasType::None;
  CanvasPattern static_pattern = CanvasPattern::RicePaper;  //!< what `static` shows
  CanvasMethod method = CanvasMethod::Tiles;                //!< rice paper and silk only
  double patch = 2.0;                                       //!< tiles: anchor spacing in kernel radii
  CanvasZoom zoom = CanvasZoom::Auto;                       //!< tiles: what the grain keeps under a dolly
  double contrast = 0.015;        //!< paper brightness × (1 + contrast · unit-variance noise)
  double absorbency = 1.0;        //!< how much the canvas varies the ink absorbency
  double grain = 6.0;             //!< kernel radius r (the quads' half side)
  double frequency = 0.3;         //!< F0, Gabor cycles per pixel
  double orientation_deg = 0.0;   //!< ω0, the weave direction
  bool isotropic = false;         //!< random orientation per impulse instead of ω0
  double mix = 0.5;               //!< weight of the swapped-coordinate Gabor (silk)
  double perlin_frequency = 1.5;  //!< rice paper: Perlin cycles per grain radius
  double impulses = 32.0;         //!< N′, expected impulses per kernel disc
  // Marks of the paper over the grain (the tiles method): fibres, impurity spots, mottle.
  double fibres = 0.8;          //!< fibres per 100 × 100 pixels (rice paper)
  double fibre_length = 24.0;   //!< mean fibre length, pixels at 1024 high
  double fibre_contrast = 0.2;  //!< brightness change along a fibre's middle
  double spots = 0.08;          //!< impurity spots per 100 × 100 pixels (rice paper)
  double mottle = 0.02;         //!< contrast of the paper's cloudy low-frequency tone (rice paper)
  double mottle_cell = 8.0;     //!< pixels at 1024 high per computed value of the mottle

  //! Whether the canvas draws rice paper's fibres or spots, and its mottle (the tiles
  //! method only).
  bool hasFibresOrSpots() const;
  bool hasMottle() const;
  //! Whether the tiles' grain is pinned to the surface under zoom (`zoom` resolved).
  bool grainOnSurface() const {
    return zoom == CanvasZoom::Surface || (zoom == CanvasZoom::Auto && pattern() == CanvasPattern::RicePaper);
  }

  //! The pattern drawn: rice paper or silk (static: static_pattern); meaningless for None.
  CanvasPattern pattern() const {
    return type == CanvasType::Silk || (type == CanvasType::Static && static_pattern == CanvasPattern::Silk)
               ? CanvasPattern::Silk
               : CanvasPattern::RicePaper;
  }
};

//! Seed 001 Eqs. 6-8, SPEC.md section 9: libs/ink's options (one set of defaults), but off
//! unless a scene asks: d = 0 and n = 0 build no pass.
struct Diffusion : ink::DiffusionOptions {
  Diffusion() {
    ring_steps = 0;
    iterations = 0;
  }
  bool enabled() const { return ring_steps > 0 || iterations > 0; }
};

//! Height mist: the lower part of the scene dissolves into paper, thinning out upwards
//! through a noise-perturbed band (the valleys of a shanshui painting left white).
struct Mist {
  double density = 0.0;    //!< how far the mist moves ink towards paper at its thickest; 0 = off
  double height = 0.3;     //!< top of the full mist, fraction of the scene's vertical extent
  double softness = 0.3;   //!< band above it over which the mist thins out, same units
  double roughness = 0.5;  //!< noise that breaks the band into banks, same units
  //! Share of the mist on the nearest land, growing to all of it at the farthest (over the
  //! distance fade's range): below 1 the near bank stands clear and the mist lies between
  //! the ranges, as the air between the eye and the land thickens with distance.
  double near = 1.0;
  bool enabled() const { return density > 0; }
};

//! Water (a lake, a river in its valley, the sea): a level below which the land is hidden
//! and left as paper with a few horizontal wave strokes, its banks drawn as a line.
struct Water {
  bool enabled = false;     //!< builds the water code into the ink pass
  double level = 0.15;      //!< the water's surface, fraction of the scene's vertical extent from its lowest point
  double waves = 0.25;      //!< share of the wave cells that hold a stroke; 0 = bare paper
  double spacing = 0.025;   //!< wave cell size, fraction of the scene's larger horizontal side
  double ink = 0.75;        //!< darkness of a wave stroke, 0..1 of the line colour
  double bank = 1.5;        //!< width of the bank line in pixels at a height of 1024; 0 = none
  double bank_break = 0.0;  //!< how far the bank line breaks into strokes of varying ink along the shore; 0 = even
};

//! The paper's body (seed 000): its relief (a scanned paper, the canvas's grain, or value
//! noise without either) as a height field and normals, which the dried paint follows.
struct SubstrateParams {
  bool enabled = false;      //!< builds the substrate pass
  std::string texture;       //!< a scanned paper (grey = height), a texel a pixel; empty: the canvas
  double roughness = 1.0;    //!< r of Eq. 1: the relief's depth
  double dry_brush = 0.3;    //!< how high the bare valleys reach where the ink is light; 0 = none
  double dry_edge = 0.08;    //!< the dry brush's edge, in height
  double granulation = 1.0;  //!< D of Eq. 4; 0 = none
  double lighting = 0.25;    //!< d_s of Eq. 5: the lit relief's share of the tone; 0 = none
  double distortion = 1.0;   //!< pixels at 1024 high the image is pushed by the paper's slopes
};

//! Edge darkening and wobbly edges (seed 003 §4.2): pigment pools where a wash ends.
struct EdgeParams {
  bool enabled = false;      //!< builds the edges pass
  double strength = 0.6;     //!< how much denser the pigment is at an edge
  double radius = 6.0;       //!< of the blur that finds edges, pixels at 1024 high
  int samples = 3;           //!< taps per side of the blur (seed 003: 5, 25 taps; 3 by measurement)
  double wobble = 1.5;       //!< how far edges wander, pixels at 1024 high
  double wobble_scale = 24;  //!< size of the wander's noise features, pixels at 1024 high
};

//! Ink dragged behind moving objects (seed 004): a velocity buffer and a blur pass.
struct MotionBlurParams {
  bool enabled = false;        //!< builds the velocity target and the blur pass
  double interval = 1.0 / 24;  //!< seconds between frames: velocities are per interval
  double length = 3.0;         //!< k: the trail is k × |v| long (v in pixels per interval)
  double paint = 0.7;          //!< a: paint carried along the trail (≥ 0.5 reaches its end)
  double water = 0.7;          //!< w: water carried (≥ 0.5 lasts the trail; less runs dry)
  double bristles = 0.5;       //!< paint varying across the trail, bristle by bristle
  double granulation = 0.3;    //!< paint settling in the paper's valleys along the trail
};

//! Cast shadows as a wash (seed 003): a shadow map from the light, and where it shows a
//! surface in shadow, a layer of the shadow's pigment laid by Kubelka–Munk.
struct ShadowParams {
  PigmentParams pigment{PigmentName::None, {0.55, 0.6, 0.7}, {0.05, 0.06, 0.09}, 0.35, 0.0, 0.0};
  int resolution = 2048;  //!< shadow map texels per side
  double softness = 1.5;  //!< radius of the filtered edge, shadow-map texels
  double bias = 2.0;      //!< depth offset against self-shadowing, shadow-map texels
  bool enabled() const { return pigment.enabled(); }
};

//! The sheet: any size, or a hanging scroll (tall, kScrollAspect wide per unit of height).
enum class Format { Free, VerticalScroll };
inline constexpr double kScrollAspect = 0.4;

struct Output {
  int width = 1024;
  int height = 768;
  Format format = Format::Free;
  //! The picture's size in pixels: width × height, or a vertical scroll `height` tall.
  int pixelWidth() const;
  int pixelHeight() const { return height; }
  glm::dvec3 paper{0.95, 0.93, 0.87};  //!< paper colour behind and under the ink, RGB
  //! Distance fade: far parts move towards the paper by up to this much (0 = off).
  double fade = 0.35;
};

struct Scene {
  std::filesystem::path base_dir;  //!< directory the relative paths are resolved against
  std::uint64_t seed = 1;          //!< noise textures; same seed, same picture
  std::vector<Object> objects;
  Light light;
  Camera camera;
  Canvas canvas;
  Diffusion diffusion;
  Mist mist;
  Water water;
  ShadowParams shadow;
  SubstrateParams substrate;
  EdgeParams edges;
  MotionBlurParams motion_blur;
  Output output;

  std::filesystem::path resolve(const std::string& relative) const;
  bool usesWrinkles() const;
  bool usesLines() const;
  bool usesStrokes() const;             //!< some object draws its lines as strokes
  bool usesSuggestiveContours() const;  //!< some object's strokes include suggestive contours
  bool usesBrushStrokes() const;        //!< some object has objects.N.strokes.style
  bool usesPigment() const;             //!< some object has a pigment wash
  bool usesShadow() const { return shadow.enabled(); }
  bool usesShading() const;
  bool usesElements() const;  //!< some object grows trees or moss dots
  bool usesWater() const { return water.enabled; }
  bool usesMarks() const;  //!< some object draws texture marks or wet strokes
  bool usesWash() const;   //!< some object draws wet strokes (objects.N.marks.wash)
  bool hasAnimation() const;
  bool dissolvesBorders() const;
  //! Several terrains (DEM objects standing on nothing): a composition of ranges, which the
  //! camera presets frame by what is drawn of them (Framing::Drawn).
  bool isComposition() const;
};

//! What a change of a parameter needs: new uniforms only (the next frame shows it), or a
//! new renderer (shader variants, GPU resources, files read again).
enum class Effect { Uniform, Rebuild };

//! One parameter of the scene, from its description (libs/scene/src/scene_params.h): its
//! dotted path (objects.* for every object), kind, range, default and meaning. The
//! viewer's panel builds its widgets from these; docs/scene.md's tables are made of them.
struct SchemaEntry {
  std::string path;
  std::string kind;             //!< number, integer, bool, string, file, choice, color, vec3, list, entries
  double min = 0.0, max = 0.0;  //!< range of the value (each element's; entries: the count)
  bool lo_open = false;         //!< (min, max] instead of [min, max]
  std::vector<std::string> choices;
  std::size_t size = 0;   //!< list: the number of values
  bool optional = false;  //!< null allowed (automatic)
  std::string unit, doc;
  Effect effect = Effect::Uniform;
  std::string default_text;  //!< as docs/scene.md writes it
  std::string range_text;
  std::string table;  //!< the docs table it is listed in ("" = top level)
};

//! Parses and validates. `origin` names the file in messages. Unknown keys and values out
//! of range throw Error naming "origin: key.path". Relative paths resolve against base_dir.
Scene parseScene(const nlohmann::json& j, const std::string& origin, const std::filesystem::path& base_dir);

//! Reads a scene file, applies --set overrides ("objects.0.lines.curve_factor=2"; the
//! value is JSON, or a plain string), then parses.
Scene loadScene(const std::filesystem::path& path, const std::vector<std::string>& overrides = {});

//! A scene file, or a mesh (.obj .ply .off .gltf .glb .fbx .dae .stl ...) or heightfield
//! (.dem .asc .png .tif .hgt .img .vrt ...) made into a one-object scene in the sample
//! scene's style (strokes, rice paper; land, a DEM or a mesh that is a piece of land, with
//! the deep-distance camera, mist and a dissolving border; any other mesh filling the
//! frame); overrides apply to both. A lone input is read here for its proportions: land
//! whose relief is under a tenth of its larger side is raised to that (at most 20 times),
//! land at most 20 km across grows trees and moss dots, and where at least 1 % of a DEM lies
//! at or below 0 m open to its edge that is sea (water at 0 m). What was decided and not
//! overridden is added to `notes`, a line each, for the tools to print. What was read is
//! handed to `cache`, when given, so that the file is read once.
Scene loadSceneInput(const std::filesystem::path& path, const std::vector<std::string>& overrides = {},
                     std::vector<std::string>* notes = nullptr, AssetCache* cache = nullptr);

//! Applies one KEY=VALUE override to raw scene JSON; array indices must exist.
void applyOverride(nlohmann::json& j, const std::string& assignment);

//! Every key with its value (defaults written out), paths as given. parseScene(toJson(s))
//! gives s back.
nlohmann::json toJson(const Scene& s);

//! Writes toJson(s) atomically (for the viewer's Save), with file paths rewritten relative
//! to the saved file's directory so that it loads from wherever it is saved.
void saveScene(const Scene& s, const std::filesystem::path& path);

//! Every parameter parseScene accepts.
const std::vector<SchemaEntry>& sceneSchema();

//! A hash of every parameter value (and list length), or of those with one effect only:
//! equal scenes hash equal; a cheap cache key (no JSON is built).
std::uint64_t parameterHash(const Scene& s, std::optional<Effect> only = std::nullopt);

//! Every key as Markdown tables, one per group (`shanshui-render --describe`).
std::string describeMarkdown();

//! `doc` with each table between "<!-- keys: GROUP -->" and "<!-- /keys -->" replaced by
//! the description's; throws naming `origin` when a group's markers are missing.
std::string spliceDescription(const std::string& doc, const std::string& origin);

}  // namespace shanshui::scene
