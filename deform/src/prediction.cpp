// The substep's prediction, one point at a time or four side by side (prediction.hpp).
#include "prediction.hpp"

#include <deform/solver_params.hpp>

#include <Eigen/Geometry>
#include <cmath>

#include "simd_rows.hpp"

namespace deform {
namespace {

void predictOne(const Prediction& p, std::size_t i, PredictionSums& sum) {
  const Eigen::Vector3d& core_velocity_mps = p.core_velocity_mps;
  const double h = p.h_s, decay = p.decay, m = p.mass_kg[i];
  p.previous[i] = p.x[i];
  // Drag first, then the load: at rest (v = 0) the full load acts, so damping leaves the static
  // equilibrium where the compliance alone puts it.
  const Eigen::Vector3d relative = p.v[i] - core_velocity_mps;
  Eigen::Vector3d vi = core_velocity_mps + relative * decay;
  sum.damping_loss_J += 0.5 * m * relative.squaredNorm() * (1.0 - decay * decay);
  sum.to_core_Ns += m * (p.v[i] - vi);
  Eigen::Vector3d inertial_mps2{0, 0, 0};
  if (p.inertial) {
    const Eigen::Vector3d r = p.x[i] - p.core_m;
    inertial_mps2 =
        p.inertial_scale * (p.load_mps2 - p.alpha_radps2.cross(r) -
                            p.omega_radps.cross(p.omega_radps.cross(r)) - 2.0 * p.omega_radps.cross(vi));
    vi += h * inertial_mps2;
  }
  Eigen::Vector3d travel = h * vi;
  // Numeric guard: a point can end a substep at most 2 d_max from where it began (visual constraint), so a
  // larger predicted travel (an enormous impulse) is shortened to that before the solve.
  const double cap = 2.0 * p.max_deviation_m[i];
  const double travel2 = travel.squaredNorm();
  if (travel2 > cap * cap) travel *= cap / std::sqrt(travel2);
  if (p.inertial) sum.inertial_work_J += m * inertial_mps2.dot(travel - h * core_velocity_mps);
  p.x[i] += travel;
}

#if defined(DEFORM_SIMD_AVX2)
/// Adds the four lanes of `v` to `sum` in lane order (the one-at-a-time sum's order).
__attribute__((target("avx2"))) inline void addLanes(double& sum, __m256d v) {
  alignas(32) double lane[4];
  _mm256_store_pd(lane, v);
  sum += lane[0];
  sum += lane[1];
  sum += lane[2];
  sum += lane[3];
}

/// scale (load - spin - swirl - two coriolis), as Eigen evaluates it component by component.
__attribute__((target("avx2"))) inline __m256d inertialComponent(__m256d scale, __m256d load, __m256d spin,
                                                                 __m256d swirl, __m256d two,
                                                                 __m256d coriolis) {
  return _mm256_mul_pd(
      scale, _mm256_sub_pd(_mm256_sub_pd(_mm256_sub_pd(load, spin), swirl), _mm256_mul_pd(two, coriolis)));
}

/// Points i .. i + 3, each lane predictOne's operations in its order.
template <bool kInertial>
__attribute__((target("avx2"))) void predictFour(const Prediction& p, std::size_t i, PredictionSums& sum,
                                                 __m256d& to_core_sum) {
  const __m256d h = _mm256_set1_pd(p.h_s), decay = _mm256_set1_pd(p.decay);
  const __m256d m = _mm256_loadu_pd(p.mass_kg + i);
  const Points4 x = loadRun4(p.x + i), v = loadRun4(p.v + i);
  storeRun4(x, p.previous + i);
  const Points4 cv = broadcast4(p.core_velocity_mps);
  const Points4 relative{_mm256_sub_pd(v.x, cv.x), _mm256_sub_pd(v.y, cv.y), _mm256_sub_pd(v.z, cv.z)};
  Points4 vi{_mm256_add_pd(cv.x, _mm256_mul_pd(relative.x, decay)),
             _mm256_add_pd(cv.y, _mm256_mul_pd(relative.y, decay)),
             _mm256_add_pd(cv.z, _mm256_mul_pd(relative.z, decay))};
  const __m256d kept = _mm256_set1_pd(1.0 - p.decay * p.decay);
  const __m256d damping =
      _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), m), dot4(relative, relative)), kept);
  const Points4 to_core{_mm256_mul_pd(m, _mm256_sub_pd(v.x, vi.x)),
                        _mm256_mul_pd(m, _mm256_sub_pd(v.y, vi.y)),
                        _mm256_mul_pd(m, _mm256_sub_pd(v.z, vi.z))};
  Points4 inertial{};
  if constexpr (kInertial) {
    const Points4 core = broadcast4(p.core_m);
    const Points4 r{_mm256_sub_pd(x.x, core.x), _mm256_sub_pd(x.y, core.y), _mm256_sub_pd(x.z, core.z)};
    const Points4 omega = broadcast4(p.omega_radps), load = broadcast4(p.load_mps2);
    const Points4 spin = cross4(broadcast4(p.alpha_radps2), r);
    const Points4 swirl = cross4(omega, cross4(omega, r));
    const Points4 coriolis = cross4(omega, vi);
    const __m256d two = _mm256_set1_pd(2.0), scale = _mm256_set1_pd(p.inertial_scale);
    inertial = {inertialComponent(scale, load.x, spin.x, swirl.x, two, coriolis.x),
                inertialComponent(scale, load.y, spin.y, swirl.y, two, coriolis.y),
                inertialComponent(scale, load.z, spin.z, swirl.z, two, coriolis.z)};
    vi = {_mm256_add_pd(vi.x, _mm256_mul_pd(h, inertial.x)),
          _mm256_add_pd(vi.y, _mm256_mul_pd(h, inertial.y)),
          _mm256_add_pd(vi.z, _mm256_mul_pd(h, inertial.z))};
  }
  Points4 travel{_mm256_mul_pd(h, vi.x), _mm256_mul_pd(h, vi.y), _mm256_mul_pd(h, vi.z)};
  const __m256d cap = _mm256_mul_pd(_mm256_set1_pd(2.0), _mm256_loadu_pd(p.max_deviation_m + i));
  const __m256d travel2 = dot4(travel, travel);
  const __m256d capped = _mm256_cmp_pd(travel2, _mm256_mul_pd(cap, cap), _CMP_GT_OQ);
  if (_mm256_movemask_pd(capped) != 0) {
    const __m256d shorten = _mm256_div_pd(cap, _mm256_sqrt_pd(travel2));
    travel = {_mm256_blendv_pd(travel.x, _mm256_mul_pd(travel.x, shorten), capped),
              _mm256_blendv_pd(travel.y, _mm256_mul_pd(travel.y, shorten), capped),
              _mm256_blendv_pd(travel.z, _mm256_mul_pd(travel.z, shorten), capped)};
  }
  addLanes(sum.damping_loss_J, damping);
  // The reaction's components, each summed in point order.
  to_core_sum = addLaneRows(to_core_sum, to_core);
  if constexpr (kInertial) {
    const Points4 core_travel = broadcast4(p.h_s * p.core_velocity_mps);
    const Points4 relative_travel{_mm256_sub_pd(travel.x, core_travel.x),
                                  _mm256_sub_pd(travel.y, core_travel.y),
                                  _mm256_sub_pd(travel.z, core_travel.z)};
    addLanes(sum.inertial_work_J, _mm256_mul_pd(m, dot4(inertial, relative_travel)));
  }
  storeRun4(plus(x, travel), p.x + i);
}

template <bool kInertial>
__attribute__((target("avx2"))) void predictAvx2(const Prediction& shared, std::size_t begin, std::size_t end,
                                                 PredictionSums& sum) {
  // A local copy: the stores through its pointers then cannot alias its fields, which stay in registers.
  const Prediction p = shared;
  // The sums as locals (registers) through the loop: the stores through p's pointers could alias `sum`.
  PredictionSums local = sum;
  __m256d to_core_sum = rowOf(local.to_core_Ns);
  std::size_t i = begin;
  for (; i + 4 <= end; i += 4) predictFour<kInertial>(p, i, local, to_core_sum);
  local.to_core_Ns = vectorOf(to_core_sum);
  for (; i < end; ++i) predictOne(p, i, local);
  sum = local;
}
#endif

}  // namespace

void predictPoints(const Prediction& p, std::size_t begin, std::size_t end, bool wide, PredictionSums& sums) {
#if defined(DEFORM_SIMD_AVX2)
  if (wide && wideSweepAvailable()) {
    if (p.inertial)
      predictAvx2<true>(p, begin, end, sums);
    else
      predictAvx2<false>(p, begin, end, sums);
    return;
  }
#else
  (void)wide;
#endif
  for (std::size_t i = begin; i < end; ++i) predictOne(p, i, sums);
}

}  // namespace deform
