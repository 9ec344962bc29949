// cbtl profile — the profile store (app/profile/ProfileStore.h) for people: what it holds, one profile's model and
// its history of versions and feedback events, export to and import from the profile JSON, rollback.
//
//   cbtl profile list     --db profiles.sqlite
//   cbtl profile show     --db profiles.sqlite USER DOMAIN [--version N]
//   cbtl profile history  --db profiles.sqlite USER DOMAIN
//   cbtl profile export   --db profiles.sqlite USER DOMAIN [--version N] [--out FILE]
//   cbtl profile import   --db profiles.sqlite USER FILE
//   cbtl profile rollback --db profiles.sqlite USER DOMAIN VERSION
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"

#include "app/profile/ProfileStore.h"
#include "support/InputFile.h"

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace {

using cbtl::app::profile::ModelVersion;
using cbtl::app::profile::ProfileStore;

struct ProfileArgs {
  std::string db, user, domain, file, out;
  std::int64_t version = 0;
};

ModelVersion versionOf(const ProfileStore& store, const ProfileArgs& a) {
  const std::optional<ModelVersion> v =
      a.version > 0 ? store.version(a.user, a.domain, a.version) : store.head(a.user, a.domain);
  if (!v)
    throw std::runtime_error(a.version > 0 ? fmt::format("{}: '{}' has no version {} of a {} profile", store.path(),
                                                         a.user, a.version, a.domain)
                                           : fmt::format("{}: '{}' has no {} profile", store.path(), a.user, a.domain));
  return *v;
}

// A stored model as JSON. A damaged one (the database edited or corrupted by hand) is bad input, said with what to
// do, never "a bug": the store keeps every version, so an earlier one can become the head again.
nlohmann::json storedModel(const ProfileStore& store, const ProfileArgs& a, const ModelVersion& v) {
  nlohmann::json model = nlohmann::json::parse(v.model, nullptr, false);
  if (model.is_discarded() || !model.is_object())
    throw std::runtime_error(fmt::format(
        "{}: version {} of the {} profile of '{}' is damaged: its stored model is not a JSON object; `cbtl profile "
        "rollback` can make an earlier version the head, `cbtl profile import` can store a good one",
        store.path(), v.version, a.domain, a.user));
  return model;
}

int list(const ProfileArgs& a) {
  const ProfileStore store(a.db, false);
  const auto profiles = store.list();
  if (profiles.empty()) fmt::print("{}: no profiles\n", a.db);
  for (const auto& p : profiles)
    fmt::print("{:<20} {:<12} version {:<4} ({} version{}, {} event{}), updated {}\n", p.user, p.domain, p.head,
               p.versions, p.versions == 1 ? "" : "s", p.events, p.events == 1 ? "" : "s", p.updated);
  return 0;
}

int show(const ProfileArgs& a) {
  const ProfileStore store(a.db, false);
  const ModelVersion v = versionOf(store, a);
  const nlohmann::json model = storedModel(store, a, v);
  fmt::print("{}'s {} profile, version {} of {} ({}, {}): {} labels\n", a.user, a.domain, v.version,
             store.versions(a.user, a.domain).size(), v.reason, v.time, v.labels);
  fmt::print("{}\n", model.dump(2));
  return 0;
}

int history(const ProfileArgs& a) {
  const ProfileStore store(a.db, false);
  const auto versions = store.versions(a.user, a.domain);
  if (versions.empty()) throw std::runtime_error(fmt::format("{}: '{}' has no {} profile", a.db, a.user, a.domain));
  const auto events = store.events(a.user, a.domain);
  std::size_t next = 0;
  for (const auto& v : versions) {
    fmt::print("version {}  {}  {}  ({} labels)\n", v.version, v.time, v.reason, v.labels);
    for (; next < events.size() && events[next].version == v.version; ++next) {
      const auto& e = events[next];
      fmt::print("  event {}  {}  {}{}\n", e.id, cbtl::app::profile::sourceName(e.source), e.event,
                 e.solution.empty() ? "" : "  (with its solution)");
    }
  }
  return 0;
}

int exportProfile(const ProfileArgs& a) {
  const ProfileStore store(a.db, false);
  const std::string model = storedModel(store, a, versionOf(store, a)).dump(2) + "\n";
  if (a.out.empty()) {
    fmt::print("{}", model);
    return 0;
  }
  std::ofstream out(a.out, std::ios::binary | std::ios::trunc);
  out << model;
  if (!out.flush()) throw std::runtime_error(fmt::format("{}: cannot write the profile", a.out));
  fmt::print(stderr, "wrote {}'s {} profile to {}\n", a.user, a.domain, a.out);
  return 0;
}

int importProfile(const ProfileArgs& a) {
  std::string text;
  try {
    text = cbtl::support::readInputFile(a.file, cbtl::support::kMaxDataBytes, "profile");
  } catch (const cbtl::support::InputFileError& e) {
    throw std::runtime_error(e.what());
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  // The store cannot check the model against a program; it checks what every profile has.
  if (j.is_discarded() || !j.is_object() || j.value("format", "") != "cbtl-profile" || j.value("version", 0) != 1 ||
      !j.contains("domain") || !j["domain"].is_string() || !j.contains("generators") || !j["generators"].is_object())
    throw std::runtime_error(fmt::format("{}: not a cbtl-profile (version 1) with a domain and generators", a.file));
  std::int64_t labels = 0;
  for (const auto& [generator, keys] : j["generators"].items())
    for (const auto& [key, factors] : keys.items())
      for (const auto& [label, factor] : factors.items())
        if (factor.contains("data") && factor["data"].is_array())
          labels += static_cast<std::int64_t>(factor["data"].size());
  ProfileStore store(a.db, true);
  const std::string domain = j["domain"];
  const std::int64_t v = store.recordLearning(a.user, domain, {}, text, labels, "import of " + a.file);
  fmt::print("imported {} as version {} of {}'s {} profile\n", a.file, v, a.user, domain);
  return 0;
}

int rollback(const ProfileArgs& a) {
  ProfileStore store(a.db, false);
  const std::int64_t v = store.rollback(a.user, a.domain, a.version);
  fmt::print("version {} of {}'s {} profile holds version {}'s model\n", v, a.user, a.domain, a.version);
  return 0;
}

void addProfile(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<ProfileArgs>();
  CLI::App* cmd = app.add_subcommand("profile", "the profile store: list, show, history, export, import, rollback");
  cmd->require_subcommand(1);
  const auto sub = [&](const char* name, const char* help, int (*body)(const ProfileArgs&)) {
    CLI::App* s = cmd->add_subcommand(name, help);
    s->add_option("--db", args->db, "the profile store (SQLite)")->required();
    s->callback([args, &exitCode, name, body]() {
      cbtl::cli::runCommand(std::string("profile ") + name, exitCode, [&] { return body(*args); });
    });
    return s;
  };
  sub("list", "every stored profile: user, domain, head version, counts", list);
  CLI::App* s = sub("show", "one profile's model (the head, or --version N)", show);
  s->add_option("user", args->user)->required();
  s->add_option("domain", args->domain)->required();
  s->add_option("--version", args->version, "a version number (default: the head)")->check(CLI::PositiveNumber);
  s = sub("history", "every version of a profile with the feedback events it learned", history);
  s->add_option("user", args->user)->required();
  s->add_option("domain", args->domain)->required();
  s = sub("export", "a version of a profile as profile JSON (cbtl run/solve --profile read it)", exportProfile);
  s->add_option("user", args->user)->required();
  s->add_option("domain", args->domain)->required();
  s->add_option("--version", args->version, "a version number (default: the head)")->check(CLI::PositiveNumber);
  s->add_option("--out", args->out, "write it here (default: stdout)");
  s = sub("import", "a profile JSON as the user's new head version for its domain (the store is created if missing)",
          importProfile);
  s->add_option("user", args->user)->required();
  s->add_option("file", args->file)->required();
  s = sub("rollback", "a new head version holding an earlier version's model (nothing is deleted)", rollback);
  s->add_option("user", args->user)->required();
  s->add_option("domain", args->domain)->required();
  s->add_option("version", args->version)->required()->check(CLI::PositiveNumber);
}

const cbtl::cli::RegisterCommand registerProfile(23, addProfile);

}  // namespace
