#pragma once
// Smooth displacement fields known everywhere, for measuring the skin alone (`sandbox tradeoff
// --skin-only`): the control points are moved by the field and the skinned render mesh is compared with
// the same field applied to every render vertex. Coordinates are the vehicle frame: +x forward (the
// front bumper at the box's largest x), +y left, +z up; s = x - x_c, h = z - z_c, y' = y - y_c about the
// centre (x_c, y_c, z_c) of the car's bounding box, L its length and W its width.
#include <deform/mesh.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace sandbox {

/// A displacement u(p) [m] defined at every point p [m] of the vehicle frame.
struct KnownField {
  std::string name;     ///< "bend", "twist", "crush", "affine"
  std::string formula;  ///< the formula, for the Markdown report
  std::function<Eigen::Vector3d(const Eigen::Vector3d& p_m)> displacement_m;
};

/// Bend about a transverse (y) axis, the beam's small-deflection field (Euler-Bernoulli: plane sections
/// stay plane and normal to the bent axis; e.g. Timoshenko & Goodier, Theory of Elasticity, section 21):
/// u = (-kappa s h, 0, kappa s^2 / 2), kappa = 0.8 / L^2 [1/m], so both ends rise 0.1 m.
KnownField bendField(const deform::Aabb& box);

/// Twist about the long axis through (y_c, z_c): each section x turned rigidly by
/// theta(x) = (10 deg) s / L, 10 degrees end to end (Saint-Venant torsion without warping).
KnownField twistField(const deform::Aabb& box);

/// Frontal crush: with d = x_max - x the distance behind the front bumper and the smooth decay
/// w(d) = (1 + cos(pi d / 1.5 m)) / 2 for d < 1.5 m, 0 behind, u = (-0.5 m w, 0.1 m w y' / (W / 2), 0):
/// the bumper pushed back 0.5 m, falling smoothly (zero slope at both ends) to 0 at 1.5 m behind it,
/// the sides bulging out by up to 0.1 m at the front.
KnownField crushField(const deform::Aabb& box);

/// An affine motion u = A p + t (a stretch, shear and turn of about 2 %, and a shift of a few cm): the
/// mls skin reproduces it exactly (linear precision), idw does not.
KnownField affineField(const deform::Aabb& box);

/// bend, twist, crush and affine.
std::vector<KnownField> knownFields(const deform::Aabb& box);

}  // namespace sandbox
