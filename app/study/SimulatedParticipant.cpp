#include "app/study/SimulatedParticipant.h"

#include "domains/feeding/FeedingUser.h"

#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <stdexcept>

namespace cbtl::app::study {

namespace {

using domains::feeding::FeedingUser;
using nlohmann::json;

// The three ideals of `person` in the meal `state` describes.
struct Ideals {
  std::string dip, signal, verbosity;
};

Ideals idealsIn(const FeedingUser& person, const json& state) {
  const json& c = state.at("context");
  const std::string setting = c.at("setting");
  return {person.idealDip(c.at("food"), setting, c.at("sauces").get<std::vector<std::string>>()),
          person.idealSignal(setting), person.idealVerbosity(setting)};
}

int metBy(const json& option, const Ideals& ideals) {
  if (!option.value("solved", false)) return 0;
  return (option.at("dip") == ideals.dip) + (option.at("signal") == ideals.signal) +
         (option.at("verbosity") == ideals.verbosity);
}

class Participant {
 public:
  Participant(const std::string& host, int port, std::string id, std::uint64_t person, std::string key)
      : client_(host, port),
        id_(std::move(id)),
        key_(std::move(key)),
        n_(person),
        person_(FeedingUser::participant(person)) {
    client_.set_read_timeout(std::chrono::seconds(300));
    client_.set_connection_timeout(std::chrono::seconds(10));
  }

  // Begins (or, with a key, continues); keeps the key a first begin issues.
  json begin() {
    json state = request("POST", "/api/participants/" + id_, "");
    if (state.contains("key") && state["key"].is_string()) key_ = state["key"].get<std::string>();
    return state;
  }
  const std::string& key() const { return key_; }

  int take() {
    json state = begin();
    int answered = 0;
    std::int64_t elapsed = 0;
    while (state.at("page") != "done") {
      const json response = answer(state);
      const std::int64_t rt = 1000 + 500 * static_cast<std::int64_t>(response.dump().size() % 7);
      elapsed += rt;
      const json record = {{"trial_index", state.at("next_trial")},
                           {"kind", state.at("page")},
                           {"meal", state.at("meal")},
                           {"elapsed_ms", elapsed},
                           {"rt_ms", rt},
                           {"response", response}};
      state = request("POST", "/api/participants/" + id_ + "/records", record.dump()).at("state");
      ++answered;
    }
    return answered;
  }

 private:
  json request(const char* method, const std::string& path, const std::string& body) {
    httplib::Headers headers;
    if (!key_.empty()) headers.emplace("Authorization", "Bearer " + key_);
    auto res = std::string(method) == "POST" ? client_.Post(path, headers, body, "application/json")
                                             : client_.Get(path, headers);
    if (!res)
      throw std::runtime_error(
          fmt::format("participant {}: {} {}: {}", id_, method, path, httplib::to_string(res.error())));
    const json j = json::parse(res->body, nullptr, false);
    if (res->status != 200)
      throw std::runtime_error(fmt::format("participant {}: {} {}: HTTP {}: {}", id_, method, path, res->status,
                                           j.is_object() && j.contains("error") ? j["error"].dump() : res->body));
    return j;
  }

  json answer(const json& state) {
    const std::string page = state.at("page");
    if (page == "consent") return {{"agree", true}};
    if (page == "demographics") {
      static const char* genders[] = {"male", "female", "male", "female", "non-binary", "prefer-not-to-say"};
      return {{"age", 19 + static_cast<int>((n_ * 37) % 50)},
              {"gender", genders[n_ % 6]},
              {"gender_other", ""},
              {"robot_experience", n_ % 2 == 0},
              {"fed_experience", n_ % 5 == 0}};
    }
    if (page == "rating") {
      const Ideals ideals = idealsIn(person_, state);
      const int lead = metBy(state.at("options").at(0), ideals) - metBy(state.at("options").at(1), ideals);
      return {{"likert", lead >= 2 ? 1 : lead == 1 ? 2 : lead == 0 ? 3 : lead == -1 ? 4 : 5}};
    }
    if (page == "answers") {
      const Ideals ideals = idealsIn(person_, state);
      json blocked = json::array();
      for (const auto& url : state.at("views")) {
        std::string measure = url.get<std::string>();
        measure.replace(measure.size() - 4, 4, ".json");
        blocked.push_back(person_.viewBlocked(request("GET", measure, "").at("occlusion").get<double>()));
      }
      return {{"dip", ideals.dip}, {"signal", ideals.signal}, {"verbosity", ideals.verbosity}, {"blocked", blocked}};
    }
    return {{"comments", ""}};
  }

  httplib::Client client_;
  std::string id_;
  std::string key_;
  std::uint64_t n_;
  FeedingUser person_;
};

}  // namespace

int takeStudy(const std::string& host, int port, const std::string& id, std::uint64_t person, const std::string& key) {
  return Participant(host, port, id, person, key).take();
}

std::string beginStudy(const std::string& host, int port, const std::string& id) {
  Participant p(host, port, id, 0, "");
  p.begin();
  return p.key();
}

}  // namespace cbtl::app::study
