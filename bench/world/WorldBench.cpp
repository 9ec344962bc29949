// Robot-world benchmarks. Targets (issue 4): collision check < 20 µs; occlusion score < 20 µs; IK median
// < 1 ms with >= 99% success on random reachable targets; RRTConnect in the feeding scene median < 20 ms over
// 100 random valid queries. Success rates and medians are reported as counters.
#include "robot/world/Collision.h"
#include "robot/world/InverseKinematics.h"
#include "robot/world/MotionPlanner.h"
#include "robot/world/Occlusion.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <vector>

namespace cbtl::world {
namespace {

std::shared_ptr<const Scene> feeding() {
  static const auto scene = Scene::loadFile(CBTL_DOMAINS_DIR "/feeding/feeding.xml").scene;
  return scene;
}

std::vector<ArmConfig> validConfigs(Workspace& ws, int n, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<ArmConfig> out;
  while (static_cast<int>(out.size()) < n) {
    const ArmConfig q = randomConfig(ws.scene(), rng);
    if (checkArm(ws, q).free()) out.push_back(q);
  }
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Set the arm and check it against the world, itself and the (absent) held object.
void BM_CollisionCheck(benchmark::State& state) {
  Workspace ws(feeding());
  Rng rng(1);
  std::vector<ArmConfig> qs;
  for (int i = 0; i < 256; ++i) qs.push_back(randomConfig(ws.scene(), rng));
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(checkArm(ws, qs[i++ % qs.size()]).status);
}
BENCHMARK(BM_CollisionCheck)->Unit(benchmark::kMicrosecond);

// Set the arm (kinematics) and cast the 25 occlusion rays.
void BM_OcclusionScore(benchmark::State& state) {
  Workspace ws(feeding());
  const auto spec = *occlusionSpecFor(ws.scene());
  const auto qs = validConfigs(ws, 256, 2);
  std::size_t i = 0;
  for (auto _ : state) {
    ws.setArm(qs[i++ % qs.size()]);
    benchmark::DoNotOptimize(occlusionScore(ws, spec));
  }
}
BENCHMARK(BM_OcclusionScore)->Unit(benchmark::kMicrosecond);

// IK to tool poses from FK of random collision-free configurations, seeded from the retract configuration.
void BM_InverseKinematics(benchmark::State& state) {
  Workspace ws(feeding());
  const auto qs = validConfigs(ws, 400, 3);
  std::vector<Pose3> targets;
  for (const auto& q : qs) targets.push_back(ws.forwardKinematics(q));
  Rng rng(4);
  std::vector<double> times;
  long solved = 0, total = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const IkResult r = solveIk(ws, targets[i++ % targets.size()], configs::kRetract, rng);
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    solved += r.solved() ? 1 : 0;
    ++total;
  }
  state.counters["success_pct"] = 100.0 * static_cast<double>(solved) / static_cast<double>(total);
  state.counters["median_ms"] = median(times);
}
BENCHMARK(BM_InverseKinematics)->Unit(benchmark::kMillisecond)->Iterations(400);

// RRTConnect (with shortcutting) between random collision-free configurations in the feeding scene,
// every edge and shortcut certified free along its length (SegmentCertificate.h).
void BM_RRTConnectFeeding(benchmark::State& state) {
  Workspace ws(feeding());
  const auto qs = validConfigs(ws, 200, 5);
  Rng rng(6);
  PlanOptions o;
  o.shortcutAttempts = static_cast<int>(state.range(0));
  o.tryDirectFirst = state.range(1) != 0;
  std::vector<double> times;
  long solved = 0, total = 0, rrt = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const ArmConfig& a = qs[(2 * i) % qs.size()];
    const ArmConfig& b = qs[(2 * i + 1) % qs.size()];
    ++i;
    const auto t0 = std::chrono::steady_clock::now();
    const ArmPlan plan = planArm(ws, a, b, rng, o);
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    solved += plan.solved() ? 1 : 0;
    rrt += plan.iterations > 0 ? 1 : 0;
    ++total;
  }
  state.counters["success_pct"] = 100.0 * static_cast<double>(solved) / static_cast<double>(total);
  state.counters["median_ms"] = median(times);
  state.counters["rrt_pct"] = 100.0 * static_cast<double>(rrt) / static_cast<double>(total);
}
// Arguments: shortcut attempts, try the straight segment first (1) or always run RRTConnect (0).
BENCHMARK(BM_RRTConnectFeeding)
    ->Args({60, 1})
    ->Args({0, 1})
    ->Args({60, 0})
    ->ArgNames({"shortcuts", "direct"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(100);

}  // namespace
}  // namespace cbtl::world

BENCHMARK_MAIN();
