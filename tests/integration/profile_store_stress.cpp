// profile_store_stress — writes to a profile store as fast as it can, acknowledging each write, so a test can kill
// it at any moment and check that nothing acknowledged was lost (profile_store_kill.sh).
//
//   profile_store_stress DB USER DOMAIN COUNT   COUNT learning steps, each: two events "tick(I, a)", "tick(I, b)"
//                                               and a model {"...": ..., "n": I}; prints "acked I" after each returns
//   profile_store_stress --check DB USER DOMAIN prints "versions V events E"; exits 1 unless the file is intact and
//                                               versions 1..V hold n = their own number with their two events
#include "app/profile/ProfileStore.h"

#include <fmt/core.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <map>
#include <set>
#include <string>

namespace {

using cbtl::app::profile::ProfileStore;

std::string modelOf(const std::string& domain, long n) {
  return fmt::format(R"({{"format": "cbtl-profile", "version": 1, "domain": "{}", "generators": {{}}, "n": {}}})",
                     domain, n);
}

int write(const std::string& db, const std::string& user, const std::string& domain, long count) {
  ProfileStore store(db);
  for (long i = 1; i <= count; ++i) {
    const std::vector<cbtl::app::profile::NewEvent> events = {
        {cbtl::app::profile::EventSource::Simulator, fmt::format("tick({}, a)", i), ""},
        {cbtl::app::profile::EventSource::Simulator, fmt::format("tick({}, b)", i), ""}};
    const std::int64_t v = store.recordLearning(user, domain, events, modelOf(domain, i), i, "learn");
    std::printf("acked %lld\n", static_cast<long long>(v));
    std::fflush(stdout);
  }
  return 0;
}

bool intact(const std::string& db) {
  sqlite3* raw = nullptr;
  if (sqlite3_open_v2(db.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return false;
  sqlite3_stmt* s = nullptr;
  bool ok = sqlite3_prepare_v2(raw, "PRAGMA integrity_check", -1, &s, nullptr) == SQLITE_OK &&
            sqlite3_step(s) == SQLITE_ROW &&
            std::string(reinterpret_cast<const char*>(sqlite3_column_text(s, 0))) == "ok";
  sqlite3_finalize(s);
  sqlite3_close(raw);
  return ok;
}

int check(const std::string& db, const std::string& user, const std::string& domain) {
  if (!intact(db)) {
    std::printf("integrity check failed\n");
    return 1;
  }
  const ProfileStore store(db, false);
  const auto versions = store.versions(user, domain);
  const auto events = store.events(user, domain);
  std::printf("versions %zu events %zu\n", versions.size(), events.size());
  std::map<std::int64_t, std::set<std::string>> byVersion;
  for (const auto& e : events) byVersion[e.version].insert(e.event);
  // Each writer numbers its models from 1 per process, so only the version sequence and the pairing of a version
  // with its own two events are checked, not n == version across restarts.
  for (std::size_t i = 0; i < versions.size(); ++i) {
    if (versions[i].version != static_cast<std::int64_t>(i + 1)) {
      std::printf("version %zu is numbered %lld\n", i + 1, static_cast<long long>(versions[i].version));
      return 1;
    }
    const long n = nlohmann::json::parse(versions[i].model).at("n").get<long>();
    const auto& own = byVersion[versions[i].version];
    const int found =
        static_cast<int>(own.count(fmt::format("tick({}, a)", n)) + own.count(fmt::format("tick({}, b)", n)));
    if (found != 2 || own.size() != 2) {
      std::printf("version %lld (n = %ld) has %d of its 2 events\n", static_cast<long long>(versions[i].version), n,
                  found);
      return 1;
    }
  }
  if (events.size() != 2 * versions.size()) {
    std::printf("%zu events for %zu versions\n", events.size(), versions.size());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 5 && std::string(argv[1]) == "--check") return check(argv[2], argv[3], argv[4]);
    if (argc == 5) return write(argv[1], argv[2], argv[3], std::stol(argv[4]));
    std::fprintf(stderr, "usage: profile_store_stress DB USER DOMAIN COUNT | --check DB USER DOMAIN\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "profile_store_stress: %s\n", e.what());
    return 1;
  }
}
