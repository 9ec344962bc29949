#include "app/study/ParticipantAccess.h"

#include <fmt/format.h>
#include <openssl/crypto.h>
#include <openssl/sha.h>
#include <nlohmann/json.hpp>

#include <sys/random.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace cbtl::app::study {

namespace {

constexpr const char* kNeedsKey =
    "this page needs the participant's key: open the link you were given when you began (it ends in #key=...), in "
    "the browser you began in";

std::string hex(const unsigned char* bytes, std::size_t n) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  out.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    out += digits[bytes[i] >> 4];
    out += digits[bytes[i] & 15];
  }
  return out;
}

HttpReply tooFast(int seconds) {
  HttpReply r = errorReply(429, fmt::format("the study is admitting many people at once: try again in {} s", seconds));
  r.retryAfterSeconds = seconds;
  return r;
}

}  // namespace

std::string newParticipantKey() {
  std::array<unsigned char, 32> bytes{};
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("no random bytes for a participant key: ") + std::strerror(errno));
    }
    got += static_cast<std::size_t>(n);
  }
  return hex(bytes.data(), bytes.size());
}

std::string participantKeyHash(const std::string& key) {
  std::array<unsigned char, SHA256_DIGEST_LENGTH> digest{};
  SHA256(reinterpret_cast<const unsigned char*>(key.data()), key.size(), digest.data());
  return hex(digest.data(), digest.size());
}

ParticipantAccess::ParticipantAccess(StudyApi& study, const std::string& databasePath, AdmissionOptions admission)
    : study_(study), keys_(databasePath), admission_(admission) {}

ParticipantAccess::KeyCheck ParticipantAccess::check(const std::string& participant, const std::string& key) {
  std::optional<std::string> stored;
  {
    std::lock_guard<std::mutex> lock(dbMutex_);
    stored = keys_.keyHash(participant);
  }
  if (!stored) return KeyCheck::NoneIssued;
  // Compared in constant time, hash against hash: the time taken says nothing of how much of a guess was right.
  const std::string given = participantKeyHash(key);
  return !key.empty() && given.size() == stored->size() &&
                 CRYPTO_memcmp(given.data(), stored->data(), given.size()) == 0
             ? KeyCheck::Valid
             : KeyCheck::Wrong;
}

HttpReply ParticipantAccess::withKey(const std::string& participant, const std::string& key,
                                     const std::function<HttpReply()>& answer) {
  if (!isParticipantId(participant)) return answer();  // the study explains an invalid id (400)
  if (check(participant, key) != KeyCheck::Valid) return errorReply(403, kNeedsKey);
  return answer();
}

HttpReply ParticipantAccess::begin(const std::string& participant, const std::string& key) {
  if (!isParticipantId(participant)) return study_.begin(participant);
  const KeyCheck k = check(participant, key);
  if (k == KeyCheck::Valid) return study_.begin(participant);
  return admitNew(participant);
}

HttpReply ParticipantAccess::admitNew(const std::string& participant) {
  std::int64_t count = 0;
  bool known = false;
  bool keyed = false;
  try {
    std::lock_guard<std::mutex> lock(dbMutex_);
    count = keys_.participantCount();
    known = keys_.participant(participant).has_value();
    keyed = keys_.keyHash(participant).has_value();
  } catch (const StudyError& e) {
    return errorReply(503, e.what());
  }
  // Counted before anything is said about the id, so that trying ids is as slow as joining.
  const AdmissionLimit::Decision d = admission_.admit(now_(), known ? 0 : count);
  if (d.verdict == AdmissionLimit::Verdict::TooFast) return tooFast(d.retryAfterSeconds);
  if (keyed)
    return errorReply(403,
                      "this participant has begun already: continue from the link you were given when you began (it "
                      "ends in #key=...), in the browser you began in");
  if (d.verdict == AdmissionLimit::Verdict::Full)
    return errorReply(403, "the study has all the participants it needs: thank you for your interest");
  HttpReply reply = study_.begin(participant);
  if (reply.status != 200) return reply;
  const std::string issued = newParticipantKey();
  bool claimed = false;
  try {
    std::lock_guard<std::mutex> lock(dbMutex_);
    claimed = keys_.claimKey(participant, participantKeyHash(issued));
  } catch (const StudyError& e) {
    return errorReply(503, e.what());
  }
  // Two first begins of one id at once: the other claimed it.
  if (!claimed)
    return errorReply(403, "this participant has begun already, in another window: continue from that window's link");
  nlohmann::json state = nlohmann::json::parse(reply.body, nullptr, false);
  if (!state.is_object()) return errorReply(500, "the study's state is not a JSON object");
  state["key"] = issued;
  reply.body = state.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return reply;
}

HttpReply ParticipantAccess::state(const std::string& participant, const std::string& key) {
  return withKey(participant, key, [&] { return study_.state(participant); });
}

HttpReply ParticipantAccess::record(const std::string& participant, const std::string& key, const std::string& body) {
  return withKey(participant, key, [&] { return study_.record(participant, body); });
}

HttpReply ParticipantAccess::view(const std::string& participant, const std::string& key, int meal, int picture) {
  return withKey(participant, key, [&] { return study_.view(participant, meal, picture); });
}

HttpReply ParticipantAccess::viewMeasure(const std::string& participant, const std::string& key, int meal,
                                         int picture) {
  return withKey(participant, key, [&] { return study_.viewMeasure(participant, meal, picture); });
}

}  // namespace cbtl::app::study
