// HelpLayout.h — how `cbtl COMMAND --help` reads: options grouped by topic (the same option is in the same group
// in every command) and a few examples at the end, each a command that runs as shown from the repository root.
//
// Applied once by main() to every command after they are all registered, so a command only declares its options.
#pragma once

#include <CLI/CLI.hpp>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cbtl::cli {

// The topic of each option, by its long name.
inline const std::vector<std::pair<std::string, std::vector<std::string>>>& optionTopics() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> topics = {
      {"Training and evaluation",
       {"--approach", "--approaches", "--seed", "--seeds", "--steps", "--eval-every", "--eval-tasks",
        "--max-eval-steps", "--task", "--epsilon", "--replan", "--columns", "--participant-from-seed", "--jobs",
        "--csp"}},
      {"Nonstationary user", {"--nonstationary", "--shift-every", "--periodic-reset-every"}},
      {"World and simulator",
       {"--simulator", "--simulator-timeout-ms", "--observe", "--participant", "--unsatisfiable-stock", "--stdlib",
        "--solution", "--event"}},
      {"Solver", {"--max-iters", "--num-improvements", "--max-improvement-attempts", "--memory-size", "--memory"}},
      {"Text preferences (language model)",
       {"--text-backend", "--llm-base-url", "--llm-model", "--llm-timeout-ms", "--llm-attempts", "--llm-breaker",
        "--llm-retry-budget", "--llm-retry-wait-ms", "--llm-max-retry-after-ms"}},
      {"Profiles", {"--profile", "--profile-db", "--user"}},
      {"Figure",
       {"--kind", "--layout", "--metric", "--panel-title", "--label", "--marks", "--at-step", "--title", "--xlabel",
        "--ylabel", "--ymin", "--ymax", "--width", "--height"}},
      {"Sweep", {"--index", "--collect", "--emit-slurm", "--list", "--trials-per-task"}},
      {"Audit", {"--resolution", "--cap", "--program"}},
      {"Output", {"--out", "--force", "--resume", "--quiet", "--format", "--explain", "--echo", "--no-motion-record"}},
  };
  return topics;
}

// Examples per command path ("run", "simulator check"); every one runs from the repository root.
inline const std::map<std::string, std::vector<std::string>>& commandExamples() {
  static const std::map<std::string, std::vector<std::string>> examples = {
      {"run",
       {"cbtl run domains/cooking/cooking.cbtl --steps 2000 --eval-every 200 --out out/cooking-0",
        "cbtl run domains/coffee/coffee.cbtl --steps 100 --eval-every 25   # an external Python simulator",
        "cbtl run domains/cooking/cooking.cbtl --nonstationary user-reset --shift-every 1000"}},
      {"experiment",
       {"cbtl experiment domains/cooking/cooking.cbtl --approaches cbtl,no-personalization --seeds 0..4 --jobs 2 "
        "--out out/sweep"}},
      {"solve",
       {"cbtl solve domains/cooking/cooking.cbtl --seed 3 --explain",
        "cbtl solve FILE --observe obs.json --format json > solution.json"}},
      {"repl", {"cbtl repl domains/feeding/feeding.cbtl --profile-db care.sqlite --user ann"}},
      {"feedback",
       {"cbtl feedback domains/feeding/feeding.cbtl --profile ann.json --event 'dipAnswer(taterTots, hummus, "
        "bbqSauce)'"}},
      {"simulator check", {"cbtl simulator check domains/coffee/coffee.cbtl"}},
      {"simulator serve",
       {"cbtl run domains/cooking/cooking.cbtl --simulator 'cbtl simulator serve domains/cooking/cooking.cbtl'"}},
      {"render", {"cbtl render domains/feeding/feeding.xml --out feeding.png"}},
      {"audit",
       {"cbtl run domains/cleaning/cleaning.cbtl --steps 200 --eval-every 100 --out out/cleaning-0 && cbtl audit "
        "out/cleaning-0"}},
      {"plot",
       {"cbtl plot results/cooking/figure3-cooking results/robots/figure3-cleaning --panel-title Cooking --panel-title "
        "Cleaning --ymin -1 "
        "--ymax 1 --out figure3.png",
        "cbtl plot results/cooking/figure5/nonstationary=no-adapt results/cooking/figure5/nonstationary=user-reset "
        "--layout together --marks 3000,6000,9000 "
        "--out figure5.svg",
        "cbtl plot results/cooking/table1-replan results/cooking/table1-noreplan --kind bars --label 'with replanning' "
        "--label "
        "'without replanning' --out table1.pdf"}},
      {"sweep",
       {"cbtl sweep bench/sweeps/paper-cooking.json --jobs 2",
        "cbtl sweep bench/sweeps/paper-cooking.json --emit-slurm   # writes results/cooking/paper-cooking.sbatch",
        "cbtl sweep bench/sweeps/paper-cooking.json --collect"}},
      {"profile", {"cbtl profile history --db care.sqlite ann feeding"}},
      {"study", {"cbtl study simulate domains/feeding/feeding.cbtl --participants 60"}},
  };
  return examples;
}

inline void arrangeHelp(CLI::App* command, const std::string& path) {
  for (CLI::Option* option : command->get_options()) {
    for (const auto& [topic, names] : optionTopics()) {
      bool inTopic = false;
      for (const auto& name : names) inTopic = inTopic || option->check_lname(name.substr(2));
      if (inTopic) option->group(topic);
    }
  }
  if (const auto it = commandExamples().find(path); it != commandExamples().end()) {
    std::string footer = "\nExamples:\n";
    for (const auto& line : it->second) footer += "  " + line + "\n";
    command->footer(footer);
  }
  for (CLI::App* sub : command->get_subcommands([](CLI::App*) { return true; }))
    arrangeHelp(sub, path.empty() ? sub->get_name() : path + " " + sub->get_name());
}

}  // namespace cbtl::cli
