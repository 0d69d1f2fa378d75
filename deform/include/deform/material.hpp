#pragma once
// The material of the deformable body, in physical units that do not depend on the level of detail
// (DESIGN.md section 5, "The answer must not depend on the level of detail"). Each constraint takes its
// stiffness and its yield from the geometry it stands for (body_settings.cpp):
//  - a spoke (control point to core) is a column of the crushable structure behind the skin, as wide as
//    the point's tributary area A (a third of the area of its triangles) and as long as the spoke L0:
//    it yields at the force crush_strength_Pa x A after an elastic strain crush_yield_strain, so a flat
//    obstacle meets the same pressure, and a crushed volume absorbs the same energy, at any N;
//  - an edge is a strip of the shell membrane: stiffness shell_stiffness_N_per_m x (A_left + A_right) /
//    L^2 (Van Gelder 1998, "Approximate simulation of elastic membranes by triangulated spring meshes"),
//    yielding at a force per unit strip width in tension and in compression (a thin panel folds under a
//    far smaller compressive load than it takes to stretch it);
//  - a bend is the shell's bending across a hinge: hinge stiffness 6 D |e|^2 / (A_left + A_right)
//    (Grinspun et al. 2003, "Discrete Shells"), taken to the distance of the wing points, yielding at the
//    plastic moment per unit hinge length.
// Plasticity follows the 1D elastoplastic return map (Simo and Hughes 1998, Box 1.1) on the elastic
// elongation l - L against a yield elongation fixed by the original geometry, so a column's yield force
// does not fall as it shortens.
#include <string>

namespace deform {

/// What a body is made of, in units that do not depend on the level of detail (see above).
struct Material {
  /// Crush strength: the pressure the structure behind the skin puts up while it crushes (the plateau of
  /// its force-crush curve per unit of skin area) [Pa = N/m^2]; 0 = no load path to the core.
  double crush_strength_Pa = 4.0e5;
  /// Elastic strain of a crush column before it yields (its spring-back) [1]; > 0.
  double crush_yield_strain = 0.012;
  /// Membrane stiffness of the shell, Young's modulus x thickness [N/m]. A flat 0.8 mm steel sheet has
  /// 1.7e8; a body's formed panels, with openings and spot welds, and a control mesh whose triangles
  /// cannot wrinkle, are taken an order of magnitude softer (measured: at 1.7e8 a pole pressed into the
  /// bumper moved the rear of the shell by 19 mm through the membrane).
  double shell_stiffness_N_per_m = 1.7e7;
  /// Membrane force per unit width at which the shell yields when stretched [N/m]. 0.8 mm steel at
  /// 250 MPa takes 2e5 N/m; a dented panel wrinkles and draws in long before that, so the lattice, which
  /// cannot wrinkle, yields at a tenth.
  double shell_tension_yield_N_per_m = 2e4;
  /// Membrane force per unit width at which the shell folds when compressed [N/m]: a thin panel buckles
  /// long before the steel yields (its plate buckling load).
  double shell_compression_yield_N_per_m = 5e3;
  /// Bending stiffness of the shell, E t^3 / 12 [N m] (0.8 mm steel: 9).
  double shell_bending_stiffness_N_m = 9.0;
  /// Plastic bending moment per unit hinge length, sigma_y t^2 / 4 [N m / m = N] (0.8 mm steel: 40).
  double shell_yield_moment_N = 40.0;
  /// Linear hardening as a ratio of plastic to elastic modulus [1]: the yield elongation grows by
  /// `hardening` x the plastic elongation |L - L0| already taken; 0 = perfectly plastic.
  double hardening = 0.0;
  /// Rest lengths stay within [min_rest_fraction, max_rest_fraction] x their original length [1], so
  /// repeated impacts can never collapse an element to zero. 0 < min <= 1 <= max.
  double min_rest_fraction = 0.25;
  double max_rest_fraction = 2.0;
};

/// Throws InputError naming `field` (e.g. "regions[2].material") and the member for a negative or
/// non-finite value, a zero crush_yield_strain or shell_stiffness_N_per_m, or a rest clamp outside
/// 0 < min <= 1 <= max.
void checkMaterial(const Material& material, const std::string& field);

}  // namespace deform
