#version 450 core
// G-buffer pass: world normal and dimensionless curvature (|k| times the mesh's feature
// size), and the surface detail the shading reads, with the object id. Curvature is either
// interpolated from the vertices (OBJECT_CURVATURE) or, as seed 001 does, estimated in
// screen space from how fast the normal turns per unit of surface, |fwidth(N)| / |fwidth(P)|
// (SCREEN_CURVATURE); objects without lines get neither. World positions are not stored:
// the image passes rebuild them from the depth buffer.
in vec3 v_normal;
#ifdef WRINKLE
in vec2 v_uv;
uniform sampler2D u_wrinkle;   // Eq. 5's luma of the wrinkle texture, mipmapped
uniform float u_repeat;        // texture repetitions per UV unit
#endif
#ifdef OBJECT_CURVATURE
in float v_curvature;
#endif
#if defined(SCREEN_CURVATURE) || defined(WRINKLE_SLOPE)
in vec3 v_world;
#endif
#ifdef SCREEN_CURVATURE
uniform float u_feature_size;  // world units
#endif
#ifdef WRINKLE_SLOPE
uniform float u_tile_px;  // a texture tile's size on screen, pixels
uniform float u_angle;    // radians: the texture's v axis turned from the fall line

uint slopeHash(uvec2 p) {
  uint h = p.x * 0x8da6b343u ^ p.y * 0xd8163841u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  return h;
}

// The wrinkle texture at one octave: q are tile coordinates (one unit per tile), turned by
// m about the three nearest points of a triangular lattice of half-tile spacing (each with
// its own random offset into the texture) and blended with weights that fall smoothly to 0
// away from each point, so a turn that changes across the surface bends the strokes instead
// of sliding the texture from a far origin. (A square lattice needs four reads: on a
// software rasteriser each costs about 1.5 % of a frame.)
float wrinkleOctave(vec2 q, mat2 m, float lod) {
  const float F2 = 0.36602540, G2 = 0.21132487;  // the skew and unskew of 2D simplex noise
  vec2 cell = q * 2.0;
  vec2 base = floor(cell + dot(cell, vec2(F2)));  // skewed lattice coordinates of corner 0
  vec2 x0 = cell - base + dot(base, vec2(G2));   // from corner 0, in cells
  vec2 i1 = x0.x > x0.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
  float sum = 0.0, total = 0.0;
  for (int i = 0; i < 3; ++i) {
    vec2 step_ = i == 0 ? vec2(0.0) : (i == 1 ? i1 : vec2(1.0));
    vec2 x = x0 - step_ + dot(step_, vec2(G2));  // from this corner, in cells
    uint h = slopeHash(uvec2(ivec2(base + step_) + 32768));
    vec2 offset = vec2(h & 0xffffu, h >> 16) / 65536.0;
    float r = max(0.5 - dot(x, x), 0.0);
    float weight = r * r;
    vec2 t = m * (x * 0.5) + offset;  // x / 2: from the corner in tile units
    sum += weight * textureLod(u_wrinkle, t, lod).r;
    total += weight;
  }
  return sum / total;
}

// Eq. 5's luma with the texture's v axis down the fall line: the fall line (the steepest
// descent on the surface, +Z up) is carried into UV space through the UVs' screen
// derivatives, and the tile's size on screen is held near u_tile_px by blending the two
// power-of-two octaves around it (from half to twice it, the nearer weighing more), so the
// strokes keep their size as the camera zooms and stay on the surface as it moves.
float slopeWrinkle(vec3 n) {
  vec3 dpx = dFdx(v_world), dpy = dFdy(v_world);
  vec2 dux = dFdx(v_uv), duy = dFdy(v_uv);
  float det = dux.x * duy.y - duy.x * dux.y;
  if (!(abs(det) > 1e-30)) return texture(u_wrinkle, v_uv * u_repeat).r;
  vec3 tu = (dpx * duy.y - dpy * dux.y) / det;  // dP/du
  vec3 tv = (dpy * dux.x - dpx * duy.x) / det;  // dP/dv
  vec3 down = vec3(0.0, 0.0, -1.0) + n.z * n;   // -Z less its normal part
  float uu = dot(tu, tu), uv = dot(tu, tv), vv = dot(tv, tv);
  float gram = uu * vv - uv * uv;
  vec2 d = gram > 0.0 ? vec2(vv * dot(down, tu) - uv * dot(down, tv), uu * dot(down, tv) - uv * dot(down, tu)) / gram
                      : vec2(0.0);
  // On flat ground there is no fall line: the strokes run along v there.
  float steep = smoothstep(0.02, 0.15, length(down));
  vec2 dir = length(d) > 0.0 ? normalize(d) : vec2(0.0, 1.0);
  dir = mix(vec2(0.0, 1.0), dir, steep);
  dir = length(dir) > 1e-6 ? normalize(dir) : vec2(0.0, 1.0);
  float c = cos(u_angle), s = sin(u_angle);
  dir = vec2(c * dir.x - s * dir.y, s * dir.x + c * dir.y);
  mat2 m = mat2(dir.y, dir.x, -dir.x, dir.y);  // takes dir to (0, 1): rows (dir.y, -dir.x), (dir.x, dir.y)
  float scale = log2(max(u_tile_px * sqrt(abs(det)), 1e-30));  // log2 of tiles' UV size at u_tile_px
  float level = floor(scale), blend = scale - level;
  float size0 = exp2(level), size1 = 2.0 * size0;
  // One mip level per octave, from the footprint of a pixel in texels (turning does not
  // change it): explicit-gradient fetches cost llvmpipe a level computation each.
  float texels = float(textureSize(u_wrinkle, 0).x) * max(length(dux), length(duy));
  float lod0 = log2(max(texels / size0, 1e-30));
  float a = wrinkleOctave(v_uv / size0, m, lod0);
  float b = wrinkleOctave(v_uv / size1, m, lod0 - 1.0);
  return mix(a, b, blend);
}
#endif
#ifdef SURFACE
in vec2 v_noise_uv;
uniform sampler2D u_noise;     // r: erosion noise, g: noise added before quantisation
#endif
uniform float u_object_id;     // (index + 1) / 255

layout(location = 0) out vec4 o_normal_curvature;  // RGBA16: n / 2 + 1/2, k / (1 + k)
layout(location = 1) out vec4 o_surface_id;  // erosion noise, added noise, wrinkle luma, id
#ifdef VELOCITY
// Seed 004's velocity buffer: how far this point moved on screen since the previous frame,
// in pixels; alpha 1 marks a surface (the target is cleared to 0).
in vec4 v_clip;
in vec4 v_previous_clip;
uniform vec2 u_viewport;
layout(location = 2) out vec4 o_velocity;
#endif

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  float k = 0.0;
#ifdef OBJECT_CURVATURE
  k = v_curvature;
#endif
#ifdef SCREEN_CURVATURE
  float dp = length(fwidth(v_world));
  k = dp > 0.0 ? length(fwidth(n)) / dp * u_feature_size : 0.0;
#endif
  // Unsigned normalised 16 bits (half floats cost a software rasteriser a conversion per
  // channel): the normal's components from [-1, 1], the curvature (never negative) from
  // [0, ∞) with k / (1 + k), relative precision ~1e-4 up to k ≈ 10 (ink.frag decodes).
  o_normal_curvature = vec4(n * 0.5 + 0.5, max(k, 0.0) / (1.0 + max(k, 0.0)));
  vec2 noise = vec2(1.0, 0.5);  // no erosion, nothing added
#ifdef SURFACE
  noise = texture(u_noise, v_noise_uv).rg;
#endif
  float wrinkle = 1.0;
#if defined(WRINKLE_SLOPE)
  wrinkle = slopeWrinkle(n);
#elif defined(WRINKLE)
  wrinkle = texture(u_wrinkle, v_uv * u_repeat).r;
#endif
  o_surface_id = vec4(noise, wrinkle, u_object_id);
#ifdef VELOCITY
  vec2 now = v_clip.xy / v_clip.w, before = v_previous_clip.xy / v_previous_clip.w;
  o_velocity = vec4((now - before) * 0.5 * u_viewport, 0.0, 1.0);
#endif
}
