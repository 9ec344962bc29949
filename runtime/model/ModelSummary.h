// ModelSummary.h — what a learned model believes about the person, in words, for people reading a profile (the
// REPL's `profile show`): per generator and key, each factor's belief with the evidence it rests on, and
// "unknown (no data)" where there is none, never a prior presented as knowledge.
#pragma once

#include "runtime/model/Factor.h"
#include "runtime/model/UserModel.h"

#include <string>

namespace cbtl::model {

// One factor's belief in a line, e.g. "liked from 66.1 to 73.8 (the bounds between 65.9 and 66.1, and 73.8 and
// 74.2); 100 answers" or "unknown (no data): the declared range 55 to 90".
std::string describeFactor(const Factor& factor);

// The whole model: a header line, then per generator its keys (the prior's line when it has none), indented.
std::string describeModel(const UserModel& model);

}  // namespace cbtl::model
