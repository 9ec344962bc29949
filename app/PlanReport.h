// PlanReport.h — how a solved (or unsolved) request reads to a person: the task's assignment, the action calls,
// which constraints rejected candidates and where they are declared, the observation the CSP was solved against,
// and the personalized constraints at an assignment. `cbtl solve` and the REPL print the same text.
//
// Every function writes to `out` and nothing else; none throws for a plan that failed (it prints why).
#pragma once

#include "runtime/approach/Planner.h"
#include "runtime/sim/DomainSimulator.h"

#include <cstdio>
#include <string>
#include <vector>

namespace cbtl::app {

// "movePot(pot1, (2.9, 4.2))": names as they are, numbers with 6 significant digits.
std::string renderCall(const sim::ActionCall& call);
// "name(arg, ...)" for a feedback event, in the same notation the REPL reads.
// `graph`, when given, supplies the event's declared parameter types, so that a bool reads back as true/false (a
// simulator sends it as a number) and the line can be pasted into `feedback` as it is.
std::string renderEvent(const sim::FeedbackEvent& event, const ir::ConstraintGraph* graph = nullptr);

// "task T: Solved", then (when solved) every task variable and the plan's calls.
void printSolution(std::FILE* out, const approach::Plan& plan);

// Per solve that ran (dry-run tiers, the failed full solve, the last): its outcome, iterations and the
// constraints ordered by how many candidates each was the first to reject, with their declarations.
void printSolveStatistics(std::FILE* out, const approach::Plan& plan);

// One observed value as printObservation shows it (a set as "{a, b}" of the members it holds).
std::string renderObserved(const rt::Program& program, const rt::ValueType& type, const double* value);

// Every observation of the program as the CSP saw it (a set as the members it holds); nothing without any.
void printObservation(std::FILE* out, const rt::Program& program, const std::vector<double>& observation);

// The personalized constraints of the plan's CSP at `assignment`: holds / fails / n/a, P(holds) against the
// generator's accept threshold, entropy (bits), and each text factor's subject, context and theta.
// `heading` opens the table ("personalized constraints at the solution").
void printPersonal(std::FILE* out, const approach::Plan& plan, const std::vector<double>& assignment,
                   const std::string& heading = "personalized constraints at the solution");

// The independent re-check's verdict line ("re-check: ... all hold"); nothing when the plan was not re-checked.
void printRecheck(std::FILE* out, const approach::Plan& plan);

}  // namespace cbtl::app
