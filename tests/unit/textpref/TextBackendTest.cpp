// Backend selection and configuration: the offline default, the language-model backend with its shared cache,
// and configuration errors.
#include "tests/unit/textpref/TestSupport.h"

#include "runtime/textpref/TextBackend.h"

namespace cbtl::textpref::testing {
namespace {

TEST(TextBackend, DefaultIsTheOfflineDescriptorModel) {
  auto config = textBackendConfigFromJson(nlohmann::json::object());
  ASSERT_TRUE(config.ok());
  TextBackend backend(config.value());
  auto model = backend.makeModel(examplePrompts());
  ASSERT_NE(model, nullptr);
  EXPECT_EQ(model->backendId(), "offline-descriptor-bayes-v1");
  EXPECT_EQ(backend.makeJudge(examplePrompts()), nullptr);
  EXPECT_EQ(backend.cache(), nullptr);
}

TEST(TextBackend, LanguageModelBackendSharesOneCacheAcrossModels) {
  Harness h;
  h.server.setDefault(replyRating({{"8", 1.0}}));
  ScratchDir dir;
  auto config = textBackendConfigFromJson({{"backend", "openai-compatible"},
                                           {"base_url", h.server.baseUrl()},
                                           {"model", "test-model"},
                                           {"cache_dir", dir.path.string()},
                                           {"cache_mode", "read-write"},
                                           {"max_attempts", 1},
                                           {"seed", 5}});
  ASSERT_TRUE(config.ok()) << config.error().describe();
  std::unique_ptr<TextPreferenceModel> first, second;
  {
    TextBackend backend(config.value(), {}, h.sleeper());
    first = backend.makeModel(examplePrompts());
    second = backend.makeModel(examplePrompts());
  }
  // The models outlive the backend object; the client and cache stay alive with them.
  auto a = first->assess(testBook(), {});
  auto b = second->assess(testBook(), {});
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_DOUBLE_EQ(a.value().probability, 0.8);
  EXPECT_EQ(b.value().provenance, "openai-compatible:test-model:cache");
  EXPECT_EQ(h.server.requestCount(), 1);
  EXPECT_EQ(h.server.requests()[0].body["seed"], 5);
}

TEST(TextBackend, ConfigurationErrorsNameTheOption) {
  auto unknown = textBackendConfigFromJson({{"backnd", "offline-descriptor"}});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().kind, ErrorKind::Configuration);
  EXPECT_NE(unknown.error().message.find("backnd"), std::string::npos);
  EXPECT_FALSE(textBackendConfigFromJson({{"backend", "gpt"}}).ok());
  EXPECT_FALSE(textBackendConfigFromJson({{"top_logprobs", 21}}).ok());
  EXPECT_FALSE(textBackendConfigFromJson({{"cache_mode", "sometimes"}}).ok());
  EXPECT_FALSE(textBackendConfigFromJson({{"model", 3}}).ok());
  EXPECT_FALSE(textBackendConfigFromJson({{"min_coverage", 2.0}}).ok());
  EXPECT_FALSE(textBackendConfigFromJson(nlohmann::json::array()).ok());
  auto options = textBackendConfigFromJson({{"scale", "options"}, {"renormalize", false}, {"split", "never"}});
  ASSERT_TRUE(options.ok());
  EXPECT_EQ(options.value().scale, RatingScale::NumberedOptions);
  EXPECT_FALSE(options.value().renormalize);
  EXPECT_EQ(options.value().split, SplitPolicy::Never);
}

}  // namespace
}  // namespace cbtl::textpref::testing
