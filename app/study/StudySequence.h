// StudySequence.h — the fixed sequence of pages every participant of the web study answers, one record each
// (docs/study-api.md): consent (trial 0), demographics (1), then per meal m = 1..kMeals a rating (2m) and an
// answers page (2m + 1), complete (2 kMeals + 2), and from there on "done" (nothing left to answer). The server
// serves it (StudyPages.h) and the analysis checks stored records against it (StudyAnalysis.h).
#pragma once

#include "app/study/StudyRecords.h"

#include <cstdint>
#include <string>

namespace cbtl::app::study {

struct StudyPage {
  std::string kind;
  int meal = 0;  // 1..kMeals, or 0 for a page about no meal
};

constexpr std::int64_t kStudyPages = 2 * kMeals + 3;  // the pages with a record: 13

// The page at `trialIndex` (>= kStudyPages: "done"; < 0: consent).
inline StudyPage pageOfTrial(std::int64_t trialIndex) {
  if (trialIndex <= 0) return {"consent", 0};
  if (trialIndex == 1) return {"demographics", 0};
  if (trialIndex < kStudyPages - 1)
    return {trialIndex % 2 == 0 ? "rating" : "answers", static_cast<int>((trialIndex - 2) / 2 + 1)};
  if (trialIndex == kStudyPages - 1) return {"complete", 0};
  return {"done", 0};
}

}  // namespace cbtl::app::study
