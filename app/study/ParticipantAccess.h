// ParticipantAccess.h — who may act as a participant: the capability check in front of the study (StudyApi).
//
// Keys: a participant's first begin issues a key, 256 random bits as 64 hex digits, sent once in that reply
// ("key"); the page keeps it in the participant's link (/p/<id>#key=<key>: a fragment, so never sent to a server or
// written in its logs) and in the browser's storage, and sends it with every request (Authorization: Bearer <key>).
// The database keeps only its SHA-256. Every request about a participant needs their key, except the first begin:
// a wrong or missing key is 403 with one message whether the participant exists or not, so ids cannot be found by
// trying them. A begin without a key for a participant who has one is 403 too (they continue from their link).
// Participants of a database from before keys hold none; the first begin of each issues one.
//
// Admission: every begin without a key is counted by an AdmissionLimit (429 with Retry-After when too fast, 403
// when the study is full), which bounds both new participants and the trying of ids.
//
// Thread-safe: the study is (StudyApi), the keys are read and claimed in single SQLite statements, and the limit
// has its own lock.
#pragma once

#include "app/study/AdmissionLimit.h"
#include "app/study/StudyHttpServer.h"
#include "app/study/StudyRecords.h"

#include <functional>
#include <mutex>
#include <string>

namespace cbtl::app::study {

// A new key: 64 hex digits from the kernel's random source. Throws std::runtime_error when it has none.
std::string newParticipantKey();
// The hex SHA-256 of a key, as stored.
std::string participantKeyHash(const std::string& key);

class ParticipantAccess {
 public:
  // `study` answers for participants whose key checked; `databasePath` is the study's database (its own
  // connection, for the keys). Throws StudyError when the database cannot be opened.
  ParticipantAccess(StudyApi& study, const std::string& databasePath, AdmissionOptions admission);

  // `key`: the key the request carried ("" for none).
  HttpReply begin(const std::string& participant, const std::string& key);
  HttpReply state(const std::string& participant, const std::string& key);
  HttpReply record(const std::string& participant, const std::string& key, const std::string& body);
  HttpReply view(const std::string& participant, const std::string& key, int meal, int picture);
  HttpReply viewMeasure(const std::string& participant, const std::string& key, int meal, int picture);

  // For tests: the clock the admission limit reads.
  void setClock(std::function<std::chrono::steady_clock::time_point()> now) { now_ = std::move(now); }

 private:
  enum class KeyCheck { Valid, Wrong, NoneIssued };
  KeyCheck check(const std::string& participant, const std::string& key);
  // The study's reply, or 403 when the key does not open the participant's records.
  HttpReply withKey(const std::string& participant, const std::string& key, const std::function<HttpReply()>& answer);
  HttpReply admitNew(const std::string& participant);

  StudyApi& study_;
  std::mutex dbMutex_;
  StudyRecords keys_;
  AdmissionLimit admission_;
  std::function<std::chrono::steady_clock::time_point()> now_ = [] { return std::chrono::steady_clock::now(); };
};

}  // namespace cbtl::app::study
