// How long the offline descriptor model and the response cache take per call. The reference code paid a disk
// round trip per rating query (about 80 per Books step); these numbers are the C++ costs of the same queries.
#include "runtime/textpref/OfflineDescriptorModel.h"
#include "runtime/textpref/ResponseCache.h"
#include "runtime/textpref/SimulatedUsers.h"

#include <benchmark/benchmark.h>

namespace {

using namespace cbtl::textpref;

std::vector<FeedbackRecord> booksFeedback() {
  std::vector<FeedbackRecord> feedback;
  const auto user = booksUser();
  for (const auto& b : standardBooks()) feedback.push_back(user.react(b).value());
  return feedback;
}

void BM_OfflineAssessNineBooks(benchmark::State& state) {
  OfflineDescriptorModel model;
  const auto feedback = booksFeedback();
  (void)model.learn(feedback);
  const auto books = standardBooks();
  for (auto _ : state)
    for (const auto& b : books) benchmark::DoNotOptimize(model.assess(b, {}));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(books.size()));
}
BENCHMARK(BM_OfflineAssessNineBooks);

void BM_OfflineLearnNineBooks(benchmark::State& state) {
  const auto feedback = booksFeedback();
  for (auto _ : state) {
    OfflineDescriptorModel model;
    benchmark::DoNotOptimize(model.learn(feedback));
  }
}
BENCHMARK(BM_OfflineLearnNineBooks);

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
