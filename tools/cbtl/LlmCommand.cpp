// `cbtl llm`: the text-preference backends from the command line.
//
// `cbtl llm probe --base-url URL --model M`: does an OpenAI-compatible server return log-probabilities that
// rating constraints can use? Two one-token questions (answers 4 and 10) with top_logprobs = 20; reports whether
// top_logprobs came back, their mass on the numerals 0..10, whether "10" is one token or split into "1" + "0",
// and, when split, whether the server continues a pre-filled "1" (the rating reader's follow-up needs that).
// The verdict names the first failure (ProbeVerdict.h): transport error, HTTP status, quota, malformed reply, no
// logprobs or low coverage. After a transport failure the remaining questions are not asked.
// `cbtl llm books FILE`: the Books user (domains/books/BooksUser.h) learned round by round by the offline
// descriptor model (default, no server) or by a language-model server. FILE is the Books program
// (domains/books/books.cbtl): its Book entries are the items, and its text factor over Book supplies the prompts.
// Exit codes: 0 ok/usable, 1 bad input or unusable server, 2 usage (CLI11), 70 internal error. The API key is read
// from the environment variable named by --api-key-env and is never printed.
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/ProbeVerdict.h"

#include "runtime/textpref/ChatClient.h"
#include "runtime/textpref/RatingReader.h"
#include "runtime/textpref/Redaction.h"
#include "runtime/textpref/TextBackend.h"

#include "app/LoadedProgram.h"
#include "app/SimulatorFacts.h"
#include "domains/books/BookCatalog.h"
#include "domains/books/BooksUser.h"

#include <fmt/core.h>

#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>

namespace {

struct ProbeOptions {
  std::string baseUrl;
  std::string model;
  std::string apiKeyEnv = "OPENAI_API_KEY";
  std::string maxTokensField = "max_tokens";
  long connectTimeoutMs = 5000;
  long timeoutMs = 30000;
  int attempts = 2;
};

struct Question {
  const char* text;
  int answer;
};

// Does the server continue a pre-filled assistant turn? Then "0" should follow "1" for the answer 10.
void reportSplitFollowUp(cbtl::textpref::ChatClient& client, const char* question) {
  using namespace cbtl::textpref;
  ChatRequest followUp;
  followUp.messages = {{"user", question}, {"assistant", "1"}};
  followUp.maxTokens = 1;
  followUp.seed = 0;
  followUp.topLogprobs = 20;
  auto next = client.complete(followUp);
  double zero = 0.0;
  if (next && next.value().hasLogprobs)
    for (const auto& t : next.value().firstTokenTop)
      if (t.token == "0") zero += std::exp(t.logprob);
  if (!next) {
    fmt::print("split follow-up: failed: {}\n", next.error().describe());
  } else if (zero >= 0.5) {
    fmt::print("split follow-up: the server continues a pre-filled answer (P(\"0\" after \"1\") = {:.3f}).\n", zero);
  } else {
    fmt::print(
        "split follow-up: P(\"0\" after \"1\") = {:.3f}: the server may not continue a pre-filled answer "
        "(vLLM needs continue_final_message); high ratings may be read as 1.\n",
        zero);
  }
}

int runProbe(const ProbeOptions& o) {
  using namespace cbtl::textpref;
  if (o.baseUrl.rfind("http://", 0) != 0 && o.baseUrl.rfind("https://", 0) != 0) {
    fmt::print(stderr, "cbtl llm probe: --base-url must start with http:// or https://, got '{}'\n", o.baseUrl);
    return 1;
  }
  if (o.model.empty()) {
    fmt::print(stderr, "cbtl llm probe: --model must not be empty\n");
    return 1;
  }
  ChatConfig config;
  config.baseUrl = o.baseUrl;
  config.model = o.model;
  config.apiKeyEnv = o.apiKeyEnv;
  config.maxTokensField = o.maxTokensField;
  config.connectTimeoutMs = o.connectTimeoutMs;
  config.requestTimeoutMs = o.timeoutMs;
  config.retry.maxAttempts = o.attempts;
  ChatClient client(config);  // no cache: a probe must see the server itself

  fmt::print("server: {}\nmodel: {}\n", client.server(), o.model);
  const Question questions[] = {
      {"How many legs does a dog have? Reply with a single number from 0 to 10 and nothing else.", 4},
      {"How many fingers do two human hands have in total? Reply with a single number from 0 to 10 and nothing "
       "else.",
       10},
  };
  const std::string key = secretFromEnvironment(o.apiKeyEnv);
  std::optional<Error> failure;  // the first thing that makes the server unusable
  bool sawTen = false;
  bool sawSplitOne = false;
  for (const auto& q : questions) {
    if (failure && (failure->kind == ErrorKind::Transport || failure->kind == ErrorKind::Timeout)) {
      fmt::print("question (answer {}): not asked: the server did not answer the previous one\n", q.answer);
      continue;
    }
    ChatRequest request;
    request.messages = {{"user", q.text}};
    request.maxTokens = 1;
    request.temperature = 0.0;
    request.seed = 0;
    request.topLogprobs = 20;
    auto response = client.complete(request);
    if (!response) {
      fmt::print("question (answer {}): failed: {}\n", q.answer, response.error().describe());
      if (!failure) failure = response.error();
      continue;
    }
    const auto& r = response.value();
    const std::string reply = redactSecrets(r.content, key);
    if (!r.hasLogprobs) {
      fmt::print("question (answer {}): reply '{}' came without top_logprobs\n", q.answer, reply);
      if (!failure) failure = Error{ErrorKind::NoLogprobs, "the reply came without top_logprobs", client.server()};
      continue;
    }
    const LabelMass labels = readLabels(r.firstTokenTop);
    double coverage = 0.0;
    for (int k = 0; k <= 10; ++k) coverage += labels[k];
    int best = 0;
    for (int k = 1; k <= 10; ++k)
      if (labels[k] > labels[best]) best = k;
    fmt::print("question (answer {}): reply '{}', {} top tokens, {:.3f} of the mass on 0..10, most likely {}\n",
               q.answer, reply, r.firstTokenTop.size(), coverage, best);
    if (coverage < 0.5 && !failure)
      failure =
          Error{ErrorKind::UnusableRating,
                fmt::format("only {:.3f} of the probability mass is on the numerals 0..10", coverage), client.server()};
    if (labels[10] > 0.0) sawTen = true;
    if (q.answer == 10 && labels[10] <= 0.0 && labels[1] > 0.0) sawSplitOne = true;
  }
  const bool usable = !failure;
  if (usable) {
    if (sawTen) {
      fmt::print("\"10\" is a single token.\n");
    } else if (sawSplitOne) {
      fmt::print(
          "\"10\" is split into \"1\" + \"0\": rating queries need the split follow-up (policy auto or always).\n");
      reportSplitFollowUp(client, questions[1].text);
    } else {
      fmt::print("could not tell how \"10\" is tokenized; keep the split policy at auto.\n");
    }
    fmt::print("verdict: usable: the server returns log-probabilities for rating constraints.\n");
    return 0;
  }
  fmt::print("{}\n", cbtl::cli::probeVerdict(*failure, o.apiKeyEnv));
  return 1;
}

struct BooksOptions {
  std::string file;
  std::string stdlibDir;
  std::string backend = "offline-descriptor";
  std::string baseUrl = "http://127.0.0.1:8080/v1";
  std::string model = "gpt-4o-mini";
  std::string apiKeyEnv = "OPENAI_API_KEY";
  std::string cacheDir;
  std::string cacheMode = "read-write";
  std::string scale = "digits";
  int rounds = 9;
  int attempts = 3;
};

// The program's `model text(...)` factor whose subject is a Book; null when there is none.
const cbtl::ir::ModelFactor* bookTextFactor(const cbtl::ir::ConstraintGraph& graph) {
  for (const auto& g : graph.generators)
    for (const auto& f : g.factors)
      if (f.kind == cbtl::ir::FactorKind::Text && f.feature && f.feature->type.kind == cbtl::ir::TypeKind::Item &&
          f.feature->type.spelling == "Book")
        return &f;
  return nullptr;
}

// Each round: assess the program's books, hand over the most uncertain one (highest entropy, the CBTL
// exploration objective; ties go to the earlier book), collect the Books user's reaction, learn. The
// language-model backend also judges the ground truth with the hidden preference text, as the reference does.
int runBooks(const BooksOptions& o) {
  using namespace cbtl::textpref;
  namespace books = cbtl::domains::books;
  nlohmann::json json{{"backend", o.backend},       {"base_url", o.baseUrl},     {"model", o.model},
                      {"api_key_env", o.apiKeyEnv}, {"cache_dir", o.cacheDir},   {"cache_mode", o.cacheMode},
                      {"scale", o.scale},           {"max_attempts", o.attempts}};
  auto config = textBackendConfigFromJson(json);
  if (!config) {
    fmt::print(stderr, "cbtl llm books: {}\n", config.error().describe());
    return 1;
  }
  const auto program = cbtl::app::LoadedProgram::load(o.file, o.stdlibDir);
  if (!program->ok()) {
    fmt::print(stderr, "{}cbtl llm books: '{}' cannot be loaded\n", program->errors(), o.file);
    return 1;
  }
  const cbtl::ir::ModelFactor* factor = bookTextFactor(program->graph());
  if (factor == nullptr) {
    fmt::print(stderr, "cbtl llm books: {}: no `model text(...)` factor over a Book\n", o.file);
    return 1;
  }
  const books::BookCatalog catalog = books::BookCatalog::fromProgram(cbtl::app::simulatorFacts(*program));
  TextBackend backend(config.value(), [](const std::string& w) { fmt::print(stderr, "{}\n", w); });
  const PromptTemplates prompts = generatorPrompts(factor->prompt, factor->learning);
  auto model = backend.makeModel(prompts);
  books::BooksUser user = books::BooksUser::paperDefault();
  user.taste().useLanguageModelJudge(backend.makeJudge(prompts));
  const std::vector<books::Book>& shelf = catalog.books();
  fmt::print("backend: {}\n", model->backendId());
  for (int round = 1; round <= o.rounds; ++round) {
    std::size_t pick = 0;
    double bestEntropy = -1.0;
    fmt::print("round {}\n", round);
    for (std::size_t i = 0; i < shelf.size(); ++i) {
      const Assessment a = assessOrFallback(model->assess(shelf[i].item, {}), FallbackPolicy{0.5});
      fmt::print("  {:<40} P={:.3f} H={:.3f} {}\n", shelf[i].title, a.probability, a.entropyBits, a.provenance);
      if (a.entropyBits > bestEntropy + 1e-12) {
        bestEntropy = a.entropyBits;
        pick = i;
      }
    }
    auto reaction = user.react(shelf[pick]);
    if (!reaction) {
      fmt::print(stderr, "cbtl llm books: the simulated user could not be judged: {}\n", reaction.error().describe());
      return 1;
    }
    fmt::print("  handed over {}: \"{}\"\n", shelf[pick].title, reaction.value().text);
    const FeedbackRecord record = reaction.value();
    if (Status s = model->learn(std::span(&record, 1)); !s.ok())
      fmt::print(stderr, "cbtl llm books: learning failed, theta unchanged: {}\n", s.error().describe());
  }
  fmt::print("theta: {}\n", model->thetaText());
  if (const FaultReport faults = backend.faultReport(); faults.any()) fmt::print(stderr, "{}", faults.summary());
  return 0;
}

}  // namespace

void addLlmCommand(CLI::App& app, int& exitCode) {
  auto* llm = app.add_subcommand("llm", "Text-preference backends: probe a language-model server, run the Books user");
  llm->require_subcommand(1);
  auto options = std::make_shared<ProbeOptions>();
  auto* probe = llm->add_subcommand("probe", "Check that an OpenAI-compatible server returns usable log-probabilities");
  probe->add_option("--base-url", options->baseUrl, "Base URL, e.g. http://127.0.0.1:8080/v1")->required();
  probe->add_option("--model", options->model, "Model name")->required();
  probe->add_option("--api-key-env", options->apiKeyEnv, "Environment variable holding the API key (never printed)")
      ->capture_default_str();
  probe->add_option("--max-tokens-field", options->maxTokensField, "max_tokens or max_completion_tokens")
      ->capture_default_str();
  probe->add_option("--connect-timeout-ms", options->connectTimeoutMs, "Connect timeout")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  probe->add_option("--timeout-ms", options->timeoutMs, "Whole-request timeout")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  probe->add_option("--attempts", options->attempts, "Attempts per request, retries included")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));
  auto books = std::make_shared<BooksOptions>();
  auto* booksCmd = llm->add_subcommand(
      "books", "Learn the simulated Books user's preference with a text-preference backend (offline by default)");
  booksCmd->add_option("file", books->file, "the Books program (domains/books/books.cbtl)")->required();
  booksCmd->add_option("--stdlib", books->stdlibDir, "standard library folder (default: embedded)");
  booksCmd->add_option("--backend", books->backend, "offline-descriptor (no server) or openai-compatible")
      ->capture_default_str()
      ->check(CLI::IsMember({"offline-descriptor", "openai-compatible"}));
  booksCmd->add_option("--base-url", books->baseUrl, "Server base URL (openai-compatible)")->capture_default_str();
  booksCmd->add_option("--model", books->model, "Model name (openai-compatible)")->capture_default_str();
  booksCmd->add_option("--api-key-env", books->apiKeyEnv, "Environment variable holding the API key")
      ->capture_default_str();
  booksCmd->add_option("--cache-dir", books->cacheDir, "Response cache folder (empty: memory only)");
  booksCmd->add_option("--cache-mode", books->cacheMode, "off, read-write, read-only or record")
      ->capture_default_str()
      ->check(CLI::IsMember({"off", "read-write", "read-only", "record"}));
  booksCmd->add_option("--scale", books->scale, "digits (paper) or options (reference code)")
      ->capture_default_str()
      ->check(CLI::IsMember({"digits", "options"}));
  booksCmd->add_option("--rounds", books->rounds, "Handovers")->capture_default_str()->check(CLI::Range(1, 100));
  booksCmd->add_option("--attempts", books->attempts, "Attempts per request")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));
  booksCmd->callback(
      [books, &exitCode] { cbtl::cli::runCommand("llm books", exitCode, [&] { return runBooks(*books); }); });

  probe->callback(
      [options, &exitCode] { cbtl::cli::runCommand("llm probe", exitCode, [&] { return runProbe(*options); }); });
}

static cbtl::cli::RegisterCommand reg(60, addLlmCommand);
