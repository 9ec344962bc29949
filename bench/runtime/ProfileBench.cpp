// Profile loading (docs/runtime.md): BM_LoadProfile/<points> parses and loads a Cooking profile whose one model
// key holds <points> labelled examples in its temperature interval factor (and one in the quantity factor), the
// shape of a user who has been served for a long time. The JSON text is built once, outside the timing.
#include "app/LoadedProgram.h"
#include "bench/runtime/BenchPrograms.h"
#include "runtime/model/UserModel.h"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using namespace cbtl;

const app::LoadedProgram& cookingProgram() { return bench::domainProgram("cooking"); }

// Points spread over the factor's range 25 .. 35 by a fixed linear congruential sequence; liked inside 28 .. 32.
std::string profileText(std::int64_t points) {
  nlohmann::json data = nlohmann::json::array();
  std::uint64_t s = 12345;
  for (std::int64_t i = 0; i < points; ++i) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    const double x = 25.0 + 10.0 * static_cast<double>(s >> 11) / static_cast<double>(1ull << 53);
    data.push_back({x, x >= 28 && x <= 32});
  }
  nlohmann::json key = {{"temp", {{"kind", "interval"}, {"lo", 25}, {"hi", 35}, {"data", data}}},
                        {"qty", {{"kind", "interval"}, {"lo", 0.9}, {"hi", 1.1}, {"data", {{1.0, true}}}}}};
  nlohmann::json root = {{"format", "cbtl-profile"},
                         {"version", 1},
                         {"domain", "cooking"},
                         {"generators", {{"userEnjoysMeal", {{"seasoning|salt", key}}}}}};
  return root.dump();
}

void BM_LoadProfile(benchmark::State& state) {
  const auto& lp = cookingProgram();
  const std::string text = profileText(state.range(0));
  model::UserModel user(lp.graph());
  for (auto _ : state) {
    user.fromJson(text, "bench.json");
    benchmark::DoNotOptimize(user.dataCount());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

}  // namespace

BENCHMARK(BM_LoadProfile)->Arg(20000)->Arg(200000)->Unit(benchmark::kMillisecond);
