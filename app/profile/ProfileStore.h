// ProfileStore.h — the per-user profiles that last: a SQLite file holding users, domains, every feedback event
// with its provenance (time, source, the solution it was about) and every version of the learned model, so a model
// can be audited and rolled back (`cbtl profile ...`, `cbtl repl --profile-db`, `cbtl feedback --profile-db`,
// `cbtl run --profile-db`).
//
// The model is the profile JSON (runtime/model/UserModel.h, format "cbtl-profile"), stored byte for byte as given:
// the store checks that it is a JSON object and nothing more (the program that reads it validates it). Versions
// of a (user, domain) count from 1; a rollback or an undo is a new version holding an older model, never a deletion.
//
// Durability and sharing: WAL journal with synchronous=FULL, so a write that returned survives kill -9 and power
// loss; every write is one BEGIN IMMEDIATE transaction (the events and the version that learned them commit
// together or not at all); several processes may use one store, a writer waiting up to the busy timeout for
// another's transaction and then failing with StoreError ("busy"), never hanging.
//
// Times are UTC, ISO 8601 with milliseconds ("2026-12-05T04:55:01.123Z").
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

struct sqlite3;

namespace cbtl::app::profile {

enum class EventSource { Simulator, Repl, Command, Study };
const char* sourceName(EventSource source);  // "simulator", "repl", "command", "study"
std::optional<EventSource> sourceNamed(const std::string& name);

// Every failure: a file that is not a store, bad names or model, a busy or broken database. The message starts
// with the store's path.
struct StoreError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct NewEvent {
  EventSource source = EventSource::Command;
  std::string event;     // as a person types it: "dipAnswer(frenchFries, ketchup, bbqSauce)"
  std::string solution;  // the cbtl-solution JSON it was about, or empty
};

struct StoredEvent {
  std::int64_t id = 0;  // unique in the store, increasing in the order of recording
  std::string time;
  EventSource source = EventSource::Command;
  std::string event, solution;
  std::int64_t version = 0;  // the model version that learned it
};

struct ModelVersion {
  std::int64_t version = 0;
  std::string time;
  std::string reason;  // "learn", "import of p.json", "rollback to 3", "undo of version 5", ...
  std::int64_t labels = 0;
  std::string model;
};

// What one learning step writes: the events it learned (possibly none) and the model it made of them.
struct LearningStep {
  std::vector<NewEvent> events;
  std::string model;
  std::int64_t labels = 0;
  std::string reason;
};

struct ProfileSummary {
  std::string user, domain;
  std::int64_t events = 0, versions = 0, head = 0;
  std::string updated;  // the time of the head version
};

class ProfileStore {
 public:
  // Opens the store at `path`, creating it when missing and `create`. Throws StoreError for a missing file (without
  // `create`), a file that is not SQLite, a SQLite file that is not a CBTL profile store, or a newer schema.
  explicit ProfileStore(const std::string& path, bool create = true, int busyTimeoutMs = 10000);
  ~ProfileStore();
  ProfileStore(const ProfileStore&) = delete;
  ProfileStore& operator=(const ProfileStore&) = delete;
  ProfileStore(ProfileStore&& other) noexcept;
  ProfileStore& operator=(ProfileStore&& other) noexcept;

  const std::string& path() const { return path_; }

  // One learning step, atomically: the events (possibly none) and the new model version that learned them. Creates
  // the user and the domain on first use. Returns the new version's number. Names are 1..200 bytes without control
  // characters; `model` must be a JSON object; otherwise StoreError and nothing is written.
  //
  // `learnedFrom` is the version the model was learned from (0: from the prior, no stored profile). When given and
  // the head is another version by the time of writing (another process stored learning in between), StoreError
  // and nothing is written: storing would silently drop the other process's learning (a lost update).
  std::int64_t recordLearning(const std::string& user, const std::string& domain, const std::vector<NewEvent>& events,
                              const std::string& model, std::int64_t labels, const std::string& reason,
                              std::optional<std::int64_t> learnedFrom = std::nullopt);
  // Read-modify-write in one write transaction: `learn` gets the head (nullopt for a profile not stored yet) and
  // returns the step made from it, which is stored as the next version. No other writer can store between the
  // read and the write (they wait, up to the busy timeout, for this one), so concurrent learners never lose each
  // other's learning. `learn` runs while the store is locked for writing: it should take milliseconds, not a
  // language model's seconds; an exception from it writes nothing and propagates.
  std::int64_t learnOnHead(const std::string& user, const std::string& domain,
                           const std::function<LearningStep(const std::optional<ModelVersion>& head)>& learn);
  // A new head version holding version `version`'s model (reason "rollback to N"). StoreError if there is none.
  std::int64_t rollback(const std::string& user, const std::string& domain, std::int64_t version);

  std::vector<ProfileSummary> list() const;  // by user, then domain
  std::optional<ModelVersion> head(const std::string& user, const std::string& domain) const;
  std::optional<ModelVersion> version(const std::string& user, const std::string& domain, std::int64_t v) const;
  std::vector<ModelVersion> versions(const std::string& user, const std::string& domain) const;  // oldest first
  std::vector<StoredEvent> events(const std::string& user, const std::string& domain) const;     // oldest first

 private:
  // Inside a write transaction: checks the store's integrity, then writes the step as the next version.
  std::int64_t writeVersion(const std::string& user, const std::string& domain, const LearningStep& step,
                            std::optional<std::int64_t> learnedFrom);

  std::string path_;
  sqlite3* db_ = nullptr;
  bool integrityChecked_ = false;  // by the first write of this connection
};

}  // namespace cbtl::app::profile
