// Google Benchmark for the per-frame deform pass (the figures in docs/BENCHMARKS.md come from
// `sandbox bench embed`, which also measures the bandwidth bound in the same run).
#include <benchmark/benchmark.h>
#include <deform/builtin_meshes.hpp>
#include <deform/control_mesh.hpp>
#include <deform/skin.hpp>

#include <cmath>

namespace {

void BM_SkinDeform(benchmark::State& state) {
  const auto vertices = static_cast<std::size_t>(state.range(0));
  const auto control_points = static_cast<std::size_t>(state.range(1));
  const auto k = static_cast<std::size_t>(state.range(2));
  const auto threads = static_cast<unsigned>(state.range(3));
  const deform::VehicleModel car = deform::makeSedan(vertices);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : car.body.positions_m) points.push_back(p.cast<double>());
  const auto control = deform::buildControlMesh(points, control_points);
  const auto skin = deform::Skin::build(car.body.positions_m, control.points_m, {3.5, k, threads});
  std::vector<Eigen::Vector3d> displacement(control.points_m.size());
  for (std::size_t i = 0; i < displacement.size(); ++i)
    displacement[i] = Eigen::Vector3d(0.01 * std::sin(double(i)), 0.02, -0.01);
  std::vector<Eigen::Vector3f> out(car.body.positions_m.size());
  for (auto _ : state) {
    skin.deform(car.body.positions_m.data(), displacement.data(), out.data(), threads);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(out.size()));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(out.size() * skin.bytesPerVertex()));
}

BENCHMARK(BM_SkinDeform)
    ->Args({900000, 60, 8, 1})
    ->Args({900000, 60, 8, 2})
    ->Args({900000, 60, 4, 2})
    ->Args({900000, 60, 16, 2})
    ->Args({100000, 1000, 8, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
