#include "frame/atmosphere.h"

#include <algorithm>
#include <limits>

#include "shanshui/render/frame_params.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/grounding.h"

namespace shanshui::render {

namespace {
double smooth01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
}  // namespace

glm::dvec2 fadeRange(const FrameInputs& in) {
  const glm::dvec3 eye = in.camera.eye();
  glm::dvec2 range(1e300, 0.0);
  for (int c = 0; c < 8; ++c) {
    const double d = glm::length(in.world_bounds.corner(c) - eye);
    range = {std::min(range.x, d), std::max(range.y, d)};
  }
  return range;
}

double presence(const FrameInputs& in, std::size_t object, const glm::dmat4& to_model, glm::dvec3 world,
                glm::dvec2 fade_range) {
  const scene::Scene& s = in.scene;
  const double far =
      smooth01((glm::length(world - in.camera.eye()) - fade_range.x) / std::max(fade_range.y - fade_range.x, 1e-9));
  double f = 1.0 - s.output.fade * far;
  if (s.mist.enabled()) {
    const double z0 = in.world_bounds.min.z, extent = std::max(in.world_bounds.size().z, 1e-9);
    const double h0 = (world.z - (z0 + s.mist.height * extent)) / std::max(s.mist.softness * extent, 1e-9);
    const double share = s.mist.near + (1.0 - s.mist.near) * far;
    f *= 1.0 - s.mist.density * share * (1.0 - smooth01(h0));
  }
  const scene::Object& o = s.objects[object];
  if (o.dissolvesBorder()) {
    const glm::dvec3 m = glm::dvec3(to_model * glm::dvec4(world, 1.0));
    const glm::dvec3 half = 0.5 * in.objects[object].model_bounds.size();
    const double width = o.border.width * std::min(half.x, half.y);
    const double t = std::min(half.x - std::abs(m.x), half.y - std::abs(m.y)) / std::max(width, 1e-12);
    f *= smooth01(t - 0.5 * o.border.roughness);
  }
  return std::clamp(f, 0.0, 1.0);
}

float waterLevel(const FrameInputs& in) {
  if (!in.scene.usesWater()) return std::numeric_limits<float>::lowest();
  return static_cast<float>(scene::waterHeight(in.scene, in.world_bounds));
}

glm::vec3 pictureHorizontal(const FrameInputs& in) {
  const glm::mat4 v = in.camera.view();
  glm::dvec3 r(v[0][0], v[1][0], 0.0);
  if (glm::length(r) < 1e-9) r = {1.0, 0.0, 0.0};
  return glm::vec3(glm::normalize(r));
}

gpu::FrameParams frameParams(const FrameInputs& in) {
  gpu::FrameParams f{};
  const OrbitCamera& camera = in.camera;
  const scene::Scene& s = in.scene;
  const double aspect = static_cast<double>(in.width) / in.height;
  f.u_view_projection = in.viewProjection();
  f.u_inverse_view_projection =
      glm::mat4(glm::inverse(glm::dmat4(camera.projection(aspect)) * glm::dmat4(camera.view())));
  f.u_eye = glm::vec3(camera.eye());
  f.u_fade = static_cast<float>(s.output.fade);
  f.u_light_dir = glm::vec3(glm::normalize(s.light.direction));
  f.u_paper = glm::vec3(s.output.paper);
  f.u_near_far = glm::vec2(static_cast<float>(camera.near_plane), static_cast<float>(camera.far_plane));
  // Aerial perspective over the distances the scene spans from this eye: nothing at its
  // nearest corner, full at its farthest, so the far third of the land is the lighter
  // whatever the view.
  const glm::dvec2 fade = fadeRange(in);
  f.u_fade_range = glm::vec2(static_cast<float>(fade.x), static_cast<float>(std::max(fade.y, fade.x + 1e-6)));
  if (s.mist.enabled()) {
    // Heights as fractions of the scene's vertical extent; noise cells about a tenth of the
    // scene's horizontal size.
    const scene::Mist& m = s.mist;
    const double z0 = in.world_bounds.min.z, extent = std::max(in.world_bounds.size().z, 1e-9);
    f.u_mist =
        glm::vec4(static_cast<float>(m.density), static_cast<float>(z0 + m.height * extent),
                  static_cast<float>(std::max(m.softness * extent, 1e-9)), static_cast<float>(m.roughness * extent));
    const double size = std::max(std::max(in.world_bounds.size().x, in.world_bounds.size().y), 1e-9);
    f.u_mist_noise = static_cast<float>(2.0 / size);
    f.u_mist_near = static_cast<float>(m.near);
  }
  // The water's level and its waves' cells in world units, the picture's horizontal on it,
  // the open water's rectangle (the land's bounds) and the bank line's width in pixels.
  const scene::Water& w = s.water;
  const double side = std::max({in.world_bounds.size().x, in.world_bounds.size().y, 1e-9});
  f.u_water = glm::vec4(waterLevel(in), static_cast<float>(w.spacing * side), static_cast<float>(w.waves),
                        static_cast<float>(w.ink));
  f.u_water_right = glm::vec2(pictureHorizontal(in));
  f.u_water_extent =
      glm::vec4(in.world_bounds.min.x, in.world_bounds.min.y, in.world_bounds.max.x, in.world_bounds.max.y);
  f.u_water_bank = static_cast<float>(w.bank * in.height / 1024.0);
  f.u_water_bank_break = static_cast<float>(w.bank_break);
  f.u_viewport = glm::vec2(in.width, in.height);
  f.u_pixel_angle = static_cast<float>(2.0 * std::tan(glm::radians(camera.fov_y_deg) * 0.5) / std::max(in.height, 1));
  // The picture plane of the view the scene is composed for (its own azimuth and its camera's
  // or preset's elevation, not the camera's now): that view's right and up rows.
  OrbitCamera composed;
  composed.azimuth_deg = s.camera.azimuth_deg;
  composed.elevation_deg = composedElevation(s);
  const glm::mat4 view = composed.view();
  f.u_brush_right = glm::vec3(view[0][0], view[1][0], view[2][0]);
  f.u_brush_up = glm::vec3(view[0][1], view[1][1], view[2][1]);
  return f;
}

}  // namespace shanshui::render
