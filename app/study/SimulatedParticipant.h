// SimulatedParticipant.h — a simulated person (domains/feeding/FeedingUser.h, participant n) taking the web study
// through its HTTP API exactly as the pages do (docs/study-api.md), so that `cbtl study simulate` exercises the
// server, the records and the analysis end to end.
//
// How the person answers each page (their hidden preferences decide; nothing is random):
// - consent: agrees. demographics: an age of 19..68, a gender, the two experiences, all drawn from n alone (a
//   stand-in: nothing is analysed of them but their counts).
// - rating: counts, for Option A and Option B, how many of the dip, ready signal and verbosity are the ones they
//   want in this meal's setting (an option without a plan meets none); prefers the option that meets more,
//   strongly when by two or more: Likert 1 / 2 / 3 / 4 / 5 for A ahead by >= 2 / 1 / tie / B ahead by 1 / >= 2.
// - answers: their ideal dip (among the meal's sauces), signal and verbosity; a picture is "blocked" when its
//   occlusion score (the picture's measure, views/<meal>/<k>.json) reaches their threshold.
// - complete: no comments.
// Times: each page's rt_ms is a made-up 1 to 4 s (from the length of the answer), elapsed_ms their running sum, so
// that the records have the browser's columns; they say nothing about people.
#pragma once

#include <cstdint>
#include <string>

namespace cbtl::app::study {

// Takes the study as participant id `id`, person `person`, against the server at http://host:port, with the
// participant's key (ParticipantAccess.h) when they have begun already ("" to begin). Returns the number of pages
// answered (13 for a complete study). Throws std::runtime_error naming the page and the server's error when a
// request fails.
int takeStudy(const std::string& host, int port, const std::string& id, std::uint64_t person,
              const std::string& key = "");

// Only begins participant `id` (the server numbers participants in the order they begin, so a simulation that runs
// participants in parallel begins them all first, in order) and returns the key it was issued. Throws as takeStudy.
std::string beginStudy(const std::string& host, int port, const std::string& id);

}  // namespace cbtl::app::study
