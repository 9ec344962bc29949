#include "app/profile/ProfileStore.h"

#include "app/profile/SqliteFile.h"

#include <fmt/format.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <thread>
#include <utility>

namespace cbtl::app::profile {

namespace {

constexpr int kApplicationId = 0x4342544C;  // "CBTL": marks the file as ours, so no other SQLite file is written
constexpr int kSchemaVersion = 1;

constexpr const char* kSchema = R"sql(
CREATE TABLE users(id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE, created TEXT NOT NULL);
CREATE TABLE domains(id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE);
CREATE TABLE profiles(id INTEGER PRIMARY KEY,
                      user_id INTEGER NOT NULL REFERENCES users(id),
                      domain_id INTEGER NOT NULL REFERENCES domains(id),
                      UNIQUE(user_id, domain_id));
CREATE TABLE versions(profile_id INTEGER NOT NULL REFERENCES profiles(id), version INTEGER NOT NULL,
                      time TEXT NOT NULL, reason TEXT NOT NULL, labels INTEGER NOT NULL, model TEXT NOT NULL,
                      PRIMARY KEY(profile_id, version));
CREATE TABLE events(id INTEGER PRIMARY KEY AUTOINCREMENT, profile_id INTEGER NOT NULL, version INTEGER NOT NULL,
                    time TEXT NOT NULL,
                    source TEXT NOT NULL CHECK(source IN ('simulator', 'repl', 'command', 'study')),
                    event TEXT NOT NULL, solution TEXT NOT NULL,
                    FOREIGN KEY(profile_id, version) REFERENCES versions(profile_id, version));
CREATE INDEX events_by_profile ON events(profile_id, id);
)sql";

struct ProfileStoreFile {
  using Error = StoreError;
  static constexpr const char* kind = "profile store";
};
using Statement = sqlite::Statement<ProfileStoreFile>;
using WriteTransaction = sqlite::WriteTransaction<ProfileStoreFile>;
using sqlite::utcNow;
std::string failure(const std::string& path, sqlite3* db, int code) {
  return sqlite::failure(path, db, code, ProfileStoreFile::kind);
}
void exec(sqlite3* db, const std::string& path, const char* sql) { sqlite::exec<ProfileStoreFile>(db, path, sql); }

std::int64_t pragmaInt(sqlite3* db, const std::string& path, const char* sql) {
  Statement s(db, path, sql);
  return s.step() ? s.integer(0) : 0;
}

void checkName(const std::string& path, const char* what, const std::string& name) {
  if (name.empty() || name.size() > 200)
    throw StoreError(fmt::format("{}: a {} name has 1 to 200 bytes, not {}", path, what, name.size()));
  for (unsigned char c : name)
    if (c < 0x20 || c == 0x7f)
      throw StoreError(fmt::format("{}: the {} name '{}' holds a control character", path, what, name));
}

ModelVersion readVersion(const Statement& s) { return {s.integer(0), s.text(1), s.text(2), s.integer(3), s.text(4)}; }

}  // namespace

const char* sourceName(EventSource source) {
  switch (source) {
    case EventSource::Simulator:
      return "simulator";
    case EventSource::Repl:
      return "repl";
    case EventSource::Command:
      return "command";
    case EventSource::Study:
      return "study";
  }
  return "command";
}

std::optional<EventSource> sourceNamed(const std::string& name) {
  for (EventSource s : {EventSource::Simulator, EventSource::Repl, EventSource::Command, EventSource::Study})
    if (name == sourceName(s)) return s;
  return std::nullopt;
}

namespace {

// An existing file of 0 bytes is a store that lost its contents (a truncating copy, `> file`, a full disk), which
// SQLite would silently open as a new, empty database. A store this process creates is 0 bytes too, but only
// until its schema is written in the creator's first transaction; another process that opens it in that window
// (milliseconds) waits a little and looks again before calling it damaged.
void refuseAnEmptyFile(const std::string& path) {
  std::error_code ec;
  for (int look = 0; look < 20; ++look) {
    const auto size = std::filesystem::file_size(path, ec);
    if (ec || size != 0) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  throw StoreError(
      fmt::format("{}: an empty file (0 bytes), not a profile store; a store whose contents were lost would "
                  "otherwise start afresh without a word. Restore it from a backup, or, to start a new store, "
                  "delete the file or name one that does not exist",
                  path));
}

}  // namespace

ProfileStore::ProfileStore(const std::string& path, bool create, int busyTimeoutMs) : path_(path) {
  const bool existed = std::filesystem::exists(path);
  if (!create && !existed) throw StoreError(fmt::format("{}: no such profile store", path));
  if (existed && !std::filesystem::is_regular_file(path))
    throw StoreError(fmt::format("{}: not a regular file, so not a profile store", path));
  if (existed) refuseAnEmptyFile(path);
  const int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_FULLMUTEX | (create ? SQLITE_OPEN_CREATE : 0);
  const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string what = failure(path_, db_, rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw StoreError(what);
  }
  try {
    sqlite3_busy_timeout(db_, busyTimeoutMs);
    exec(db_, path_, "PRAGMA foreign_keys = ON");
    if (pragmaInt(db_, path_, "PRAGMA application_id") != kApplicationId) {
      WriteTransaction t(db_, path_);  // a fresh file is set up by exactly one of the processes opening it
      const std::int64_t id = pragmaInt(db_, path_, "PRAGMA application_id");
      if (id != kApplicationId) {
        if (id != 0 || pragmaInt(db_, path_, "SELECT count(*) FROM sqlite_master") != 0)
          throw StoreError(fmt::format("{}: a SQLite database, but not a CBTL profile store", path_));
        exec(db_, path_, kSchema);
        exec(db_, path_, fmt::format("PRAGMA application_id = {}", kApplicationId).c_str());
        exec(db_, path_, fmt::format("PRAGMA user_version = {}", kSchemaVersion).c_str());
      }
      t.commit();
    }
    const std::int64_t schema = pragmaInt(db_, path_, "PRAGMA user_version");
    if (schema > kSchemaVersion)
      throw StoreError(
          fmt::format("{}: a store of schema {}, newer than this cbtl's {}", path_, schema, kSchemaVersion));
    exec(db_, path_, "PRAGMA journal_mode = WAL");
    exec(db_, path_, "PRAGMA synchronous = FULL");
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

ProfileStore::~ProfileStore() {
  if (db_ != nullptr) sqlite3_close(db_);
}

ProfileStore::ProfileStore(ProfileStore&& other) noexcept
    : path_(std::move(other.path_)),
      db_(std::exchange(other.db_, nullptr)),
      integrityChecked_(other.integrityChecked_) {}

ProfileStore& ProfileStore::operator=(ProfileStore&& other) noexcept {
  if (this != &other) {
    if (db_ != nullptr) sqlite3_close(db_);
    path_ = std::move(other.path_);
    db_ = std::exchange(other.db_, nullptr);
    integrityChecked_ = other.integrityChecked_;
  }
  return *this;
}

namespace {

// The id of (user, domain)'s profile, made when missing (inside the caller's transaction).
std::int64_t profileId(sqlite3* db, const std::string& path, const std::string& user, const std::string& domain,
                       const std::string& now) {
  Statement(db, path, "INSERT OR IGNORE INTO users(name, created) VALUES (?, ?)").bind(1, user).bind(2, now).step();
  Statement(db, path, "INSERT OR IGNORE INTO domains(name) VALUES (?)").bind(1, domain).step();
  Statement(db, path,
            "INSERT OR IGNORE INTO profiles(user_id, domain_id) SELECT users.id, domains.id FROM users, domains "
            "WHERE users.name = ? AND domains.name = ?")
      .bind(1, user)
      .bind(2, domain)
      .step();
  Statement s(db, path,
              "SELECT profiles.id FROM profiles JOIN users ON users.id = profiles.user_id JOIN domains ON "
              "domains.id = profiles.domain_id WHERE users.name = ? AND domains.name = ?");
  s.bind(1, user).bind(2, domain);
  if (!s.step()) throw StoreError(fmt::format("{}: the profile of '{}' for '{}' was not made", path, user, domain));
  return s.integer(0);
}

constexpr const char* kProfileOf =
    "(SELECT profiles.id FROM profiles JOIN users ON users.id = profiles.user_id JOIN domains ON domains.id = "
    "profiles.domain_id WHERE users.name = ?1 AND domains.name = ?2)";

}  // namespace

std::int64_t ProfileStore::recordLearning(const std::string& user, const std::string& domain,
                                          const std::vector<NewEvent>& events, const std::string& model,
                                          std::int64_t labels, const std::string& reason,
                                          std::optional<std::int64_t> learnedFrom) {
  WriteTransaction t(db_, path_);
  const std::int64_t version = writeVersion(user, domain, {events, model, labels, reason}, learnedFrom);
  t.commit();
  return version;
}

std::int64_t ProfileStore::learnOnHead(
    const std::string& user, const std::string& domain,
    const std::function<LearningStep(const std::optional<ModelVersion>& head)>& learn) {
  WriteTransaction t(db_, path_);
  const std::optional<ModelVersion> now = head(user, domain);
  const LearningStep step = learn(now);
  const std::int64_t version = writeVersion(user, domain, step, now ? now->version : 0);
  t.commit();
  return version;
}

std::int64_t ProfileStore::writeVersion(const std::string& user, const std::string& domain, const LearningStep& step,
                                        std::optional<std::int64_t> learnedFrom) {
  checkName(path_, "user", user);
  checkName(path_, "domain", domain);
  const nlohmann::json parsed = nlohmann::json::parse(step.model, nullptr, false);
  if (parsed.is_discarded() || !parsed.is_object())
    throw StoreError(fmt::format("{}: the model to store is not a JSON object", path_));
  const std::string now = utcNow();
  // Learning is never added to a damaged store: writing into broken pages can lose what is still readable. The
  // check reads the whole file (2 ms a MB), inside the write lock, so no other writer changes it between the check
  // and the write; once per connection: a command opens the store for each run, while a long-lived server (the
  // study's, with hundreds of writes into one growing file) would otherwise pay it on every answer.
  if (!integrityChecked_) {
    Statement integrity(db_, path_, "PRAGMA integrity_check(1)");
    if (integrity.step() && integrity.text(0) != "ok")
      throw StoreError(
          fmt::format("{}: the store fails SQLite's integrity check ({}); nothing was written. `cbtl "
                      "profile export` still reads the versions it can: export them and import them into "
                      "a new store, or restore a backup",
                      path_, integrity.text(0)));
    integrityChecked_ = true;
  }
  const std::int64_t profile = profileId(db_, path_, user, domain, now);
  Statement next(db_, path_, "SELECT COALESCE(MAX(version), 0) FROM versions WHERE profile_id = ?");
  next.bind(1, profile).step();
  const std::int64_t headVersion = next.integer(0);
  if (learnedFrom && *learnedFrom != headVersion)
    throw StoreError(fmt::format(
        "{}: the {} profile of '{}' changed while this model was learned (it was learned from {}, the store now "
        "holds version {}, stored by another process); nothing was written, since storing it would drop that "
        "learning. Start again from the stored profile",
        path_, domain, user, *learnedFrom == 0 ? std::string("the prior") : fmt::format("version {}", *learnedFrom),
        headVersion));
  const std::int64_t version = headVersion + 1;
  Statement(db_, path_,
            "INSERT INTO versions(profile_id, version, time, reason, labels, model) VALUES (?, ?, ?, ?, ?, ?)")
      .bind(1, profile)
      .bind(2, version)
      .bind(3, now)
      .bind(4, step.reason)
      .bind(5, step.labels)
      .bind(6, step.model)
      .step();
  Statement insert(db_, path_,
                   "INSERT INTO events(profile_id, version, time, source, event, solution) VALUES (?, ?, ?, ?, ?, ?)");
  for (const NewEvent& e : step.events) {
    insert.bind(1, profile).bind(2, version).bind(3, now).bind(4, std::string(sourceName(e.source)));
    insert.bind(5, e.event).bind(6, e.solution).step();
    insert.reset();
  }
  return version;
}

std::int64_t ProfileStore::rollback(const std::string& user, const std::string& domain, std::int64_t version) {
  const std::optional<ModelVersion> old = this->version(user, domain, version);
  if (!old) throw StoreError(fmt::format("{}: '{}' has no version {} of a {} profile", path_, user, version, domain));
  return recordLearning(user, domain, {}, old->model, old->labels, fmt::format("rollback to {}", version));
}

std::vector<ProfileSummary> ProfileStore::list() const {
  Statement s(db_, path_,
              "SELECT users.name, domains.name, "
              "(SELECT count(*) FROM events WHERE events.profile_id = profiles.id), "
              "(SELECT count(*) FROM versions WHERE versions.profile_id = profiles.id), "
              "(SELECT MAX(version) FROM versions WHERE versions.profile_id = profiles.id), "
              "(SELECT time FROM versions WHERE versions.profile_id = profiles.id ORDER BY version DESC LIMIT 1) "
              "FROM profiles JOIN users ON users.id = profiles.user_id JOIN domains ON domains.id = "
              "profiles.domain_id ORDER BY users.name, domains.name");
  std::vector<ProfileSummary> out;
  while (s.step()) out.push_back({s.text(0), s.text(1), s.integer(2), s.integer(3), s.integer(4), s.text(5)});
  return out;
}

std::optional<ModelVersion> ProfileStore::head(const std::string& user, const std::string& domain) const {
  Statement s(db_, path_,
              fmt::format("SELECT version, time, reason, labels, model FROM versions WHERE profile_id = {} "
                          "ORDER BY version DESC LIMIT 1",
                          kProfileOf)
                  .c_str());
  s.bind(1, user).bind(2, domain);
  if (!s.step()) return std::nullopt;
  return readVersion(s);
}

std::optional<ModelVersion> ProfileStore::version(const std::string& user, const std::string& domain,
                                                  std::int64_t v) const {
  Statement s(db_, path_,
              fmt::format("SELECT version, time, reason, labels, model FROM versions WHERE profile_id = {} "
                          "AND version = ?3",
                          kProfileOf)
                  .c_str());
  s.bind(1, user).bind(2, domain).bind(3, v);
  if (!s.step()) return std::nullopt;
  return readVersion(s);
}

std::vector<ModelVersion> ProfileStore::versions(const std::string& user, const std::string& domain) const {
  Statement s(db_, path_,
              fmt::format("SELECT version, time, reason, labels, model FROM versions WHERE profile_id = {} "
                          "ORDER BY version",
                          kProfileOf)
                  .c_str());
  s.bind(1, user).bind(2, domain);
  std::vector<ModelVersion> out;
  while (s.step()) out.push_back(readVersion(s));
  return out;
}

std::vector<StoredEvent> ProfileStore::events(const std::string& user, const std::string& domain) const {
  Statement s(db_, path_,
              fmt::format("SELECT id, time, source, event, solution, version FROM events WHERE profile_id = {} "
                          "ORDER BY id",
                          kProfileOf)
                  .c_str());
  s.bind(1, user).bind(2, domain);
  std::vector<StoredEvent> out;
  while (s.step())
    out.push_back({s.integer(0), s.text(1), sourceNamed(s.text(2)).value_or(EventSource::Command), s.text(3), s.text(4),
                   s.integer(5)});
  return out;
}

}  // namespace cbtl::app::profile
