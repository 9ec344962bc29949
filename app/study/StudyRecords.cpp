#include "app/study/StudyRecords.h"

#include "app/profile/ProfileStore.h"
#include "app/profile/SqliteFile.h"

#include <fmt/format.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <utility>

namespace cbtl::app::study {

namespace {

// 2: study_keys (participants' keys, as hashes). A file of schema 1 gets the table when opened.
constexpr std::int64_t kSchemaVersion = 2;

constexpr const char* kKeysTable = R"sql(
CREATE TABLE IF NOT EXISTS study_keys(participant TEXT PRIMARY KEY, key_hash TEXT NOT NULL, issued TEXT NOT NULL);
)sql";

constexpr const char* kSchema = R"sql(
CREATE TABLE study_meta(key TEXT PRIMARY KEY, value INTEGER NOT NULL);
CREATE TABLE study_participants(id TEXT PRIMARY KEY, created TEXT NOT NULL, seed INTEGER NOT NULL,
                                options TEXT NOT NULL, completed TEXT);
CREATE TABLE study_records(participant TEXT NOT NULL REFERENCES study_participants(id), trial_index INTEGER NOT NULL,
                           kind TEXT NOT NULL, meal INTEGER NOT NULL, elapsed_ms INTEGER NOT NULL,
                           rt_ms INTEGER NOT NULL, response TEXT NOT NULL, recorded TEXT NOT NULL,
                           PRIMARY KEY(participant, trial_index));
CREATE TABLE study_keys(participant TEXT PRIMARY KEY, key_hash TEXT NOT NULL, issued TEXT NOT NULL);
)sql";

struct StudyDatabaseFile {
  using Error = StudyError;
  static constexpr const char* kind = "study database";
};
using Statement = sqlite::Statement<StudyDatabaseFile>;
using WriteTransaction = sqlite::WriteTransaction<StudyDatabaseFile>;
using sqlite::utcNow;
std::string failure(const std::string& path, sqlite3* db, int code) {
  return sqlite::failure(path, db, code, StudyDatabaseFile::kind);
}
void exec(sqlite3* db, const std::string& path, const char* sql) { sqlite::exec<StudyDatabaseFile>(db, path, sql); }

std::int64_t schemaVersion(sqlite3* db, const std::string& path) {
  Statement version(db, path, "SELECT value FROM study_meta WHERE key = 'schema_version'");
  return version.step() ? version.integer(0) : 0;
}

bool hasStudyTables(sqlite3* db, const std::string& path) {
  Statement s(db, path, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'study_meta'");
  return s.step() && s.integer(0) > 0;
}

}  // namespace

std::string quotedText(const std::string& text) {
  constexpr std::size_t kShown = 80;
  std::string out = "'";
  for (std::size_t i = 0; i < text.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\'' || c == '\\')
      out += fmt::format("\\{}", static_cast<char>(c));
    else if (c < 0x20 || c >= 0x7f)
      out += fmt::format("\\x{:02x}", c);
    else
      out += static_cast<char>(c);
  }
  out += text.size() > kShown ? fmt::format("'... ({} bytes)", text.size()) : "'";
  return out;
}

namespace {

bool isKind(const std::string& kind) {
  if (kind.empty() || kind.size() > 40) return false;
  for (char c : kind)
    if (!((c >= 'a' && c <= 'z') || c == '_' || c == '-')) return false;
  return true;
}

void checkId(const std::string& path, const std::string& id) {
  if (!isParticipantId(id))
    throw StudyError(fmt::format("{}: the participant id {} is not 1 to 64 characters of A-Z, a-z, 0-9, '_', '.', '-'",
                                 path, quotedText(id)));
}

// The response as compact JSON, keeping the sender's key order; StudyError when it is not JSON.
std::string compactResponse(const std::string& path, const NewRecord& r) {
  const nlohmann::ordered_json parsed = nlohmann::ordered_json::parse(r.response, nullptr, false);
  if (parsed.is_discarded())
    throw StudyError(fmt::format("{}: the response of trial {} of participant {} is not JSON", path, r.trialIndex,
                                 quotedText(r.participant)));
  return parsed.dump();
}

void checkRecord(const std::string& path, const NewRecord& r) {
  checkId(path, r.participant);
  const std::string which = fmt::format("trial {} of participant {}", r.trialIndex, quotedText(r.participant));
  if (r.trialIndex < 0) throw StudyError(fmt::format("{}: {}: a trial index is >= 0", path, which));
  if (!isKind(r.kind))
    throw StudyError(
        fmt::format("{}: {}: the kind {} is not 1 to 40 characters of a-z, '_', '-'", path, which, quotedText(r.kind)));
  if (r.meal < 0 || r.meal > kMeals)
    throw StudyError(fmt::format("{}: {}: meal {} is not 0 (none) or 1 to {}", path, which, r.meal, kMeals));
  if (r.elapsedMs < 0 || r.rtMs < 0)
    throw StudyError(
        fmt::format("{}: {}: negative time (elapsed {} ms, reaction {} ms)", path, which, r.elapsedMs, r.rtMs));
}

constexpr const char* kParticipantColumns = "id, created, seed, options, completed";

Participant readParticipant(const Statement& s) {
  Participant p{s.text(0), s.text(1), static_cast<std::uint64_t>(s.integer(2)), s.text(3), std::nullopt};
  if (!s.null(4)) p.completed = s.text(4);
  return p;
}

constexpr const char* kRecordColumns = "participant, trial_index, kind, meal, elapsed_ms, rt_ms, response, recorded";

StoredRecord readRecord(const Statement& s) {
  return {s.text(0),    s.integer(1), s.text(2), static_cast<int>(s.integer(3)),
          s.integer(4), s.integer(5), s.text(6), s.text(7)};
}

// What differs between a stored record and a re-sent one, for the message refusing it; empty for a replay.
std::string differences(const StoredRecord& stored, const NewRecord& sent) {
  std::string out;
  const auto add = [&](const std::string& what) { out += (out.empty() ? "" : ", ") + what; };
  if (stored.kind != sent.kind) add(fmt::format("kind {} vs {}", quotedText(stored.kind), quotedText(sent.kind)));
  if (stored.meal != sent.meal) add(fmt::format("meal {} vs {}", stored.meal, sent.meal));
  if (nlohmann::json::parse(stored.response, nullptr, false) != nlohmann::json::parse(sent.response, nullptr, false))
    add("the response");
  return out;
}

std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

bool isParticipantId(const std::string& id) {
  if (id.empty() || id.size() > 64) return false;
  for (char c : id)
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' ||
          c == '-'))
      return false;
  return true;
}

StudyRecords::StudyRecords(const std::string& path, bool create, int busyTimeoutMs) : path_(path) {
  if (!create && !std::filesystem::exists(path)) throw StudyError(fmt::format("{}: no such study database", path));
  try {
    const profile::ProfileStore profiles(path, create, busyTimeoutMs);  // makes, or checks, the store we live in
  } catch (const profile::StoreError& e) {
    throw StudyError(e.what());
  }
  const int rc = sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_FULLMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    const std::string what = failure(path_, db_, rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw StudyError(what);
  }
  try {
    sqlite3_busy_timeout(db_, busyTimeoutMs);
    exec(db_, path_, "PRAGMA foreign_keys = ON");
    if (!hasStudyTables(db_, path_)) {
      WriteTransaction t(db_, path_);  // the study tables are added by exactly one of the processes opening the file
      if (!hasStudyTables(db_, path_)) {
        exec(db_, path_, kSchema);
        Statement(db_, path_, "INSERT INTO study_meta(key, value) VALUES ('schema_version', ?)")
            .bind(1, kSchemaVersion)
            .step();
      }
      t.commit();
    }
    std::int64_t schema = schemaVersion(db_, path_);
    if (schema < kSchemaVersion) {
      WriteTransaction t(db_, path_);
      if (schemaVersion(db_, path_) < kSchemaVersion) {
        exec(db_, path_, kKeysTable);
        Statement(db_, path_, "UPDATE study_meta SET value = ? WHERE key = 'schema_version'")
            .bind(1, kSchemaVersion)
            .step();
      }
      t.commit();
      schema = schemaVersion(db_, path_);
    }
    if (schema > kSchemaVersion)
      throw StudyError(
          fmt::format("{}: study tables of schema {}, newer than this cbtl's {}", path_, schema, kSchemaVersion));
    exec(db_, path_, "PRAGMA journal_mode = WAL");
    exec(db_, path_, "PRAGMA synchronous = FULL");
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

StudyRecords::~StudyRecords() {
  if (db_ != nullptr) sqlite3_close(db_);
}

StudyRecords::StudyRecords(StudyRecords&& other) noexcept
    : path_(std::move(other.path_)), db_(std::exchange(other.db_, nullptr)) {}

StudyRecords& StudyRecords::operator=(StudyRecords&& other) noexcept {
  if (this != &other) {
    if (db_ != nullptr) sqlite3_close(db_);
    path_ = std::move(other.path_);
    db_ = std::exchange(other.db_, nullptr);
  }
  return *this;
}

Participant StudyRecords::begin(const std::string& id, std::uint64_t seed, const std::string& optionsJson) {
  checkId(path_, id);
  const nlohmann::json options = nlohmann::json::parse(optionsJson, nullptr, false);
  if (options.is_discarded() || !options.is_object())
    throw StudyError(fmt::format("{}: the options of participant {} are not a JSON object", path_, quotedText(id)));
  WriteTransaction t(db_, path_);
  // Seeds of 2^63 and more are kept as their two's complement bit pattern, which reads back unchanged.
  Statement(db_, path_, "INSERT OR IGNORE INTO study_participants(id, created, seed, options) VALUES (?, ?, ?, ?)")
      .bind(1, id)
      .bind(2, utcNow())
      .bind(3, static_cast<std::int64_t>(seed))
      .bind(4, optionsJson)
      .step();
  t.commit();
  return *participant(id);
}

bool StudyRecords::claimKey(const std::string& id, const std::string& keyHash) {
  checkId(path_, id);
  WriteTransaction t(db_, path_);
  Statement(db_, path_, "INSERT OR IGNORE INTO study_keys(participant, key_hash, issued) VALUES (?, ?, ?)")
      .bind(1, id)
      .bind(2, keyHash)
      .bind(3, utcNow())
      .step();
  const bool claimed = sqlite3_changes(db_) == 1;
  t.commit();
  return claimed;
}

std::optional<std::string> StudyRecords::keyHash(const std::string& id) const {
  checkId(path_, id);
  Statement s(db_, path_, "SELECT key_hash FROM study_keys WHERE participant = ?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return s.text(0);
}

std::int64_t StudyRecords::participantCount() const {
  Statement s(db_, path_, "SELECT count(*) FROM study_participants");
  return s.step() ? s.integer(0) : 0;
}

std::optional<Participant> StudyRecords::participant(const std::string& id) const {
  checkId(path_, id);
  Statement s(db_, path_, fmt::format("SELECT {} FROM study_participants WHERE id = ?", kParticipantColumns).c_str());
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return readParticipant(s);
}

std::vector<Participant> StudyRecords::participants() const {
  Statement s(db_, path_, fmt::format("SELECT {} FROM study_participants ORDER BY rowid", kParticipantColumns).c_str());
  std::vector<Participant> out;
  while (s.step()) out.push_back(readParticipant(s));
  return out;
}

void StudyRecords::complete(const std::string& id) {
  checkId(path_, id);
  WriteTransaction t(db_, path_);
  Statement(db_, path_, "UPDATE study_participants SET completed = ? WHERE id = ? AND completed IS NULL")
      .bind(1, utcNow())
      .bind(2, id)
      .step();
  if (sqlite3_changes(db_) == 0 && !participant(id))
    throw StudyError(fmt::format("{}: no participant {} to complete", path_, quotedText(id)));
  t.commit();
}

RecordOutcome StudyRecords::record(const NewRecord& r) {
  checkRecord(path_, r);
  const std::string response = compactResponse(path_, r);
  WriteTransaction t(db_, path_);
  const std::optional<Participant> who = participant(r.participant);
  if (!who)
    throw StudyError(fmt::format("{}: no participant {} (begin the session first)", path_, quotedText(r.participant)));

  Statement existing(
      db_, path_,
      fmt::format("SELECT {} FROM study_records WHERE participant = ? AND trial_index = ?", kRecordColumns).c_str());
  existing.bind(1, r.participant).bind(2, r.trialIndex);
  if (existing.step()) {
    StoredRecord stored = readRecord(existing);
    const std::string differ = differences(stored, r);
    if (!differ.empty())
      throw StudyError(fmt::format("{}: trial {} of participant {} is already recorded, differently ({})", path_,
                                   r.trialIndex, quotedText(r.participant), differ));
    return {RecordOutcome::Status::Replayed, std::move(stored)};
  }
  if (who->completed)
    throw StudyError(fmt::format("{}: participant {} completed the study at {}; trial {} comes too late", path_,
                                 quotedText(r.participant), *who->completed, r.trialIndex));
  const std::int64_t expected = nextTrial(r.participant);
  if (r.trialIndex != expected)
    throw StudyError(fmt::format("{}: participant {}: expected trial {}, got {}", path_, quotedText(r.participant),
                                 expected, r.trialIndex));

  StoredRecord stored{r.participant, r.trialIndex, r.kind, r.meal, r.elapsedMs, r.rtMs, response, utcNow()};
  Statement(db_, path_,
            fmt::format("INSERT INTO study_records({}) VALUES (?, ?, ?, ?, ?, ?, ?, ?)", kRecordColumns).c_str())
      .bind(1, stored.participant)
      .bind(2, stored.trialIndex)
      .bind(3, stored.kind)
      .bind(4, std::int64_t{stored.meal})
      .bind(5, stored.elapsedMs)
      .bind(6, stored.rtMs)
      .bind(7, stored.response)
      .bind(8, stored.recorded)
      .step();
  t.commit();
  return {RecordOutcome::Status::Stored, std::move(stored)};
}

std::vector<StoredRecord> StudyRecords::records(const std::string& participant) const {
  checkId(path_, participant);
  Statement s(
      db_, path_,
      fmt::format("SELECT {} FROM study_records WHERE participant = ? ORDER BY trial_index", kRecordColumns).c_str());
  s.bind(1, participant);
  std::vector<StoredRecord> out;
  while (s.step()) out.push_back(readRecord(s));
  return out;
}

std::int64_t StudyRecords::nextTrial(const std::string& participant) const {
  if (!this->participant(participant))
    throw StudyError(fmt::format("{}: no participant {}", path_, quotedText(participant)));
  Statement s(db_, path_, "SELECT count(*) FROM study_records WHERE participant = ?");
  s.bind(1, participant);
  return s.step() ? s.integer(0) : 0;
}

namespace {

// Every record, by participant creation, then trial index: one SELECT, so one consistent snapshot.
template <typename Write>
void forEachRecord(sqlite3* db, const std::string& path, std::ostream& out, Write write) {
  Statement s(db, path,
              "SELECT r.participant, r.trial_index, r.kind, r.meal, r.elapsed_ms, r.rt_ms, r.response, r.recorded "
              "FROM study_records AS r JOIN study_participants AS p ON p.id = r.participant "
              "ORDER BY p.rowid, r.trial_index");
  while (s.step()) write(readRecord(s));
  out.flush();
  if (!out) throw StudyError(fmt::format("{}: writing the export failed", path));
}

}  // namespace

void StudyRecords::exportJsonLines(std::ostream& out) const {
  forEachRecord(db_, path_, out, [&](const StoredRecord& r) {
    nlohmann::ordered_json line;
    line["participant"] = r.participant;
    line["trial_index"] = r.trialIndex;
    line["kind"] = r.kind;
    line["meal"] = r.meal;
    line["elapsed_ms"] = r.elapsedMs;
    line["rt_ms"] = r.rtMs;
    line["response"] = nlohmann::ordered_json::parse(r.response);
    line["recorded"] = r.recorded;
    out << line.dump() << '\n';
  });
}

void StudyRecords::exportCsv(std::ostream& out) const {
  out << "participant,trial_index,kind,meal,elapsed_ms,rt_ms,response,recorded\r\n";
  forEachRecord(db_, path_, out, [&](const StoredRecord& r) {
    out << r.participant << ',' << r.trialIndex << ',' << r.kind << ',' << r.meal << ',' << r.elapsedMs << ',' << r.rtMs
        << ',' << csvField(r.response) << ',' << r.recorded << "\r\n";
  });
}

}  // namespace cbtl::app::study
