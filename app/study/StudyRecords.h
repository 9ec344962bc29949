// StudyRecords.h — what the web study (`cbtl study serve`) keeps of its sessions: one participant per session and,
// jsPsych-style, one record per page the participant answered, so the paper's analysis (meal ratings of CBTL vs
// the baseline, the questionnaires) can be rebuilt from the database alone (exportJsonLines, exportCsv).
//
// One file with the profiles: the study keeps each participant's learned model in a ProfileStore
// (app/profile/ProfileStore.h, user = participant id) in the same SQLite file. Opening StudyRecords first opens it
// as a ProfileStore, so a fresh file gets the profile schema and marks and any file that is not a profile store is
// refused (StudyError); then it adds its own tables, all named study_*. The study's schema version lives in its own
// table study_meta, never in PRAGMA user_version or application_id, which are ProfileStore's. Either may open the
// file first, in any order, any number of times.
//
// Participants: ids come from URLs (survey recruiters pass them), so every function taking one accepts only 1..64
// characters of [A-Za-z0-9_.-] and otherwise throws StudyError naming it (quoted, control characters escaped,
// long ones cut). begin() is idempotent: a participant who reloads the page continues the same session, whatever
// seed and options the reload passes. The options are a JSON object, stored byte for byte and opaque here.
//
// Records: trial indices of a participant count 0, 1, 2, ... without gaps; the next one is the count of their
// records. Re-sending a stored record (same index, kind, meal and response as JSON values) is a replay, answered
// with the stored record and writing nothing, so a browser retrying a request never fails; the stored elapsed and
// reaction times stay. Anything else out of order is a StudyError. A completed participant takes no new records
// (replays still succeed). `elapsed_ms` (since the session began) and `rt_ms` (the reaction time on that page) are
// milliseconds as the browser measured them, >= 0; the response is any JSON value, stored as compact JSON in the
// order the browser sent its keys.
//
// Durability and sharing, as ProfileStore: WAL journal with synchronous=FULL, so a write that returned survives
// kill -9 and power loss; every write is one BEGIN IMMEDIATE transaction; a writer waits up to the busy timeout for
// another process's transaction, then fails with StudyError ("busy"). Times are the server's, UTC, ISO 8601 with
// milliseconds ("2026-12-05T04:55:01.123Z"). Every error message starts with the file's path.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

struct sqlite3;

namespace cbtl::app::study {

struct StudyError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr int kMeals = 5;  // a record's meal is 1..kMeals, or 0 for a page about no meal

// 1..64 characters of [A-Za-z0-9_.-].
bool isParticipantId(const std::string& id);

// Text as it may appear in a message: quoted, with quotes, backslashes and anything outside printable ASCII escaped,
// and cut when long, since it may be whatever a URL held.
std::string quotedText(const std::string& text);

struct Participant {
  std::string id;
  std::string created;
  std::uint64_t seed = 0;
  std::string options;                   // a JSON object, as given to begin()
  std::optional<std::string> completed;  // the time of complete()
};

struct NewRecord {
  std::string participant;
  std::int64_t trialIndex = 0;
  std::string kind;  // 1..40 characters of [a-z_-]: "consent", "meal_rating", ...
  int meal = 0;
  std::int64_t elapsedMs = 0;
  std::int64_t rtMs = 0;
  std::string response;  // JSON text, any value
};

struct StoredRecord {
  std::string participant;
  std::int64_t trialIndex = 0;
  std::string kind;
  int meal = 0;
  std::int64_t elapsedMs = 0;
  std::int64_t rtMs = 0;
  std::string response;  // compact JSON
  std::string recorded;  // server time
};

struct RecordOutcome {
  enum class Status { Stored, Replayed };
  Status status = Status::Stored;
  StoredRecord record;  // as stored: for a replay, the first sending's
};

class StudyRecords {
 public:
  // Opens the study database at `path`, creating it when missing and `create`. Throws StudyError for a missing file
  // (without `create`), a file that is not a profile store, or a newer study or profile schema.
  explicit StudyRecords(const std::string& path, bool create = true, int busyTimeoutMs = 10000);
  ~StudyRecords();
  StudyRecords(const StudyRecords&) = delete;
  StudyRecords& operator=(const StudyRecords&) = delete;
  StudyRecords(StudyRecords&& other) noexcept;
  StudyRecords& operator=(StudyRecords&& other) noexcept;

  const std::string& path() const { return path_; }

  // Creates the participant when missing; returns the stored one, unchanged, otherwise. `optionsJson` must be a
  // JSON object (checked even when the participant exists).
  Participant begin(const std::string& id, std::uint64_t seed, const std::string& optionsJson);
  std::optional<Participant> participant(const std::string& id) const;
  std::vector<Participant> participants() const;  // in the order begin() created them
  std::int64_t participantCount() const;

  // Participants' keys (ParticipantAccess.h): only a hash of each is stored, so the file alone does not let anyone
  // act as a participant. claimKey stores `keyHash` for a participant who has none and returns true; false, writing
  // nothing, when they have one (the first claim wins). Ids need not be participants (yet).
  bool claimKey(const std::string& id, const std::string& keyHash);
  std::optional<std::string> keyHash(const std::string& id) const;
  // Marks the participant completed; completing again keeps the first time. StudyError for an unknown one.
  void complete(const std::string& id);

  // Stores the participant's next record or recognizes a replay of a stored one (see the top of this file).
  RecordOutcome record(const NewRecord& record);
  std::vector<StoredRecord> records(const std::string& participant) const;  // by trial index; none if unknown
  std::int64_t nextTrial(const std::string& participant) const;             // StudyError if unknown

  // Every record of every participant, by participant creation, then trial index. JSON Lines: one object a line
  // with participant, trial_index, kind, meal, elapsed_ms, rt_ms, response (a JSON value), recorded. CSV (RFC 4180:
  // a header row, CRLF line ends, fields quoted when they hold a comma, quote or line break): the same columns, the
  // response as its compact JSON text. StudyError if the stream fails.
  void exportJsonLines(std::ostream& out) const;
  void exportCsv(std::ostream& out) const;

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

}  // namespace cbtl::app::study
