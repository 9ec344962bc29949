// How long the offline descriptor model and the response cache take per call. The reference code paid a disk
// round trip per rating query (about 80 per Books step); these numbers are the C++ costs of the same queries.
#include "runtime/textpref/OfflineDescriptorModel.h"
#include "runtime/textpref/ResponseCache.h"

#include <benchmark/benchmark.h>

namespace {

using namespace cbtl::textpref;

// Nine synthetic items, each with a title and three descriptor fields of one to three values: about the size of a
// .cbtl catalogue entry.
std::vector<Item> nineItems() {
  std::vector<Item> items;
  for (int i = 0; i < 9; ++i) {
    const std::string k = std::to_string(i);
    items.push_back(Item{
        "item" + k,
        {{"title", {"Item " + k}},
         {"maker", {"maker" + std::to_string(i % 4)}},
         {"kind", {"kind" + std::to_string(i % 2), "kind" + std::to_string(2 + i % 3)}},
         {"tag",
          {"tag" + std::to_string(i % 5), "tag" + std::to_string(5 + i % 3), "tag" + std::to_string(8 + i % 2)}}}});
  }
  return items;
}

// One labelled reaction per item, two of nine liked.
std::vector<FeedbackRecord> nineFeedback() {
  std::vector<FeedbackRecord> feedback;
  for (const auto& item : nineItems())
    feedback.push_back(FeedbackRecord{item, {}, "", item.name == "item0" || item.name == "item1"});
  return feedback;
}

void BM_OfflineAssessNineItems(benchmark::State& state) {
  OfflineDescriptorModel model;
  const auto feedback = nineFeedback();
  (void)model.learn(feedback);
  const auto items = nineItems();
  for (auto _ : state)
    for (const auto& item : items) benchmark::DoNotOptimize(model.assess(item, {}));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(items.size()));
}
BENCHMARK(BM_OfflineAssessNineItems);

void BM_OfflineLearnNineItems(benchmark::State& state) {
  const auto feedback = nineFeedback();
  for (auto _ : state) {
    OfflineDescriptorModel model;
    benchmark::DoNotOptimize(model.learn(feedback));
  }
}
BENCHMARK(BM_OfflineLearnNineItems);

nlohmann::json sampleRequest() {
  return nlohmann::json{{"model", "gpt-4o-mini"},
                        {"messages", {{{"role", "user"}, {"content", std::string(900, 'x')}}}},
                        {"temperature", 0.0},
                        {"max_tokens", 1},
                        {"logprobs", true},
                        {"top_logprobs", 20},
                        {"seed", 0}};
}

void BM_CacheKey(benchmark::State& state) {
  const auto request = sampleRequest();
  for (auto _ : state) benchmark::DoNotOptimize(ResponseCache::keyOf(request));
}
BENCHMARK(BM_CacheKey);

void BM_CacheMemoryHit(benchmark::State& state) {
  ResponseCache cache({}, CacheMode::ReadWrite);
  const auto request = sampleRequest();
  cache.store(request, nlohmann::json{{"choices", nlohmann::json::array()}});
  for (auto _ : state) benchmark::DoNotOptimize(cache.lookup(request));
}
BENCHMARK(BM_CacheMemoryHit);

}  // namespace
