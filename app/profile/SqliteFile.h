// SqliteFile.h — the SQLite plumbing the project's stores share (profile::ProfileStore, study::StudyRecords):
// prepared statements, one-shot statements, write transactions and the time stamps they record. Every failure is
// thrown as the store's own error type, its message starting with the file's path.
//
// A store describes itself with a traits type:
//   struct Traits { using Error = StoreError; static constexpr const char* kind = "profile store"; };
// `kind` names the file in messages ("the profile store is busy ...", "not a CBTL profile store").
#pragma once

#include <fmt/format.h>
#include <sqlite3.h>

#include <chrono>
#include <cstdint>
#include <ctime>
#include <string>

namespace cbtl::app::sqlite {

inline std::string failure(const std::string& path, sqlite3* db, int code, const char* kind) {
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED)
    return fmt::format("{}: the {} is busy (another process held it longer than the busy timeout)", path, kind);
  if (code == SQLITE_NOTADB) return fmt::format("{}: not a SQLite database, so not a CBTL {}", path, kind);
  return fmt::format("{}: {}", path, db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(code));
}

template <class Traits>
class Statement {
 public:
  Statement(sqlite3* db, const std::string& path, const char* sql) : db_(db), path_(path) {
    const int rc = sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr);
    if (rc != SQLITE_OK) throw typename Traits::Error(failure(path_, db_, rc, Traits::kind));
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, const std::string& text) {
    check(sqlite3_bind_text(stmt_, i, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind(int i, std::int64_t value) {
    check(sqlite3_bind_int64(stmt_, i, value));
    return *this;
  }
  // True while there is a row to read.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    throw typename Traits::Error(failure(path_, db_, rc, Traits::kind));
  }
  void reset() {
    sqlite3_reset(stmt_);
    sqlite3_clear_bindings(stmt_);
  }
  std::int64_t integer(int column) const { return sqlite3_column_int64(stmt_, column); }
  bool null(int column) const { return sqlite3_column_type(stmt_, column) == SQLITE_NULL; }
  std::string text(int column) const {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, column));
    return p != nullptr ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column))) : "";
  }

 private:
  void check(int rc) const {
    if (rc != SQLITE_OK) throw typename Traits::Error(failure(path_, db_, rc, Traits::kind));
  }
  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* stmt_ = nullptr;
};

// Runs `sql` (any number of statements, no results).
template <class Traits>
void exec(sqlite3* db, const std::string& path, const char* sql) {
  char* message = nullptr;
  const int rc = sqlite3_exec(db, sql, nullptr, nullptr, &message);
  if (rc != SQLITE_OK) {
    const std::string what = rc == SQLITE_BUSY || rc == SQLITE_NOTADB || message == nullptr
                                 ? failure(path, db, rc, Traits::kind)
                                 : fmt::format("{}: {}", path, message);
    sqlite3_free(message);
    throw typename Traits::Error(what);
  }
}

// BEGIN IMMEDIATE takes the write lock at once, so two writers queue on the busy timeout instead of failing later
// with a deadlock; anything that leaves the scope before commit() rolls back.
template <class Traits>
class WriteTransaction {
 public:
  WriteTransaction(sqlite3* db, const std::string& path) : db_(db), path_(path) {
    exec<Traits>(db_, path_, "BEGIN IMMEDIATE");
  }
  ~WriteTransaction() {
    if (!done_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;
  void commit() {
    exec<Traits>(db_, path_, "COMMIT");
    done_ = true;
  }

 private:
  sqlite3* db_;
  const std::string& path_;
  bool done_ = false;
};

// Now, UTC, ISO 8601 with milliseconds ("2026-12-05T04:55:01.123Z").
inline std::string utcNow() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  return fmt::format("{}.{:03d}Z", text, static_cast<int>(ms));
}

}  // namespace cbtl::app::sqlite
