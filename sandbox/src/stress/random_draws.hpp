#pragma once
// The random numbers of the crash campaign (random_scenes.hpp). std::mt19937_64's sequence is fixed by the
// C++ standard; std::uniform_real_distribution's mapping is not (it differs between standard libraries),
// so the mapping to numbers is ours. Every drawn value is rounded to the precision it is written with, so
// that the scene file holds exactly what the generator placed.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <random>

namespace sandbox {

class RandomDraws {
 public:
  /// The stream of scene `index` of seed `seed`: splitmix64 of both, so neighbouring seeds and indices
  /// start far apart in the generator's state.
  RandomDraws(uint64_t seed, uint64_t index) : engine_(splitmix64(splitmix64(seed) ^ index)) {}

  /// In [0, 1): the top 53 bits of the next number.
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// In [lo, hi), rounded to `step`.
  double uniform(double lo, double hi, double step) { return rounded(lo + (hi - lo) * unit(), step); }
  /// Uniform in log(value) over [lo, hi]: sizes and masses across decades, rounded to `step`.
  double logUniform(double lo, double hi, double step) {
    return rounded(std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * unit()), step);
  }
  bool chance(double probability) { return unit() < probability; }
  /// One of 0 .. n-1.
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(engine_() % n); }
  /// An index into `weights`, each drawn in proportion to its weight.
  std::size_t weighted(std::initializer_list<double> weights) {
    double total = 0;
    for (double w : weights) total += w;
    double left = unit() * total;
    std::size_t i = 0;
    for (double w : weights) {
      if (left < w) return i;
      left -= w;
      ++i;
    }
    return weights.size() - 1;
  }
  /// `value` to the nearest multiple of `step` (a power of ten); below 1 divided rather than multiplied, so
  /// that 0.3 is written 0.3 (the double nearest it), not 0.30000000000000004.
  static double rounded(double value, double step) {
    if (step >= 1) return std::round(value / step) * step;
    const double per_unit = std::round(1 / step);
    return std::round(value * per_unit) / per_unit;
  }

 private:
  static uint64_t splitmix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  }
  std::mt19937_64 engine_;
};

}  // namespace sandbox
