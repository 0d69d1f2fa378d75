// Checks of the material and solver parameters where they enter (DESIGN.md section 9).
#include <deform/error.hpp>
#include <deform/material.hpp>
#include <deform/solver_params.hpp>

#include "input_checks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace deform {

void checkMaterial(const Material& material, const std::string& field) {
  detail::requireNonNegative(material.crush_strength_Pa, field + ".crush_strength_Pa");
  detail::requirePositive(material.crush_yield_strain, field + ".crush_yield_strain");
  detail::requirePositive(material.shell_stiffness_N_per_m, field + ".shell_stiffness_N_per_m");
  detail::requireNonNegative(material.shell_tension_yield_N_per_m, field + ".shell_tension_yield_N_per_m");
  detail::requireNonNegative(material.shell_compression_yield_N_per_m,
                             field + ".shell_compression_yield_N_per_m");
  detail::requireNonNegative(material.shell_bending_stiffness_N_m, field + ".shell_bending_stiffness_N_m");
  detail::requireNonNegative(material.shell_yield_moment_N, field + ".shell_yield_moment_N");
  detail::requireNonNegative(material.hardening, field + ".hardening");
  if (!(material.min_rest_fraction > 0 && material.min_rest_fraction <= 1))
    throw InputError(field + ".min_rest_fraction: must be in (0, 1] (got " +
                     std::to_string(material.min_rest_fraction) + ")");
  if (!(material.max_rest_fraction >= 1 && std::isfinite(material.max_rest_fraction)))
    throw InputError(field + ".max_rest_fraction: must be finite and >= 1 (got " +
                     std::to_string(material.max_rest_fraction) + ")");
}

uint32_t substepsNoLongerThan(double dt_s, uint32_t substeps, double longest_s) {
  const double needed = std::ceil(dt_s / longest_s * (1.0 - 1e-9));
  return needed > substeps ? static_cast<uint32_t>(std::min(needed, 4096.0)) : substeps;
}

void checkSolverParams(const SolverParams& params) {
  if (params.substeps < 1) throw InputError("substeps: must be at least 1 (got 0)");
  if (params.iterations < 1) throw InputError("iterations: must be at least 1 (got 0)");
  if (params.threads < 1) throw InputError("threads: must be at least 1 (got 0)");
  detail::requireNonNegative(params.damping_per_s, "damping_per_s");
  detail::requireNonNegative(params.inertial_scale, "inertial_scale");
  detail::requireNonNegative(params.contact_margin_m, "contact_margin_m");
  if (!(params.longest_contact_substep_s > 0))
    throw InputError("longest_contact_substep_s: must be > 0 (infinite: substeps alone) (got " +
                     std::to_string(params.longest_contact_substep_s) + ")");
  if (!(params.max_depenetration_mps > 0))
    throw InputError("max_depenetration_mps: must be > 0 (infinite: no cap) (got " +
                     std::to_string(params.max_depenetration_mps) + ")");
  detail::requireNonNegative(params.sleep_speed_mps, "sleep_speed_mps");
  detail::requireNonNegative(params.wake_load_mps2, "wake_load_mps2");
  if (std::isnan(params.sleep_delay_s)) throw InputError("sleep_delay_s: must not be NaN");
}

}  // namespace deform
