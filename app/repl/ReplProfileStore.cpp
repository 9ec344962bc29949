// The REPL's use of the profile store (ReplConfig::store): which profile a loaded program starts from and how every
// change of the model becomes a stored version. Kept apart from ReplSession.cpp, which works without a store.
#include "app/PlanReport.h"
#include "app/SolutionJson.h"
#include "app/repl/ReplSession.h"

#include <fmt/format.h>

namespace cbtl::app::repl {

void ReplSession::loadStoredProfile() {
  if (!config_.store) return;
  const std::string& domain = lp_->graph().domain;
  const std::optional<profile::ModelVersion> head = config_.store->head(config_.user, domain);
  storedVersion_ = head ? head->version : 0;
  if (!head) {
    fmt::print(out_, "profile store {}: no {} profile of '{}' yet (the first learn stores version 1)\n",
               config_.store->path(), domain, config_.user);
    return;
  }
  user_->fromJson(head->model, fmt::format("{} ({}'s {} profile, version {})", config_.store->path(), config_.user,
                                           domain, head->version));
  fmt::print(out_, "profile store {}: {}'s {} profile, version {} ({} labels)\n", config_.store->path(), config_.user,
             domain, head->version, user_->dataCount());
}

std::int64_t ReplSession::storeModel(const std::vector<PendingEvent>& events, const std::string& reason) {
  if (!config_.store) return 0;
  // The solution the events were about, for the audit trail (a plan only exists when they followed a solve).
  const std::string solution = plan_ && plan_->ok ? solutionJson(*plan_, planObservation_) : std::string();
  std::vector<profile::NewEvent> stored;
  for (const auto& e : events) {
    const profile::EventSource source =
        e.source == "simulated user" ? profile::EventSource::Simulator : profile::EventSource::Repl;
    stored.push_back({source, renderEvent(e.event, &lp_->graph()), solution});
  }
  storedVersion_ = config_.store->recordLearning(config_.user, lp_->graph().domain, stored, user_->toJson(),
                                                 static_cast<std::int64_t>(user_->dataCount()), reason, storedVersion_);
  return storedVersion_;
}

std::string ReplSession::storedNote(std::int64_t version) {
  return version > 0 ? fmt::format(" (stored as version {})", version) : std::string();
}

}  // namespace cbtl::app::repl
