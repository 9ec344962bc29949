// The response cache: keys, hits and misses through the real client, corrupt entries, read-only and record modes.
#include "tests/unit/textpref/TestSupport.h"

#include "runtime/textpref/ResponseCache.h"
#include "runtime/textpref/Sha256.h"

#include <fstream>

namespace cbtl::textpref::testing {
namespace {

TEST(Sha256, MatchesTheStandardTestVector) {
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(ResponseCache, KeyIsCanonicalOverObjectKeyOrder) {
  const auto a = nlohmann::json::parse(R"({"model":"m","temperature":0,"messages":[{"role":"user","content":"x"}]})");
  const auto b = nlohmann::json::parse(R"({"messages":[{"content":"x","role":"user"}],"temperature":0,"model":"m"})");
  EXPECT_EQ(ResponseCache::keyOf(a), ResponseCache::keyOf(b));
  EXPECT_EQ(ResponseCache::keyOf(a).size(), 64u);
}

TEST(ResponseCache, MissThenHitFromMemoryAndFromDisk) {
  ScratchDir dir;
  Harness h;
  h.server.setDefault(replyRating({{"9", 1.0}}));
  {
    ResponseCache cache(dir.path, CacheMode::ReadWrite);
    LlmPreferenceModel model(h.client(&cache), bookOptions());
    auto first = model.assess(testBook(), {});
    auto second = model.assess(testBook(), {});
    ASSERT_TRUE(first.ok() && second.ok());
    EXPECT_EQ(h.server.requestCount(), 1);
    EXPECT_EQ(first.value().provenance, "openai-compatible:test-model");
    EXPECT_EQ(second.value().provenance, "openai-compatible:test-model:cache");
    EXPECT_DOUBLE_EQ(second.value().probability, 0.9);
    EXPECT_EQ(cache.stats().misses, 1);
    EXPECT_EQ(cache.stats().memoryHits, 1);
    EXPECT_EQ(cache.stats().stores, 1);
  }
  // A new cache object over the same folder answers from disk.
  ResponseCache cache(dir.path, CacheMode::ReadWrite);
  LlmPreferenceModel model(h.client(&cache), bookOptions());
  auto third = model.assess(testBook(), {});
  ASSERT_TRUE(third.ok());
  EXPECT_EQ(cache.stats().diskHits, 1);
  EXPECT_EQ(h.server.requestCount(), 1);
}

TEST(ResponseCache, EntryFileHoldsRequestAndResponseButNoKey) {
  ScratchDir dir;
  Harness h;
  ::setenv(kKeyVariable, "sk-cache-secret", 1);
  h.server.setDefault(replyRating({{"9", 1.0}}));
  ResponseCache cache(dir.path, CacheMode::ReadWrite);
  auto client = h.client(&cache);
  ChatRequest request;
  request.messages = {{"user", "rate this"}};
  ASSERT_TRUE(client->complete(request).ok());
  ::unsetenv(kKeyVariable);
  const auto body = client->requestBody(request).value();
  const std::string key = ResponseCache::keyOf(body);
  const auto path = cache.pathOf(key);
  EXPECT_EQ(path, dir.path / key.substr(0, 2) / (key + ".json"));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const auto entry = nlohmann::json::parse(text.str());
  EXPECT_EQ(entry["format"], "cbtl-textpref-cache-1");
  EXPECT_EQ(entry["key"], key);
  EXPECT_EQ(entry["request"], body);
  EXPECT_EQ(entry["response"]["system_fingerprint"], "fp_test");
  EXPECT_EQ(text.str().find("sk-cache-secret"), std::string::npos);
  // No temporary files are left behind.
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path)) files += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(files, 1);
}

TEST(ResponseCache, ErrorsAreNeverCached) {
  ScratchDir dir;
  Harness h;
  h.server.push(reply(400, errorBody("bad", "invalid_request_error", "bad")));
  h.server.push(replyRating({{"2", 1.0}}));
  ResponseCache cache(dir.path, CacheMode::ReadWrite);
  LlmPreferenceModel model(h.client(&cache), bookOptions());
  EXPECT_FALSE(model.assess(testBook(), {}).ok());
  auto again = model.assess(testBook(), {});
  ASSERT_TRUE(again.ok());
  EXPECT_DOUBLE_EQ(again.value().probability, 0.2);
  EXPECT_EQ(h.server.requestCount(), 2);
}

TEST(ResponseCache, ReadOnlyMissNeverReachesTheNetwork) {
  ScratchDir dir;
  Harness h;
  h.server.setDefault(replyRating({{"9", 1.0}}));
  ResponseCache cache(dir.path, CacheMode::ReadOnly);
  LlmPreferenceModel model(h.client(&cache), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().kind, ErrorKind::CacheMiss);
  EXPECT_EQ(h.server.requestCount(), 0);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path));
}

TEST(ResponseCache, ReadOnlyReplaysRecordedEntriesWithoutAServer) {
  ScratchDir dir;
  std::string deadUrl;
  {
    Harness h;
    h.server.setDefault(replyRating({{"7", 0.5}, {"9", 0.5}}));
    ResponseCache cache(dir.path, CacheMode::ReadWrite);
    LlmPreferenceModel model(h.client(&cache), bookOptions());
    ASSERT_TRUE(model.assess(testBook(), {}).ok());
    deadUrl = h.server.baseUrl();
  }
  Harness other;
  ChatConfig c = other.config();
  c.baseUrl = deadUrl;  // the recording server is gone; the key does not depend on the URL
  ResponseCache cache(dir.path, CacheMode::ReadOnly);
  LlmPreferenceModel model(other.client(c, &cache), bookOptions());
  auto a = model.assess(testBook(), {});
  ASSERT_TRUE(a.ok()) << a.error().describe();
  EXPECT_NEAR(a.value().probability, 0.8, 1e-9);
  EXPECT_EQ(other.server.requestCount(), 0);
}

TEST(ResponseCache, CorruptEntryIsAMissWithAWarningAndIsRewritten) {
  ScratchDir dir;
  Harness h;
  h.server.setDefault(replyRating({{"9", 1.0}}));
  std::filesystem::path entryPath;
  {
    ResponseCache cache(dir.path, CacheMode::ReadWrite);
    auto client = h.client(&cache);
    ChatRequest request;
    request.messages = {{"user", "rate this"}};
    ASSERT_TRUE(client->complete(request).ok());
    entryPath = cache.pathOf(ResponseCache::keyOf(client->requestBody(request).value()));
  }
  {
    std::ofstream out(entryPath, std::ios::trunc);
    out << "{\"format\": \"cbtl-textpref-cache-1\", \"key\": ";  // truncated write
  }
  std::vector<std::string> warnings;
  ResponseCache cache(dir.path, CacheMode::ReadWrite, [&](const std::string& w) { warnings.push_back(w); });
  auto client = h.client(&cache);
  ChatRequest request;
  request.messages = {{"user", "rate this"}};
  auto r = client->complete(request);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r.value().fromCache);
  EXPECT_EQ(h.server.requestCount(), 2);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("not valid JSON"), std::string::npos);
  EXPECT_EQ(cache.stats().corrupt, 1);
  // The entry was rewritten and is valid again.
  ResponseCache fresh(dir.path, CacheMode::ReadOnly);
  EXPECT_TRUE(fresh.lookup(client->requestBody(request).value()).has_value());
}

TEST(ResponseCache, EntryWhoseRequestDoesNotHashToItsKeyIsCorrupt) {
  ScratchDir dir;
  const nlohmann::json request{{"model", "m"}, {"messages", nlohmann::json::array()}};
  ResponseCache writer(dir.path, CacheMode::ReadWrite);
  writer.store(request, nlohmann::json{{"choices", nlohmann::json::array()}});
  const auto path = writer.pathOf(ResponseCache::keyOf(request));
  auto entry = nlohmann::json::parse(std::ifstream(path));
  entry["request"]["model"] = "other";
  std::ofstream(path, std::ios::trunc) << entry.dump();
  std::vector<std::string> warnings;
  ResponseCache reader(dir.path, CacheMode::ReadOnly, [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_FALSE(reader.lookup(request).has_value());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("does not match its key"), std::string::npos);
}

TEST(ResponseCache, RecordModeAlwaysAsksTheServerAndOffModeStoresNothing) {
  ScratchDir dir;
  Harness h;
  h.server.setDefault(replyRating({{"9", 1.0}}));
  {
    ResponseCache cache(dir.path, CacheMode::Record);
    LlmPreferenceModel model(h.client(&cache), bookOptions());
    ASSERT_TRUE(model.assess(testBook(), {}).ok());
    ASSERT_TRUE(model.assess(testBook(), {}).ok());
    EXPECT_EQ(h.server.requestCount(), 2);
    EXPECT_FALSE(std::filesystem::is_empty(dir.path));
  }
  ScratchDir empty;
  ResponseCache off(empty.path, CacheMode::Off);
  LlmPreferenceModel model(h.client(&off), bookOptions());
  ASSERT_TRUE(model.assess(testBook(), {}).ok());
  EXPECT_TRUE(std::filesystem::is_empty(empty.path));
}

TEST(ResponseCache, ModeNamesRoundTrip) {
  for (CacheMode m : {CacheMode::Off, CacheMode::ReadWrite, CacheMode::ReadOnly, CacheMode::Record})
    EXPECT_EQ(parseCacheMode(cacheModeName(m)), m);
  EXPECT_FALSE(parseCacheMode("sometimes").has_value());
}

}  // namespace
}  // namespace cbtl::textpref::testing
