#pragma once
// What the renderer draws: meshes (uploaded once, positions updated per frame), a ground plane with a
// grid, a sun and a sky. Colours are sRGB in [0, 1]; lighting is computed in linear light.
#include <deform/mesh.hpp>

#include <Eigen/Core>
#include <vector>

namespace sandbox::render {

/// A mesh as the renderer takes it: vehicle-frame geometry plus how to place and colour it.
struct MeshData {
  std::vector<Eigen::Vector3f> positions_m;  ///< vertex positions in the mesh's own frame [m]
  std::vector<Eigen::Vector3f> normals;      ///< unit vertex normals, one per position (required)
  std::vector<deform::Triangle> triangles;   ///< vertex indices; winding matters only when `closed`
  std::vector<Eigen::Vector3f> colours;      ///< per-vertex sRGB (heat map); empty: base_colour
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();  ///< mesh frame -> world (rigid + uniform scale)
  Eigen::Vector3f base_colour{0.75f, 0.08f, 0.06f};     ///< sRGB colour without per-vertex colours
  float specular = 0.35f;   ///< strength of the sun's highlight (0 matte .. 1 glossy paint)
  float shininess = 60.0f;  ///< Blinn-Phong exponent: larger is a smaller, sharper highlight
  /// Closed surface wound counter-clockwise seen from outside: back faces are culled (half the
  /// triangles, which is what a 900,000-vertex body costs in a software rasteriser) and the shadow
  /// pass draws the back faces instead (no self-shadowing acne on lit faces). False: two-sided.
  bool closed = false;
};

/// True when every edge of `mesh` is shared by exactly two triangles that traverse it in opposite
/// directions (closed, consistently wound) and the enclosed volume is positive (wound outwards).
bool isClosedOutward(const deform::Mesh& mesh);

/// Copies `mesh` (computing normals when it has none) with the given colour; `closed` is set by
/// isClosedOutward.
MeshData meshData(const deform::Mesh& mesh, const Eigen::Vector3f& base_colour);

/// The ground: a horizontal plane with grid lines that fades into the horizon colour far away.
struct Ground {
  bool visible = true;
  float height_m = 0.0f;           ///< world Z of the plane [m]
  Eigen::Vector2f centre_m{0, 0};  ///< world XY the grid and the fade are centred on [m]
  float radius_m = 80.0f;          ///< distance at which the plane has faded into the horizon [m]
  float grid_spacing_m = 1.0f;     ///< minor grid line spacing; every fifth line is stronger [m]
  Eigen::Vector3f colour{0.62f, 0.62f, 0.60f};       ///< sRGB of the plane
  Eigen::Vector3f line_colour{0.42f, 0.42f, 0.42f};  ///< sRGB of the grid lines
};

/// Lights and background.
struct Environment {
  Ground ground;
  Eigen::Vector3f sun_direction{-0.22f, 0.60f, 0.77f};  ///< towards the sun (normalised when used)
  float sun_intensity = 2.2f;                           ///< linear multiplier of the sun's colour
  Eigen::Vector3f sun_colour{1.0f, 0.96f, 0.90f};       ///< sRGB
  Eigen::Vector3f sky_light{0.62f, 0.69f, 0.80f};       ///< sRGB ambient from above (hemisphere light)
  Eigen::Vector3f ground_light{0.38f, 0.35f, 0.31f};    ///< sRGB ambient from below (bounce)
  float ambient_intensity = 0.85f;                      ///< linear multiplier of the hemisphere light
  bool shadows = true;                                  ///< soft sun shadow (shadow map with PCF)
  bool sky = true;  ///< gradient sky; false: the plain background colour (tests count those pixels)
  Eigen::Vector3f sky_zenith{0.36f, 0.55f, 0.82f};   ///< sRGB straight up
  Eigen::Vector3f sky_horizon{0.82f, 0.87f, 0.92f};  ///< sRGB at the horizon (also the ground's fade)
  Eigen::Vector3f background{0.82f, 0.87f, 0.92f};   ///< sRGB clear colour when sky is false
};

/// Default lights and sky with the ground under `box` (its lowest point), centred below it, with a
/// grid and horizon fade scaled to its size: the same picture for a drinks can as for a car.
Environment environmentAround(const deform::Aabb& box);

/// Grid spacing that gives a handful of lines across an object of diagonal `diagonal_m`: a power of ten
/// (1 m for a car, 1 cm for a drinks can).
float gridSpacingFor(double diagonal_m);

}  // namespace sandbox::render
