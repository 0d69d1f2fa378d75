#pragma once
// The material of the deformable body's constraints: how compliant they are and when they yield.
// Compliance is the inverse of stiffness, in m/N (XPBD, Macklin, Mueller, Chentanez 2016, eq. 4: the
// potential U = 1/2 C^T alpha^-1 C); 0 is rigid. Plasticity follows the 1D elastoplastic return map
// (Simo and Hughes 1998, Box 1.1) on the elastic strain e = (l - L) / L (DESIGN.md section 4).
#include <string>

namespace deform {

/// Choosing compliances: a constraint is effectively rigid for the solver when alpha m / h^2 << 1 (m the
/// point mass, h the substep). Many such constraints on a fine control mesh (thousands of light points)
/// over-constrain the shell and one Gauss-Seidel sweep per substep jitters (seen at 4,000 points with the
/// default edges, 1e-6 m/N); 1e-5 .. 1e-4 m/N edges, more iterations or more substeps settle it. Spokes
/// act in parallel, so the body's radial stiffness is about N / spoke compliance: to keep a car equally
/// stiff across levels of detail, scale the spoke compliance with N.
struct Material {
  double edge_compliance_m_per_N = 1e-6;   ///< hull edges (the shell's structure) [m/N]; 0 = rigid
  double spoke_compliance_m_per_N = 1e-5;  ///< spokes, control point to core (volume, load path) [m/N]
  double bend_compliance_m_per_N = 1e-5;   ///< bending across each hull edge [m/N]
  /// Elastic strain |l - L| / L beyond which the rest length L flows [1]; 0 = every strain is plastic.
  double yield_strain = 0.02;
  /// Linear hardening as a ratio of plastic to elastic modulus [1]: the yield strain grows by
  /// `hardening` x the plastic strain |L - L0| / L0 already taken; 0 = perfectly plastic.
  double hardening = 0.0;
  /// Rest lengths stay within [min_rest_fraction, max_rest_fraction] x their original length [1], so
  /// repeated impacts can never collapse an element to zero. 0 < min <= 1 <= max.
  double min_rest_fraction = 0.25;
  double max_rest_fraction = 2.0;
};

/// Throws InputError naming `field` (e.g. "regions[2].material") and the member for a negative or
/// non-finite compliance, yield or hardening, or a rest clamp outside 0 < min <= 1 <= max.
void checkMaterial(const Material& material, const std::string& field);

}  // namespace deform
