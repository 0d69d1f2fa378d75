#pragma once
// A known field from the physics (`sandbox tradeoff --skin-only`): the dent the finest model leaves in the
// 56 km/h wall crash, smoothed into a displacement defined at every point of the vehicle frame, so that a
// coarse skin can be measured against the dent a real crash makes, not only against formulas.
#include "tradeoff/known_fields.hpp"

#include <cstddef>

namespace sandbox {

/// `wall_crash` run to its end with `control_points` control points; its control points' residual
/// displacements d_i (vehicle frame) at their rest places c_i, smoothed by a Gaussian kernel average
/// (Nadaraya 1964, Watson 1964): u(p) = sum_i g_i d_i / sum_i g_i, g_i = exp(-|p - c_i|^2 / (2 sigma^2)),
/// sigma the mean distance from a control point to its nearest neighbour. Smooth everywhere, far from the
/// points it tends to the nearest one's displacement, and it is neither skin's interpolant.
KnownField wallCrashField(std::size_t control_points);

}  // namespace sandbox
