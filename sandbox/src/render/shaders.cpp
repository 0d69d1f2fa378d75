#include "render/shaders.hpp"

#include <string>

namespace sandbox::render::shaders {
namespace {

// Shared by the mesh and ground programs: lights, the soft shadow and the output transform.
const char* const kLighting = R"(
uniform vec3 u_sun_direction;   // unit, towards the sun
uniform vec3 u_sun_radiance;    // linear colour x intensity
uniform vec3 u_sky_ambient;     // linear hemisphere light from above
uniform vec3 u_ground_ambient;  // linear hemisphere light from below
uniform vec3 u_eye;
uniform int u_shadows;
uniform sampler2DShadow u_shadow_map;
uniform vec2 u_shadow_radius;   // PCF kernel radius in shadow-map UV units (x, y)
uniform float u_shadow_bias;        // constant depth bias [light depth units]
uniform float u_shadow_slope_bias;  // bias per unit tan(angle to the sun) [light depth units]

// 16-tap Poisson disk: irregular taps hide the banding a regular PCF grid shows in soft penumbrae. The
// first eight lie near the rim, one per 45-degree sector: they decide whether the inner eight are needed.
const vec2 kPoisson[16] = vec2[](
    vec2(0.97484398, 0.75648379), vec2(0.19984126, 0.78641367), vec2(-0.81409955, 0.91437590),
    vec2(-0.91588581, 0.45771432), vec2(-0.94201624, -0.39906216), vec2(-0.09418410, -0.92938870),
    vec2(0.44323325, -0.97511554), vec2(0.94558609, -0.76890725), vec2(-0.24188840, 0.99706507),
    vec2(-0.81544232, -0.87912464), vec2(0.34495938, 0.29387760), vec2(-0.38277543, 0.27676845),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(0.14383161, -0.14100790));

// Fraction of the sun that reaches a point (1 lit .. 0 fully shadowed).
// llvmpipe runs both sides of an `if` for a block of pixels but leaves a loop as soon as no pixel of
// the block needs another iteration, so the work is skipped with loop counts, not with early returns:
// no taps without shadows, outside the map or facing away from the sun, and only the eight rim taps
// where they agree (fully lit or fully shadowed, which is most of the picture). Four rim taps were
// measured too few: thin shadows (a tyre's contact patch) slipped between them and left streaks.
float sunVisibility(vec4 light_clip, float n_dot_l) {
  vec3 p = light_clip.xyz / light_clip.w * 0.5 + 0.5;
  bool inside = u_shadows != 0 && n_dot_l > 0.0 && p.x > 0.0 && p.x < 1.0 && p.y > 0.0 && p.y < 1.0 &&
                p.z < 1.0;
  // Across the PCF kernel a surface tilted away from the sun spans a depth range of about
  // radius x tan(angle); biasing by that keeps soft shadows free of self-shadowing acne.
  float c = clamp(n_dot_l, 0.05, 1.0);
  float bias = u_shadow_bias + u_shadow_slope_bias * min(sqrt(1.0 - c * c) / c, 3.0);
  vec3 centre = vec3(p.xy, p.z - bias);
  float lit = 0.0;
  int taps = inside ? 8 : 0;
  for (int i = 0; i < taps; ++i) {
    lit += textureLod(u_shadow_map, centre + vec3(kPoisson[i] * u_shadow_radius, 0.0), 0.0);
  }
  if (!inside) return 1.0;
  taps = (lit > 0.0 && lit < 8.0) ? 16 : 8;
  for (int i = 8; i < taps; ++i) {
    lit += textureLod(u_shadow_map, centre + vec3(kPoisson[i] * u_shadow_radius, 0.0), 0.0);
  }
  return lit / float(taps);
}

vec3 toLinear(vec3 srgb) { return pow(max(srgb, vec3(0.0)), vec3(2.2)); }

// ACES filmic fit (Narkowicz 2015): bright highlights roll off instead of clipping to flat white.
vec3 toDisplay(vec3 linear) {
  vec3 x = linear;
  vec3 mapped = clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
  return pow(mapped, vec3(1.0 / 2.2));
}

// Sun (Lambert + normalised Blinn-Phong highlight, shadowed) plus hemisphere ambient.
vec3 shade(vec3 albedo, vec3 n, vec3 world, float visibility, float specular, float shininess) {
  vec3 l = u_sun_direction;
  vec3 v = normalize(u_eye - world);
  float n_dot_l = max(dot(n, l), 0.0);
  vec3 h = normalize(l + v);
  float highlight = specular * (shininess + 8.0) / 25.13 * pow(max(dot(n, h), 0.0), shininess);
  vec3 ambient = mix(u_ground_ambient, u_sky_ambient, n.z * 0.5 + 0.5);
  // A little fresnel-like sky reflection at grazing angles reads as a painted, curved body.
  float rim = pow(1.0 - max(dot(n, v), 0.0), 4.0) * specular * 0.5;
  return albedo * (ambient + u_sun_radiance * n_dot_l * visibility) +
         u_sun_radiance * highlight * n_dot_l * visibility + u_sky_ambient * rim;
}
)";

}  // namespace

const char* const kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_colour;
uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;
uniform mat4 u_light_view_projection;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_colour;
out vec4 v_light_clip;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_colour = a_colour;
  v_light_clip = u_light_view_projection * world;
  gl_Position = u_view_projection * world;
}
)";

const std::string kMeshFragment = std::string("#version 330 core\n") + kLighting + R"(
in vec3 v_world;
in vec3 v_normal;
in vec3 v_colour;
in vec4 v_light_clip;
uniform float u_specular;
uniform float u_shininess;
out vec4 o_colour;
void main() {
  vec3 n = normalize(v_normal);
  // Two-sided: imported meshes are not always consistently wound or closed.
  if (!gl_FrontFacing) n = -n;
  float visibility = sunVisibility(v_light_clip, dot(n, u_sun_direction));
  vec3 colour = shade(toLinear(v_colour), n, v_world, visibility, u_specular, u_shininess);
  o_colour = vec4(toDisplay(colour), 1.0);
}
)";

const char* const kGroundVertex = R"(#version 330 core
uniform vec2 u_centre;
uniform float u_radius;
uniform float u_height;
uniform mat4 u_view_projection;
uniform mat4 u_light_view_projection;
out vec3 v_world;
out vec4 v_light_clip;
void main() {
  // Two triangles (0,1,2) (2,1,3) covering the square of half-size u_radius.
  int corner = gl_VertexID == 3 ? 2 : (gl_VertexID == 4 ? 1 : (gl_VertexID == 5 ? 3 : gl_VertexID));
  vec2 xy = u_centre + u_radius * vec2((corner & 1) == 0 ? -1.0 : 1.0, (corner & 2) == 0 ? -1.0 : 1.0);
  vec4 world = vec4(xy, u_height, 1.0);
  v_world = world.xyz;
  v_light_clip = u_light_view_projection * world;
  gl_Position = u_view_projection * world;
}
)";

const std::string kGroundFragment = std::string("#version 330 core\n") + kLighting + R"(
in vec3 v_world;
in vec4 v_light_clip;
uniform vec2 u_centre;
uniform float u_radius;
uniform float u_grid_spacing;
uniform vec3 u_ground_linear;  // the ground's colour, linear (converted once, not per pixel)
uniform vec3 u_line_linear;    // the grid lines' colour, linear
uniform vec3 u_horizon;
out vec4 o_colour;

// Coverage of grid lines `width_px` pixels wide, spaced `spacing` apart; fades out where the lines
// would be closer than a few pixels (far away), which would otherwise alias into moire.
float gridLines(vec2 xy, float spacing, float width_px) {
  vec2 coord = xy / spacing;
  vec2 footprint = fwidth(coord);
  vec2 distance_px = abs(fract(coord - 0.5) - 0.5) / max(footprint, vec2(1e-6));
  float line = 1.0 - clamp(min(distance_px.x, distance_px.y) - 0.5 * width_px + 0.5, 0.0, 1.0);
  float density = max(footprint.x, footprint.y);
  return line * (1.0 - smoothstep(0.15, 0.45, density));
}

void main() {
  float minor = gridLines(v_world.xy, u_grid_spacing, 1.0) * 0.55;
  float major = gridLines(v_world.xy, 5.0 * u_grid_spacing, 1.6);
  vec3 albedo = mix(u_ground_linear, u_line_linear, max(minor, major));
  float visibility = sunVisibility(v_light_clip, u_sun_direction.z);
  // shade() for the normal (0, 0, 1) without a highlight: the ambient is the sky's alone, and the
  // per-pixel view vectors and powers the ground does not need are skipped (the ground covers most
  // of the frame).
  vec3 colour = albedo * (u_sky_ambient + u_sun_radiance * max(u_sun_direction.z, 0.0) * visibility);
  // Fade into the horizon so the plane's edge never shows.
  float fade = smoothstep(0.3 * u_radius, 0.95 * u_radius, length(v_world.xy - u_centre));
  o_colour = vec4(mix(toDisplay(colour), u_horizon, fade), 1.0);
}
)";

const char* const kShadowVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_light_view_projection;
void main() { gl_Position = u_light_view_projection * u_model * vec4(a_position, 1.0); }
)";

const char* const kShadowFragment = R"(#version 330 core
void main() {}
)";

const char* const kSkyVertex = R"(#version 330 core
out vec2 v_ndc;
void main() {
  // One triangle that covers the screen: (-1,-1), (3,-1), (-1,3).
  v_ndc = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(v_ndc, 1.0, 1.0);
}
)";

const char* const kSkyFragment = R"(#version 330 core
in vec2 v_ndc;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_zenith;   // sRGB
uniform vec3 u_horizon;  // sRGB
out vec4 o_colour;
void main() {
  vec4 near = u_inverse_view_projection * vec4(v_ndc, -1.0, 1.0);
  vec4 far = u_inverse_view_projection * vec4(v_ndc, 1.0, 1.0);
  vec3 ray = normalize(far.xyz / far.w - near.xyz / near.w);
  float t = pow(clamp(ray.z, 0.0, 1.0), 0.6);
  o_colour = vec4(mix(u_horizon, u_zenith, t), 1.0);
}
)";

}  // namespace sandbox::render::shaders
