// The scene's parameters, each described once: key, field, default (the struct's
// initialiser), range, unit, one line of meaning and whether a change rebuilds the
// renderer. Every use walks these descriptions with a visitor (scene_params.cpp):
// parsing and validation, saving, the schema behind the viewer's widgets, the cache and
// structure hashes, and the tables of docs/scene.md (`shanshui-render --describe`).
//
// A visitor V provides, for a Key k and a field f:
//   number(k, double& f, Range<double>)          integer(k, I& f, Range<long long>)
//   boolean(k, bool& f)                          text(k, std::string& f, Text)
//   choice(k, E& f, const std::array<Named<E>, N>&)   vec3(k, glm::dvec3& f, Range<double>, Vec)
//   optionalVec3(k, std::optional<glm::dvec3>&, Range<double>)
//   numbers(k, std::array<double, N>& f, Range<double>)
//   group(name, T& g, Table)                     list(k, std::vector<T>&, Range<long long>, make, Table)
//   check(key, F)   F() returns an error message, empty when the values read so far agree
// and calls describe(v, g) for groups and list items.
#pragma once

#include <array>

#include "shanshui/core/range.h"
#include "shanshui/ink/diffusion.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/noise/gabor.h"
#include "shanshui/scene/grounding.h"
#include "shanshui/scene/scene.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::scene {

struct Key {
  const char* name;
  const char* doc;
  Effect effect = Effect::Uniform;
  const char* unit = "";
};

template <typename E>
struct Named {
  const char* name;
  E value;
};

enum class Text { Plain, File };
enum class Vec { Vector, Color };
//! Where a group's keys are documented: in its parent's table with the group's name as a
//! prefix (transform.scale), or in a table of their own.
enum class Table { Inline, Own };

inline constexpr double kBig = 1e9;
inline constexpr Range<double> kUnit{0.0, 1.0};
inline constexpr Range<double> kAnyCoordinate{-kBig, kBig};
inline constexpr Range<double> kAzimuth{-36000, 36000};
inline constexpr Range<double> kElevation{-89.9, 89.9};
inline constexpr Range<double> kZoom{0.001, 1000};

inline constexpr Range<long long> wide(Range<int> r) {
  return {r.lo, r.hi, r.lo_open};
}

inline constexpr std::array<Named<CurvatureSource>, 3> kCurvatureSources{{{"quadric", CurvatureSource::Quadric},
                                                                          {"cotangent", CurvatureSource::Cotangent},
                                                                          {"screen", CurvatureSource::Screen}}};
inline constexpr std::array<Named<UvSource>, 2> kUvSources{{{"mesh", UvSource::Mesh}, {"planar", UvSource::Planar}}};
inline constexpr std::array<Named<TextureFilter>, 3> kTextureFilters{{{"nearest", TextureFilter::Nearest},
                                                                      {"bilinear", TextureFilter::Bilinear},
                                                                      {"trilinear", TextureFilter::Trilinear}}};
inline constexpr std::array<Named<CanvasType>, 4> kCanvasTypes{{{"none", CanvasType::None},
                                                                {"rice_paper", CanvasType::RicePaper},
                                                                {"silk", CanvasType::Silk},
                                                                {"static", CanvasType::Static}}};
inline constexpr std::array<Named<CanvasPattern>, 2> kCanvasPatterns{
    {{"rice_paper", CanvasPattern::RicePaper}, {"silk", CanvasPattern::Silk}}};
inline constexpr std::array<Named<CanvasMethod>, 2> kCanvasMethods{
    {{"tiles", CanvasMethod::Tiles}, {"splat", CanvasMethod::Splat}}};
inline constexpr std::array<Named<CanvasZoom>, 3> kCanvasZooms{
    {{"auto", CanvasZoom::Auto}, {"surface", CanvasZoom::Surface}, {"screen", CanvasZoom::Screen}}};

inline constexpr std::array<Named<BrushStyle>, 7> kBrushStyles{{{"none", BrushStyle::None},
                                                                {"qinxian", BrushStyle::Qinxian},
                                                                {"liuye", BrushStyle::Liuye},
                                                                {"zaohe", BrushStyle::Zaohe},
                                                                {"jianbi", BrushStyle::Jianbi},
                                                                {"zhuye", BrushStyle::Zhuye},
                                                                {"mixed", BrushStyle::Mixed}}};
inline constexpr std::array<Named<PigmentName>, 9> kPigmentNames{{{"none", PigmentName::None},
                                                                  {"ochre", PigmentName::Ochre},
                                                                  {"indigo", PigmentName::Indigo},
                                                                  {"azurite", PigmentName::Azurite},
                                                                  {"malachite", PigmentName::Malachite},
                                                                  {"cinnabar", PigmentName::Cinnabar},
                                                                  {"gamboge", PigmentName::Gamboge},
                                                                  {"ink", PigmentName::Ink},
                                                                  {"custom", PigmentName::Custom}}};
inline constexpr std::array<Named<BorderMode>, 3> kBorderModes{
    {{"auto", BorderMode::Auto}, {"dissolve", BorderMode::Dissolve}, {"keep", BorderMode::Keep}}};

inline constexpr std::array<Named<WrinkleMapping>, 2> kWrinkleMappings{
    {{"uv", WrinkleMapping::Uv}, {"slope", WrinkleMapping::Slope}}};
inline constexpr std::array<Named<UpAxis>, 4> kUpAxes{
    {{"auto", UpAxis::Auto}, {"x", UpAxis::X}, {"y", UpAxis::Y}, {"z", UpAxis::Z}}};
inline constexpr std::array<Named<MarkStyle>, 3> kMarkStyles{
    {{"none", MarkStyle::None}, {"hemp", MarkStyle::Hemp}, {"axe", MarkStyle::Axe}}};
inline constexpr std::array<Named<GroundSite>, 6> kGroundSites{{{"at", GroundSite::At},
                                                                {"summit", GroundSite::Summit},
                                                                {"ridge", GroundSite::Ridge},
                                                                {"water_edge", GroundSite::WaterEdge},
                                                                {"bank", GroundSite::Bank},
                                                                {"slope_foot", GroundSite::SlopeFoot}}};
inline constexpr std::array<Named<CameraPreset>, 4> kCameraPresets{{{"none", CameraPreset::None},
                                                                    {"high", CameraPreset::High},
                                                                    {"deep", CameraPreset::Deep},
                                                                    {"level", CameraPreset::Level}}};
inline constexpr std::array<Named<Framing>, 3> kFramings{
    {{"sphere", Framing::Sphere}, {"fill", Framing::Fill}, {"drawn", Framing::Drawn}}};
inline constexpr std::array<Named<Format>, 2> kFormats{
    {{"free", Format::Free}, {"vertical_scroll", Format::VerticalScroll}}};

constexpr Effect kRebuild = Effect::Rebuild;

template <typename V>
void describe(V& v, Transform& t) {
  v.vec3({"translate", "model to world: scale, then rotate, then translate", Effect::Uniform, "world units"},
         t.translate, kAnyCoordinate, Vec::Vector);
  v.vec3({"rotate", "rotations about x, then y, then z", Effect::Uniform, "degrees"}, t.rotate_deg, {-3600, 3600},
         Vec::Vector);
  v.vec3({"scale", "per axis", Effect::Uniform}, t.scale, {1e-6, 1e6}, Vec::Vector);
}

template <typename V>
void describe(V& v, LineParams& p) {
  v.boolean({"enabled", "false: no lines for this object (and no curvature is computed)", kRebuild}, p.enabled);
  v.choice({"curvature",
            "`quadric`: per vertex, a quadric fitted to the two-ring, precomputed on load (robust); `cotangent`: "
            "cotangent Laplacian and angle defect (~3x faster to load, outliers on irregular meshes); `screen`: "
            "the paper's per-pixel \\|fwidth(N)\\| / \\|fwidth(P)\\| (view dependent, noisy)",
            kRebuild},
           p.curvature, kCurvatureSources);
  v.number({"curve_factor", "R_CurveFactor, on dimensionless curvature (k = 1 at the mesh's 90th percentile)"},
           p.curve_factor, {0, 100});
  v.number({"threshold", "Curv0: a pixel is line where 1 − k · curve_factor is below it"}, p.threshold, {-10, 1});
  v.number({"soft_width", "width of the smoothstep around Curv0; 0 = hard binarisation (lines pop under motion)"},
           p.soft_width, kUnit);
  v.vec3({"line_color", "_LineColor", Effect::Uniform, "RGB"}, p.line_color, kUnit, Vec::Color);
  v.vec3({"bg_color", "_BgColor; multiplies paper and tone", Effect::Uniform, "RGB"}, p.bg_color, kUnit, Vec::Color);
  v.number({"silhouette", "N·V below which the surface is silhouette (full weight below half of it); 0 = off"},
           p.silhouette, kUnit);
  v.number({"depth_edges",
            "a pixel whose neighbour is farther by more than this fraction of its distance (or is background) "
            "is an outline; 0 = off"},
           p.depth_edges, {0, 10});
  v.number({"small_object_px",
            "objects whose bounding sphere covers fewer pixels get N·V and depth-edge lines only (the paper's "
            "trees and pavilions)",
            Effect::Uniform, "pixels at 1024 high"},
           p.small_object_px, {0, kBig});
  v.boolean({"thin",
             "keep only the crest of each band past the threshold (curvature peaks across it): strokes, not "
             "filled regions"},
            p.thin);
  v.integer({"smoothing",
             "one-ring averaging sweeps of the per-vertex curvature on load (quadric, cotangent): lines at the "
             "scale of landforms, not of the mesh's finest roughness",
             kRebuild, "sweeps"},
            p.smoothing, {0, 200});
  v.number({"width",
            "strokes instead of Eq. 1's bands: crests of the curvature (ridges, valleys), outlines and thinned "
            "silhouettes drawn this wide near the camera at full strength; 0 = Eq. 1",
            Effect::Uniform, "pixels at 1024 high"},
           p.width, {0, 32});
  v.number({"taper", "width of a crest just past the threshold, relative to one of twice its curvature"}, p.taper,
           kUnit);
  v.number({"far_width", "stroke width at the far side of the scene, relative to the near side"}, p.far_width, kUnit);
  v.number({"valley_ink", "ink of concave crests (valleys, crevices), relative to ridges and outlines"}, p.valley_ink,
           kUnit);
  v.number({"suggestive",
            "strokes: suggestive contours (DeCarlo et al. 2003), where N·V has a local minimum along the view "
            "direction projected into the surface, drawn where that trough is at least this deep 3 pixels "
            "either side (the lines a contour would become from a little lower); light ink, as valleys; 0 = off"},
           p.suggestive, {0, 1});
  v.number({"break",
            "strokes: how far they break along their length as a brush lifts and presses (gaps where noise fixed "
            "on the land is low, a cell 8 stroke widths across near the object's centre; the ink and width of what "
            "stays vary): at 1 about a fifth of a line is left as gaps; 0 = even lines"},
           p.line_break, kUnit);
}

template <typename V>
void describe(V& v, ShadingParams& p) {
  v.boolean({"enabled", "false: no shading for this object (flat `bg_color`)", kRebuild}, p.enabled);
  v.numbers({"tones", "C1..C5, grey multiplying paper and `bg_color`, darkest first"}, p.tones, kUnit);
  v.numbers({"thresholds", "t1..t4, ascending"}, p.thresholds, kUnit);
  v.check("thresholds", [&]() -> std::string {
    for (std::size_t k = 1; k < p.thresholds.size(); ++k) {
      if (p.thresholds[k] < p.thresholds[k - 1]) {
        std::ostringstream s;
        s << "t" << k + 1 << " = " << p.thresholds[k] << " is below t" << k << " = " << p.thresholds[k - 1]
          << "; expected ascending thresholds";
        return s.str();
      }
    }
    return "";
  });
  v.number({"sigma", "σ of the Gaussian-smoothed steps; 0 = Eq. 2's hard ladder"}, p.sigma, kUnit);
  v.number({"beta", "β of Eq. 3: t_dw = clamp(t_d + t_w + β, 0, 1)"}, p.beta, {-2, 1});
  v.number({"erosion", "strength of the erosion noise: t_w = 1 − erosion · (1 − noise)"}, p.erosion, kUnit);
  v.number({"noise", "amplitude of the noise added before quantisation"}, p.noise, kUnit);
  v.number({"noise_scale",
            "size of the erosion noise's coarsest cells (octaves at 1, 1/2, 1/4 of it) as a fraction of the "
            "object's bounding radius; fixed to the model, so it moves with the object"},
           p.noise_scale, {1e-4, 10});
  v.boolean({"half_lambert", "t_d = 0.5 · N·L + 0.5 instead of max(N·L, 0)"}, p.half_lambert);
  v.boolean({"line_value", "multiply by the line pass's col_i (the paper's Fig. 4f); needs lines on"}, p.line_value);
}

template <typename V>
void describe(V& v, WrinkleParams& p) {
  v.text({"texture", "the (quilted) wrinkle texture; empty = no wrinkles, no UVs needed, no wrinkle code compiled",
          kRebuild},
         p.texture, Text::File);
  v.number({"inner_tex_factor", "R_InnerTexFactor: t_w = luma / factor; below 1 lightens the strokes"},
           p.inner_tex_factor, {0.01, 100});
  v.number({"repeat", "texture repetitions per UV unit"}, p.repeat, {0, 1e4, true});
  v.choice({"uv",
            "`mesh`: the mesh's UVs (from `shanshui-param`; none is an error); `planar`: x, y over the larger "
            "horizontal extent (terrain)",
            kRebuild},
           p.uv, kUvSources);
  v.choice({"filter",
            "where the texture is minified: one texel of the nearest mip level, bilinear in it, or trilinear "
            "(bench/ink_tradeoff.md)"},
           p.filter, kTextureFilters);
  v.choice({"mapping",
            "`uv`: the texture as the UVs lay it, `repeat` times per unit (seed 001); `slope`: turned per fragment "
            "so its v axis runs down the fall line, at a fixed size on screen (two octaves blended as the camera "
            "moves; `repeat` is not used)",
            kRebuild},
           p.mapping, kWrinkleMappings);
  v.number({"tile_px",
            "slope: a texture tile's size on screen: the two octaves drawn span half to twice it, the nearer "
            "weighing more, so the strokes keep their size at every zoom",
            Effect::Uniform, "pixels at 1024 high"},
           p.tile_px, {8, 4096});
  v.number({"angle", "slope: the texture's v axis turned this far from the fall line (align the scan's strokes)",
            Effect::Uniform, "degrees"},
           p.angle_deg, {-360, 360});
}

template <typename V>
void describe(V& v, BorderParams& b) {
  v.choice({"mode", "`dissolve`: the horizontal border fades into paper; `keep`: a hard edge; `auto`: dissolve DEMs"},
           b.mode, kBorderModes);
  v.number({"width", "falloff width, fraction of the smaller horizontal half-extent; 0 = a hard edge"}, b.width, kUnit);
  v.number({"roughness", "how far noise pushes the falloff inwards, fraction of the width"}, b.roughness, {0, 4});
}

template <typename V>
void describe(V& v, MarksParams& m) {
  v.choice({"style",
            "texture strokes as discrete marks down the fall line: `hemp` long, thin, wavy fibres (披麻皴), `axe` "
            "short wedges broad at the downhill end (斧劈皴); `none`: no marks code",
            kRebuild},
           m.style, kMarkStyles);
  v.number({"density",
            "share of lattice cells holding a mark in shadow near a ridge; less on lit slopes, none on flat ground"},
           m.density, kUnit);
  v.number({"size", "a mark's length (the lattice follows it)", Effect::Uniform, "pixels at 1024 high"}, m.size,
           {2, 512});
  v.number({"ink", "a mark's darkness, share of the line colour"}, m.ink, kUnit);
  v.number({"lit", "density on fully lit slopes relative to shadowed ones"}, m.lit, kUnit);
  v.number({"ridge", "extra density at ridges and creases, times the curvature (1 at the mesh's 90th percentile)"},
           m.ridge, {0, 8});
  v.number({"angle", "turn from the fall line: 90 lays the marks along the contour arcs", Effect::Uniform, "degrees"},
           m.angle_deg, {-360, 360});
  v.number({"wash",
            "broad wet strokes on the shadowed slopes, beside the marks: share of their lattice's cells holding "
            "one in full shadow; 0: none (no code)",
            kRebuild},
           m.wash, kUnit);
  v.number({"wash_size", "a wet stroke's length (its lattice follows it)", Effect::Uniform, "pixels at 1024 high"},
           m.wash_size, {8, 1024});
  v.number({"wash_ink", "a wet stroke's darkness at its head (it pales towards its tail), share of the line colour"},
           m.wash_ink, kUnit);
  v.number({"wash_lit", "wet strokes' density on fully lit slopes relative to shadowed ones"}, m.wash_lit, kUnit);
  v.number({"wash_follow",
            "how far wet strokes follow the slope's fall line as it looks on the picture (1) rather than run "
            "straight down it (0: clean strokes on rough ground, where the fall line turns from pixel to pixel)"},
           m.wash_follow, kUnit);
  v.number({"wash_width",
            "a wet stroke group's breadth: 1 up to three strokes apart; more, up to seven closer than their "
            "width, as a brush laid on its side, darker where two overlap; under 1 thinner strokes closer together"},
           m.wash_width, {0.5, 2.5});
}

template <typename V>
void describe(V& v, GroundParams& g) {
  v.text({"on",
          "name of the object this one stands on (a terrain), or `water` to float on the water (a boat: at "
          "translate's x, y, `sink` of its height under the surface); empty: the transform alone places it. "
          "Grounded, its base rests on that surface: translate.z lifts it above the ground",
          kRebuild},
         g.on, Text::Plain);
  v.choice({"site",
            "where on the ground: `at` transform.translate's x, y (world); or a spot found from the ground's form, "
            "away from objects grounded before it: `summit` the highest flat enough to build on, `ridge` a "
            "ridge's crest, `water_edge` where the ground meets the water, `bank` a flat spot a little above the "
            "water, `slope_foot` where a slope flattens into a hollow or a valley floor"},
           g.site, kGroundSites);
  v.number({"align", "0 stands upright (buildings), 1 tilts to the ground's slope (boulders)"}, g.align, kUnit);
  v.number({"sink", "fraction of its height sunk into the ground, so no gap shows under it on a slope"}, g.sink,
           {0, 0.9});
}

template <typename V>
void describe(V& v, BrushStrokeParams& p) {
  v.choice({"style",
            "brush strokes along the silhouettes, borders and creases (seed 002): `qinxian` (zither string: even), "
            "`liuye` (willow leaf: thin-thick-thin), `zaohe` (date pit: a beat every 30 px), `jianbi` (reduced "
            "stroke: pressed, then lifted), `zhuye` (bamboo leaf: as jianbi, side tip), `mixed` (by length); "
            "`none`: no strokes pass",
            kRebuild},
           p.style, kBrushStyles);
  v.number(
      {"crease", "edges whose two faces' normals are further apart are creases; 180 = silhouettes and borders only",
       Effect::Uniform, "degrees"},
      p.crease_deg, {1, 180});
  v.number({"width", "stroke width at full pressure", Effect::Uniform, "pixels at 1024 high"}, p.width, {0.1, 64});
  v.number({"min_pressure", "width where the brush is lifted, relative to full"}, p.min_pressure, kUnit);
  v.number({"ink", "ink of a stroke's core"}, p.ink, kUnit);
  v.number(
      {"max_turn", "linking: largest turn where two visible pieces join (seed 002: 45)", Effect::Uniform, "degrees"},
      p.max_turn_deg, {0, 180});
  v.number(
      {"max_gap", "linking: largest gap bridged between pieces (seed 002: 5)", Effect::Uniform, "pixels at 1024 high"},
      p.max_gap_px, {0, 1000});
  v.number({"tension", "Cardinal spline tension: 0 Catmull-Rom, 1 straight between the pieces' ends"}, p.tension,
           {-1, 1});
  v.number({"short",
            "strokes shorter than this are left out (a painter does not draw scratches); ink rises to full "
            "at three times it; 0 keeps every stroke",
            Effect::Uniform, "pixels at 1024 high"},
           p.short_px, {0, 1000});
}

template <typename V>
void describe(V& v, PigmentParams& p) {
  v.choice({"name",
            "a wash of colour over the object, composited by Kubelka-Munk over the ink: `ochre` (赭石, rock and "
            "the foot of mountains), `indigo` (花青, distant ranges, foliage), `azurite` (石青) and `malachite` "
            "(石绿, the opaque blue and green of the blue-green style), `cinnabar` (朱砂), `gamboge` (藤黄), `ink` "
            "(墨 as a wash), `custom` (`on_white`, `on_black`); `none`: no pigment pass",
            kRebuild},
           p.name, kPigmentNames);
  v.vec3({"on_white", "custom: colour of a unit layer over white", Effect::Uniform, "RGB"}, p.on_white, kUnit,
         Vec::Color);
  v.vec3({"on_black", "custom: colour of a unit layer over black, darker than on white in each channel",
          Effect::Uniform, "RGB"},
         p.on_black, kUnit, Vec::Color);
  v.check("on_black", [&]() -> std::string {
    if (p.name != PigmentName::Custom) return "";
    for (int i = 0; i < 3; ++i) {
      if (!(p.on_black[i] > 0.0 && p.on_white[i] < 1.0 && p.on_black[i] < p.on_white[i])) {
        std::ostringstream s;
        s << "channel " << i << ": on_black " << p.on_black[i] << ", on_white " << p.on_white[i]
          << "; expected 0 < on_black < on_white < 1";
        return s.str();
      }
    }
    return "";
  });
  v.number({"thickness", "thickness of the wash, in layers of the pigment's unit (seed 003: 0.5)"}, p.thickness,
           {0, 16});
  v.number({"follow_ink", "0: an even wash; 1: the wash only where the ink under it is, thicker where darker"},
           p.follow_ink, kUnit);
  v.number({"texture",
            "how much the wash's thickness varies with a noise that follows the surface (seed 003's "
            "texture layer)"},
           p.texture, kUnit);
}

template <typename V>
void describe(V& v, elements::TreeOptions& t) {
  v.boolean({"enabled", "grow trees on this object (issue 44); false: no elements pass unless it has dots", kRebuild},
            t.enabled);
  v.number({"density",
            "trees per hectare of horizontal area where the site suits them best (ridges, hollows, valley floors); "
            "open slopes get `open` of it",
            kRebuild, "per hectare"},
           t.density, {0, 10000});
  v.number({"size", "mean tree height (a 20 m pine is 20 model units on a DEM in metres)", kRebuild, "model units"},
           t.size, {0, 1e6, true});
  v.number({"size_spread", "log-normal spread of the heights", kRebuild}, t.size_spread, {0, 2});
  v.number({"max_slope", "no tree on ground steeper than this; fewer from 70 % of it", kRebuild, "degrees"},
           t.max_slope_deg, {0, 90});
  v.numbers({"band", "lowest and highest tree line, fractions of the object's relief", kRebuild}, t.band, kUnit);
  v.check("band", [&]() -> std::string {
    if (t.band[0] < t.band[1]) return "";
    return "the band's low end " + std::to_string(t.band[0]) + " must be below its high end " +
           std::to_string(t.band[1]);
  });
  v.number({"open", "density on open slopes relative to ridges, hollows and valley floors", kRebuild}, t.open, kUnit);
  v.number({"grove", "mean trees per grove; 1 scatters them one by one", kRebuild}, t.grove, {1, 1000});
  v.number({"grove_radius", "spread of a grove; 0: six mean tree heights; at most the object's larger side", kRebuild,
            "model units"},
           t.grove_radius, {0, 1e6});
  v.numbers({"kinds",
             "shares of pine, leafy (dot leaves), bare (branches) and distant (a few vertical dots) trees; all 0: none",
             kRebuild},
            t.kinds, {0, 1000});
  v.integer({"seed", "placement and growth; 0: the scene's seed", kRebuild}, t.seed, {0, 1LL << 53});
  v.number({"ink", "scales the ink of every mark of the trees (1: as grown, the darkest near 0.95)"}, t.ink, kUnit);
  v.number({"massed_beyond",
            "land wider than this (its larger side) masses its trees as a painter masses a far forest: with f = this "
            "over the side, groves of `grove`/f trees in the same radius and f of `open`; 0: never",
            kRebuild, "model units"},
           t.massed_beyond, {0, 1e9});
}

template <typename V>
void describe(V& v, elements::DotOptions& d) {
  v.boolean(
      {"enabled", "moss dots (苔点): clusters of dark dabs on ridges, rock edges and at the feet of trees", kRebuild},
      d.enabled);
  v.number(
      {"density", "clusters per hectare of horizontal area where the site suits them best", kRebuild, "per hectare"},
      d.density, {0, 10000});
  v.number({"cluster", "mean dots per cluster", kRebuild}, d.cluster, {1, 100});
  v.number({"spread", "a cluster's radius; 0: 0.4 % of the object's larger side; at most that side", kRebuild,
            "model units"},
           d.spread, {0, 1e6});
  v.number({"at_trees", "share of trees with one to three dots at their feet", kRebuild}, d.at_trees, kUnit);
  v.integer({"seed", "placement; 0: the scene's seed", kRebuild}, d.seed, {0, 1LL << 53});
  v.number({"size", "a dot's size", Effect::Uniform, "pixels at 1024 high"}, d.size_px, {0.5, 64});
  v.number({"ink", "a dot's ink: the darkest accents of the picture"}, d.ink, kUnit);
  v.number({"massed_beyond",
            "land wider than this (its larger side) keeps f of `density`, f = this over the side, as its trees "
            "are massed; 0: never",
            kRebuild, "model units"},
           d.massed_beyond, {0, 1e9});
}

template <typename V>
void describe(V& v, Object& o) {
  v.text({"name", "shown in the viewer; empty: `objects.N`"}, o.name, Text::Plain);
  v.text({"mesh",
          "`.obj`, `.ply`, `.off`, glTF (`.gltf`, `.glb`), FBX, COLLADA (`.dae`), 3DS, STL or any other format Assimp "
          "reads, repaired on load like `shanshui-repair`; give `mesh` or `dem`",
          kRebuild},
         o.mesh, Text::File);
  v.text({"dem",
          "heightfield meshed on load like `shanshui-terrain`: any raster GDAL reads (GeoTIFF, `.hgt`, VRT, ...), "
          "a PNG or TIFF height map, `.dem` (USGS ASCII) or `.asc` (ESRI ASCII)",
          kRebuild},
         o.dem, Text::File);
  v.check("", [&]() -> std::string {
    if (o.mesh.empty() && o.dem.empty()) return "needs a 'mesh' or a 'dem' file";
    if (!o.mesh.empty() && !o.dem.empty()) return "has both 'mesh' and 'dem'; give one";
    return "";
  });
  v.number({"z_scale", "dem only: vertical exaggeration", kRebuild}, o.z_scale, {0, 1000, true});
  v.integer({"max_vertices", "dem only: the grid is decimated to at most this many vertices", kRebuild}, o.max_vertices,
            {4, 100000000});
  v.boolean({"fill_nodata",
             "dem only: fill no-data samples (voids, the sea) by interpolation from their edges; false leaves them "
             "out of the mesh as holes",
             kRebuild},
            o.fill_nodata);
  v.boolean({"smooth_steps",
             "dem only: heights stored in steps (whole metres as SRTM and USGS DEMs store them, tenths, an image's "
             "grey levels) are smoothed within half a step, so gentle ground is not drawn as a staircase of cracks; "
             "false keeps the file's values (a model of terraces in exact steps)",
             kRebuild},
            o.smooth_steps);
  v.integer({"upsample",
             "dem only: the grid made this many times finer along each side by bicubic interpolation (within "
             "max_vertices; every stored sample keeps its height), so a coarse DEM's coasts, islands and ridges are "
             "drawn as curves, not as the grid's facets; 1 keeps the file's grid",
             kRebuild},
            o.upsample, {1, terrain::kMostUpsample});
  v.numbers({"crop",
             "dem only: the part of the grid kept, its west, south, east and north edges as fractions of its width "
             "and height, so one DEM gives several ranges",
             kRebuild},
            o.crop, kUnit);
  v.check("crop", [&]() -> std::string {
    if (o.crop[0] < o.crop[2] && o.crop[1] < o.crop[3]) return "";
    return "west " + std::to_string(o.crop[0]) + " must be below east " + std::to_string(o.crop[2]) + " and south " +
           std::to_string(o.crop[1]) + " below north " + std::to_string(o.crop[3]);
  });
  v.number({"cell_size",
            "dem only: metres between samples; 0: from the file's header, and an image (PNG, TIFF: no header) "
            "gets cells that make its larger side 8 times its relief",
            kRebuild, "metres"},
           o.cell_size, {0, 1e6});
  v.choice({"up",
            "the model axis that points up in the world; `auto`: z for DEMs; a mesh much thinner along one axis "
            "(a piece of land) lies on that axis, any other is y-up (what most modelling tools write)",
            kRebuild},
           o.up, kUpAxes);
  v.number({"crease_angle",
            "mesh only: normals are smooth across edges whose faces meet at less than this angle and split across "
            "sharper ones, as modelling tools do (a cube shows six flat faces); 180: smooth everywhere. A file's own "
            "normals are kept where repair keeps its vertices",
            kRebuild, "degrees"},
           o.crease_angle, {0, 180});
  v.integer({"subdivide",
             "mesh only: Loop subdivision steps after repair, each making four triangles of one and rounding the "
             "surface, so a low-poly land's facets and their creases are not drawn as ladders of lines (a lone land "
             "mesh under 4000 vertices gets enough of them by itself; a step that would make more than 2 million "
             "triangles is not taken); 0 keeps the file's triangles",
             kRebuild},
            o.subdivide, {0, mesh::kMostSubdivisions});
  v.boolean(
      {"recentre", "move the mesh so its bounding-box centre is the model origin (keeps UTM-sized coordinates precise)",
       kRebuild},
      o.recentre);
  v.group("transform", o.transform, Table::Inline);
  v.number({"spin",
            "turn about the vertical axis through the centre; a spinning object is drawn over a cached layer of "
            "the static ones",
            Effect::Uniform, "degrees/s"},
           o.spin_deg_per_s, {-36000, 36000});
  v.vec3({"velocity",
          "moves along a straight line from where the transform puts it at time 0; a moving object is drawn over "
          "the cached layer of the static ones",
          Effect::Uniform, "world units/s"},
         o.velocity, kAnyCoordinate, Vec::Vector);
  v.list(
      {"path",
       "keys of a translation path (none, or two or more, times increasing): the object moves linearly from key to key "
       "(and stands at "
       "the first before it, at the last after it), added to the velocity's motion"},
      o.path, {0, 100000}, [] { return PathKey{}; }, Table::Inline);
  v.check("path", [&]() -> std::string {
    if (o.path.size() == 1) return "a path needs at least two keys (one key is a place: use the transform)";
    for (std::size_t i = 1; i < o.path.size(); ++i)
      if (!(o.path[i].time > o.path[i - 1].time))
        return "key " + std::to_string(i) + "'s time " + std::to_string(o.path[i].time) + " must be later than key " +
               std::to_string(i - 1) + "'s " + std::to_string(o.path[i - 1].time);
    return "";
  });
  v.group("lines", o.lines, Table::Own);
  v.group("shading", o.shading, Table::Own);
  v.group("wrinkle", o.wrinkle, Table::Own);
  v.group("border", o.border, Table::Own);
  v.group("strokes", o.strokes, Table::Own);
  v.group("pigment", o.pigment, Table::Own);
  v.group("substrate", o.substrate, Table::Inline);
  v.group("trees", o.trees, Table::Own);
  v.group("dots", o.dots, Table::Own);
  v.group("marks", o.marks, Table::Own);
  v.group("ground", o.ground, Table::Own);
}

template <typename V>
void describe(V& v, Light& l) {
  v.vec3({"direction", "towards the directional light, world space, normalised on use; not zero"}, l.direction,
         kAnyCoordinate, Vec::Vector);
  v.check("direction", [&]() -> std::string { return glm::length(l.direction) > 0 ? "" : "must not be zero"; });
}

template <typename V>
void describe(V& v, PathKey& k) {
  v.number({"time", "when the object is at this key", Effect::Uniform, "s"}, k.time, {-kBig, kBig});
  v.vec3({"offset", "from where the transform puts the object", Effect::Uniform, "world units"}, k.offset,
         kAnyCoordinate, Vec::Vector);
}

template <typename V>
void describe(V& v, CameraKey& k) {
  v.number({"azimuth", "one key's azimuth (default: the camera's)", Effect::Uniform, "degrees"}, k.azimuth_deg,
           kAzimuth);
  v.number({"elevation", "one key's elevation (default: the camera's)", Effect::Uniform, "degrees"}, k.elevation_deg,
           kElevation);
  v.number({"zoom", "one key's zoom (default: the camera's)"}, k.zoom, kZoom);
}

template <typename V>
void describe(V& v, Camera& c) {
  v.optionalVec3({"target", "point looked at; null: the centre of the scene's bounds", Effect::Uniform, "world units"},
                 c.target, kAnyCoordinate);
  v.number({"distance", "from the target; 0 frames the scene", Effect::Uniform, "world units"}, c.distance, {0, kBig});
  v.number({"azimuth", "around +Z; 0 looks from +X", Effect::Uniform, "degrees"}, c.azimuth_deg, kAzimuth);
  v.number({"elevation", "above the horizon", Effect::Uniform, "degrees"}, c.elevation_deg, kElevation);
  v.number({"fov", "vertical field of view", Effect::Uniform, "degrees"}, c.fov_y_deg, {1, 170});
  v.number({"zoom", "> 1 moves closer"}, c.zoom, kZoom);
  v.choice({"preset",
            "the three distances of landscape painting: `high` looks up at the highest peak from its foot, "
            "`deep` looks from above into ranges behind ranges, `level` looks across the ranges from near the "
            "ground; each sets the elevation, field of view and framing (`fill`; `drawn` when the scene holds "
            "several terrains; azimuth and zoom stay); `none`: as given"},
           c.preset, kCameraPresets);
  v.choice({"framing",
            "how distance 0 frames the scene: `sphere`, its bounding sphere (room on every side); `fill`, its "
            "bounding box filling the frame from this angle; `drawn`, what is drawn of its land filling the frame "
            "(surfaces inside their dissolving borders, above the water: a composition of ranges)"},
           c.framing, kFramings);
  v.list(
      {"path", "keys for `--frames`: frames spread evenly over them, angles linear, zoom geometric"}, c.path,
      {0, 100000},
      [&] {
        return CameraKey{c.azimuth_deg, c.elevation_deg, c.zoom};
      },
      Table::Inline);
}

template <typename V>
void describe(V& v, Canvas& c) {
  v.choice({"type",
            "`rice_paper` (Perlin) and `silk` (Gabor weave) move with the scene; `static` is fixed to the screen "
            "(the shower-door baseline); `none` builds no canvas pass",
            kRebuild},
           c.type, kCanvasTypes);
  v.choice({"static_pattern", "what `static` draws", kRebuild}, c.static_pattern, kCanvasPatterns);
  v.choice({"method",
            "how `rice_paper` and `silk` are drawn: `tiles`, a precomputed noise tile pinned to the surfaces in "
            "small patches (one full-screen pass); `splat`, seed 001's kernels scattered on every triangle by a "
            "geometry shader (the reference, 10-20x slower)",
            kRebuild},
           c.method, kCanvasMethods);
  v.number({"patch",
            "tiles: spacing of the points the tile is pinned to, in kernel radii; smaller follows the surface "
            "more closely under zoom, larger keeps the spectrum closer to the kernels'",
            Effect::Uniform, "kernel radii"},
           c.patch, {0.5, 16});
  v.choice({"zoom",
            "tiles, when the camera moves in or out: `surface` keeps the grain on the surface (it grows and "
            "shrinks with it between octaves, two octaves mixed, 0.5x to 2x); `screen` keeps its size on screen "
            "exact (it slides as the surface scales); `auto` is `surface` for rice paper and `screen` for silk, "
            "whose narrow weave spectrum the octave mix widens",
            Effect::Uniform},
           c.zoom, kCanvasZooms);
  v.number({"contrast", "the paper's brightness is multiplied by 1 + contrast × the unit-variance canvas noise"},
           c.contrast, kUnit);
  v.number({"absorbency", "how far the canvas varies the diffusion's absorbency: 0.75 + 0.25 × absorbency × noise"},
           c.absorbency, kUnit);
  v.number({"grain", "r, the radius of one noise kernel (half the side of a canvas quad)", Effect::Uniform,
            "pixels at 1024 high"},
           c.grain, {0.5, 256});
  v.number({"frequency", "F0, the silk's thread frequency", Effect::Uniform, "cycles/pixel"}, c.frequency, {0, 2});
  v.number(
      {"orientation", "ω0, the thread direction; the second silk noise runs across it", Effect::Uniform, "degrees"},
      c.orientation_deg, {-360, 360});
  v.boolean({"isotropic", "each kernel gets a random direction (a felt rather than a weave)"}, c.isotropic);
  v.number({"mix", "silk: weight of the weft, the noise across the threads (0: threads one way only)"}, c.mix, kUnit);
  v.number({"perlin_frequency", "rice paper: Perlin cycles across one kernel radius"}, c.perlin_frequency, {0, 64});
  v.number({"impulses", "N′, kernels per kernel disc: more is smoother and costs more"}, c.impulses,
           noise::kImpulsesRange);
  v.number({"fibres",
            "rice paper: about this many fibres per 100 × 100 pixels, thin curved threads pinned to the "
            "surfaces like the grain (the `tiles` method; 0 draws none)",
            Effect::Uniform, "per 100² pixels"},
           c.fibres, {0, 4});
  v.number({"fibre_length",
            "mean length of a fibre (they range over 0.6-1.4 times it); a fibre shows over the cube of the "
            "lattice it hangs on, 2.8-5.7 × `patch` × `grain` across on screen, so past about 3 × `patch` × "
            "`grain` some are cut short",
            Effect::Uniform, "pixels at 1024 high"},
           c.fibre_length, {4, 256});
  v.number({"fibre_contrast", "brightness change along a fibre's middle: most fibres darken, some lighten"},
           c.fibre_contrast, kUnit);
  v.number({"spots",
            "rice paper: about this many dark impurity spots (1-4 pixels across) per 100 × 100 pixels (the "
            "`tiles` method)",
            Effect::Uniform, "per 100² pixels"},
           c.spots, {0, 4});
  v.number({"mottle",
            "rice paper: contrast of the paper's cloudy tone, patches about a fibre length across (the `tiles` "
            "method; 0: none)"},
           c.mottle, kUnit);
  v.number({"mottle_cell",
            "rice paper: the mottle is computed once per square of this many pixels and read bilinearly between "
            "them (at 8 within 2 % of its own contrast on average of computing it at every pixel, 1)",
            Effect::Uniform, "pixels at 1024 high"},
           c.mottle_cell, {1, 64});
}

template <typename V>
void describe(V& v, Diffusion& d) {
  v.integer({"ring_steps", "d, main diffusion distance around the strokes; 0 with `iterations` 0: no pass",
             Effect::Uniform, "pixels"},
            d.ring_steps, wide(ink::kRingStepsRange));
  v.number({"attenuation", "f, ink kept per ring: ring r holds f^r of its stroke's ink"}, d.attenuation,
           ink::kAttenuationRange);
  v.number({"absorb", "I_p, ink a paper pixel can absorb over the n iterations (times its absorbency)"}, d.absorb,
           ink::kAbsorbRange);
  v.number({"residual", "I_r, ink a donor pixel keeps; more gives a tighter, more ragged edge"}, d.residual,
           ink::kResidualRange);
  v.integer({"iterations", "n, boundary diffusion iterations"}, d.iterations, wide(ink::kIterationsRange));
  v.number({"threshold", "ink (1 − luminance relative to the paper) above which a pixel is a stroke"}, d.threshold,
           ink::kThresholdRange);
}

template <typename V>
void describe(V& v, Mist& m) {
  v.number({"density", "how far the mist moves ink towards paper at its thickest; 0 = no mist (no mist code)"},
           m.density, kUnit);
  v.number({"height", "top of the full mist, fraction of the scene's vertical extent from its lowest point"}, m.height,
           kUnit);
  v.number({"softness", "band above it over which the mist thins out, same units"}, m.softness, {0.001, 1});
  v.number({"roughness", "noise amplitude that breaks the band into banks, same units"}, m.roughness, {0, 1});
  v.number({"near",
            "share of the mist on the nearest land, growing to all of it at the farthest (the distance fade's "
            "range): below 1 the near bank stands clear and the mist lies between the ranges"},
           m.near, kUnit);
}

template <typename V>
void describe(V& v, Water& w) {
  v.boolean({"enabled",
             "a water level: the land below it is hidden and left as paper with sparse horizontal wave strokes, "
             "the banks drawn as a line; false: no water code",
             kRebuild},
            w.enabled);
  v.number({"level", "the water's surface, fraction of the scene's vertical extent from its lowest point"}, w.level,
           kUnit);
  v.number({"waves", "share of the wave cells that hold a stroke; 0 leaves the water bare paper"}, w.waves, kUnit);
  v.number({"spacing", "wave cell size, fraction of the scene's larger horizontal side"}, w.spacing, {0.001, 1});
  v.number({"ink", "darkness of a wave stroke, fraction of the line colour"}, w.ink, kUnit);
  v.number({"bank", "width of the bank line where land meets the water, pixels at a picture height of 1024; 0: none",
            Effect::Uniform, "pixels"},
           w.bank, {0, 16});
  v.number({"bank_break",
            "how far the bank line breaks into strokes of varying ink along the shore, as a brush draws a shore: "
            "at 1 about a third of it is left as gaps; 0: one even line",
            Effect::Uniform},
           w.bank_break, kUnit);
}

template <typename V>
void describe(V& v, SubstrateParams& p) {
  v.boolean({"enabled",
             "the paper's relief acts on the dried paint (seed 000): dry brush, granulation, lighting, "
             "distortion; false: no substrate pass",
             kRebuild},
            p.enabled);
  v.text({"texture",
          "a scanned paper whose grey is its height, tiled a texel a pixel; empty: the canvas's grain "
          "(value noise without a canvas)",
          kRebuild},
         p.texture, Text::File);
  v.number({"roughness", "r of Eq. 1: how deep the paper's relief is"}, p.roughness, {0, 4});
  v.number({"dry_brush",
            "dry brush: light ink leaves the paper's valleys bare up to this height (times the "
            "object's weight and how light the ink is); 0 = none"},
           p.dry_brush, kUnit);
  v.number({"dry_edge", "height over which the dry brush's bare valleys fade into the ink"}, p.dry_edge, {0.001, 1});
  v.number({"granulation",
            "D of Eq. 4: pigment settling into the paper's valleys, stronger on light washes; 0 = "
            "none"},
           p.granulation, {0, 16});
  v.number({"lighting", "d_s of Eq. 5: the scene's light raking the paper's relief; 0 = none"}, p.lighting, kUnit);
  v.number({"distortion", "the picture is pushed along the paper's slopes by up to this much", Effect::Uniform,
            "pixels at 1024 high"},
           p.distortion, {0, 32});
}

template <typename V>
void describe(V& v, EdgeParams& e) {
  v.boolean({"enabled", "edge darkening and wobbly edges (seed 003); false: no edges pass", kRebuild}, e.enabled);
  v.number({"strength", "pigment at an edge is this much denser: T^(1 + strength)"}, e.strength, {0, 8});
  v.number({"radius", "half-width of the jittered blur that finds edges", Effect::Uniform, "pixels at 1024 high"},
           e.radius, {0.5, 64});
  v.integer({"samples",
             "taps per side of that blur (seed 003: 5, i.e. 25 taps; 3 costs half for 0.1 levels more "
             "error, docs/bench/paper_tradeoff.md)"},
            e.samples, {1, 15});
  v.number({"wobble", "how far the edges wander", Effect::Uniform, "pixels at 1024 high"}, e.wobble, {0, 32});
  v.number({"wobble_scale", "size of the wander's noise features", Effect::Uniform, "pixels at 1024 high"},
           e.wobble_scale, {1, 1024});
}

template <typename V>
void describe(V& v, MotionBlurParams& m) {
  v.boolean({"enabled",
             "ink dragged behind moving objects (seed 004): a velocity target in the G-buffer and a blur "
             "pass; false: neither",
             kRebuild},
            m.enabled);
  v.number({"interval", "seconds between frames: a velocity is how far a point moves in one", Effect::Uniform, "s"},
           m.interval, {1e-4, 10});
  v.number({"length", "k of Eqs. 6-7: the trail is k times the distance moved per interval"}, m.length, {0, 64});
  v.number({"paint", "a of Eq. 6: paint dragged along the trail; from 0.5 up it reaches the trail's end"}, m.paint,
           kUnit);
  v.number({"water", "w of Eq. 7: water carried; from 0.5 up it lasts the trail, below it runs dry on the way"},
           m.water, kUnit);
  v.number({"bristles", "paint varying across the trail, bristle by bristle (seed 004 section 3.5)"}, m.bristles,
           kUnit);
  v.number({"granulation", "paint settling in the paper's valleys along the trail (Eq. 8)"}, m.granulation, kUnit);
}

template <typename V>
void describe(V& v, SubstrateWeights& w) {
  v.number({"dry_brush", "this object's share of substrate.dry_brush"}, w.dry_brush, {0, 4});
  v.number({"granulation", "this object's share of substrate.granulation"}, w.granulation, {0, 4});
  v.number({"lighting", "this object's share of substrate.lighting (the bare paper takes 1)"}, w.lighting, {0, 4});
  v.number({"distortion", "this object's share of substrate.distortion (the bare paper takes 1)"}, w.distortion,
           {0, 4});
}

template <typename V>
void describe(V& v, ShadowParams& sh) {
  v.group("pigment", sh.pigment, Table::Own);
  v.integer({"resolution", "shadow map texels per side", Effect::Uniform, "texels"}, sh.resolution, {64, 8192});
  v.number({"softness", "radius of the filtered shadow edge", Effect::Uniform, "shadow-map texels"}, sh.softness,
           {0, 16});
  v.number(
      {"bias", "depth offset that keeps lit slopes from shadowing themselves", Effect::Uniform, "shadow-map texels"},
      sh.bias, {0, 64});
}

template <typename V>
void describe(V& v, Output& o) {
  v.integer({"width", "`--size WxH` overrides", Effect::Uniform, "pixels"}, o.width, {1, 16384});
  v.integer({"height", "`--size WxH` overrides", Effect::Uniform, "pixels"}, o.height, {1, 16384});
  v.choice({"format",
            "`free`: width × height; `vertical_scroll`: a hanging scroll `height` tall and 0.4 of it wide "
            "(`width` is not used)"},
           o.format, kFormats);
  v.vec3({"paper", "paper colour behind and under the ink", Effect::Uniform, "RGB"}, o.paper, kUnit, Vec::Color);
  v.number({"fade", "distance fade: far surfaces move towards the paper by up to this much"}, o.fade, kUnit);
}

template <typename V>
void describe(V& v, Scene& s) {
  v.integer({"seed", "seed of every noise (erosion, canvas kernels, paper absorbency); same seed, same picture"},
            s.seed, {0, 1LL << 53});
  v.list(
      {"objects", "the objects, below", kRebuild}, s.objects, {1, 255}, [] { return Object{}; }, Table::Own);
  v.group("light", s.light, Table::Inline);
  v.group("camera", s.camera, Table::Own);
  v.group("canvas", s.canvas, Table::Own);
  v.group("diffusion", s.diffusion, Table::Own);
  v.group("mist", s.mist, Table::Own);
  v.group("water", s.water, Table::Own);
  v.group("shadow", s.shadow, Table::Inline);
  v.group("substrate", s.substrate, Table::Own);
  v.group("edges", s.edges, Table::Own);
  v.group("motion_blur", s.motion_blur, Table::Own);
  v.group("output", s.output, Table::Own);
  // After the water's keys: an object may float on it.
  v.check("objects", [&]() -> std::string { return groundingProblem(s); });
}

}  // namespace shanshui::scene
