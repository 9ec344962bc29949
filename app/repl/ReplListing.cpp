// The REPL's read-only commands (help, list, show) and completion: what the loaded program declares, by name.
#include "app/PlanReport.h"
#include "app/repl/ReplSession.h"
#include "app/repl/ValueSyntax.h"
#include "ir/GraphPrinter.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

namespace cbtl::app::repl {

namespace {

std::string spanText(const rt::Program&, const ir::Span& span) { return rt::Program::where(span); }

const std::vector<std::string> kListKinds = {"variables", "constraints",  "personal", "skills",
                                             "tasks",     "observations", "events"};
const std::vector<std::string> kShowKinds = {"observations", "plan", "feedback", "profile"};
const std::vector<std::string> kSolveModes = {"exploit", "explore", "hard", "--replan"};

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

// Files and folders that complete `prefix` (a path as typed so far).
std::vector<std::string> pathsStartingWith(const std::string& prefix) {
  namespace fs = std::filesystem;
  const auto slash = prefix.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : prefix.substr(0, slash + 1);
  const std::string head = slash == std::string::npos ? "" : prefix.substr(0, slash + 1);
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = head + entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    out.push_back(entry.is_directory(ec) ? name + "/" : name);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

const std::vector<ReplSession::CommandInfo>& ReplSession::commands() {
  static const std::vector<CommandInfo> list = {
      {"help", "[COMMAND]", "the commands, or one command's use"},
      {"load", "FILE", "compile and load a .cbtl file (or an emitted graph); diagnostics as cbtlc prints them"},
      {"reload", "", "load the same file again, keeping what was learned when it still fits"},
      {"list", "variables|constraints|personal|skills|tasks|observations|events", "what the program declares"},
      {"show", "observations|plan|feedback|profile", "the current observation, plan, queued feedback or model"},
      {"observe", "NAME = VALUE | file PATH | simulator [SEED]",
       "set one observation, those of a JSON file, or take them all from a new world"},
      {"solve", "[TASK] [exploit|explore|hard] [--replan]",
       "solve a task: hard + personalized constraints (exploit, the default), hard only maximizing entropy "
       "(explore), or hard only"},
      {"explain", "", "the last solve: rejections per constraint, the observation, P(holds) per personalized instance"},
      {"why-not", "VARIABLE = VALUE", "which constraints the last solution would break with that value"},
      {"act", "", "carry out the last plan in the domain simulator; its user's feedback is queued"},
      {"feedback", "EVENT(ARGS...)", "queue a feedback event, checked against its declaration (alone: the queue)"},
      {"learn", "", "apply the queued feedback to the user model"},
      {"profile", "show [json] | save FILE | load FILE",
       "what the model believes about the person, per generator, with its evidence (json: the profile file)"},
      {"undo", "", "drop the last queued event, or else undo the last learn or profile load"},
      {"reset", "", "the prior user model, a fresh solver and a fresh world"},
      {":eval", "EXPR",
       "evaluate an expression at the last solution (or the initial values): :eval distance(platePos, plateXY)"},
      {"quit", "", "end the session (also exit, Ctrl-D)"},
  };
  return list;
}

bool ReplSession::cmdHelp(const std::string& args) {
  const auto& list = commands();
  if (!args.empty()) {
    const auto it = std::find_if(list.begin(), list.end(), [&](const CommandInfo& c) { return c.name == args; });
    if (it == list.end()) return fail(fmt::format("no command '{}' (help lists them)", args));
    fmt::print(out_, "{} {}\n  {}\n", it->name, it->synopsis, it->summary);
    return true;
  }
  for (const auto& c : list) fmt::print(out_, "  {:<10} {:<44} {}\n", c.name, c.synopsis, c.summary);
  fmt::print(out_,
             "Values: 1.5, true, ketchup (or dips.ketchup), \"a text\", (x, y, yaw), {{a, b}}. A line ending in \\ or "
             "with an open bracket continues on the next.\n");
  return true;
}

bool ReplSession::cmdList(const std::string& args) {
  if (!requireProgram()) return false;
  if (args == "variables" || args == "vars")
    listVariables();
  else if (args == "constraints")
    listConstraints();
  else if (args == "personal" || args == "generators")
    listPersonal();
  else if (args == "skills")
    listSkills();
  else if (args == "tasks")
    listTasks();
  else if (args == "observations")
    listObservations();
  else if (args == "events" || args == "feedback")
    listEvents();
  else {
    std::string kinds;
    for (const auto& k : kListKinds) kinds += (kinds.empty() ? "" : ", ") + k;
    return fail(fmt::format("list what? ({})", kinds));
  }
  return true;
}

bool ReplSession::cmdShow(const std::string& args) {
  if (!requireProgram()) return false;
  if (args == "observations") {
    printObservation(out_, lp_->program(), observation_);
    if (!typedObservations_.empty()) {
      std::string typed;
      for (const auto& [name, text] : typedObservations_) typed += (typed.empty() ? "" : ", ") + name;
      fmt::print(out_, "set by hand: {}\n", typed);
    }
    return true;
  }
  if (args == "plan") {
    if (!plan_) return fail("no plan: solve first");
    printSolution(out_, *plan_);
    return true;
  }
  if (args == "feedback") {
    showPending();
    return true;
  }
  if (args == "profile") return cmdProfile("show");
  return fail("show observations|plan|feedback|profile");
}

void ReplSession::showPending() const {
  if (pending_.empty()) {
    fmt::print(out_, "no feedback queued ({} learns so far)\n", learned_.size());
    return;
  }
  fmt::print(out_, "queued feedback ({}):\n", pending_.size());
  for (const auto& p : pending_) fmt::print(out_, "  {}  [{}]\n", renderEvent(p.event, &lp_->graph()), p.source);
}

void ReplSession::listVariables() const {
  const auto& g = lp_->graph();
  for (const auto& v : g.variables)
    fmt::print(out_, "  {:<28} {:<14} {:<24} {}\n", v.name, v.type.spelling, v.scope, spanText(lp_->program(), v.span));
}

void ReplSession::listConstraints() const {
  const auto& g = lp_->graph();
  for (const auto& c : g.constraints)
    fmt::print(out_, "  {:<36} {}\n      {}\n", c.name, spanText(lp_->program(), c.span), ir::exprText(c.expr, g));
}

void ReplSession::listPersonal() const {
  const auto& g = lp_->graph();
  for (const auto& gen : g.generators) {
    std::string params, models;
    for (const auto& p : gen.params) params += (params.empty() ? "" : ", ") + p.name + ": " + p.type.spelling;
    for (const auto& f : gen.factors) models += (models.empty() ? "" : ", ") + f.label;
    fmt::print(out_, "  {}({})  accept {:g}, {} learning rule{}, model {}  {}\n", gen.name, params, gen.accept,
               gen.learnRules.size(), gen.learnRules.size() == 1 ? "" : "s", models,
               spanText(lp_->program(), gen.span));
  }
  if (!plan_) return;
  const auto& instances = lp_->instances(plan_->csp.taskIndex);
  fmt::print(out_, "instances in task {} ({}):\n", plan_->csp.task->name, instances.size());
  for (const auto& i : instances) fmt::print(out_, "  {}\n", i.name);
}

void ReplSession::listSkills() const {
  std::set<std::string> seen;
  for (const auto& t : lp_->graph().tasks)
    for (const auto& i : t.instances)
      if (seen.insert(i.skill).second) fmt::print(out_, "  {:<24} {}\n", i.skill, spanText(lp_->program(), i.span));
}

void ReplSession::listTasks() const {
  for (const auto& t : lp_->graph().tasks) {
    std::string skills;
    for (const auto& i : t.instances) skills += (skills.empty() ? "" : " then ") + i.name;
    fmt::print(out_, "  {:<20} {} variables, {} constraints: {}\n", t.name, t.vars.size(), t.constraints.size(),
               skills.empty() ? "(no skills)" : skills);
  }
}

void ReplSession::listObservations() const {
  const rt::Program& program = lp_->program();
  for (const auto& [name, slot] : program.observationSlots())
    fmt::print(out_, "  {:<28} {}\n", name, describeType(program, slot.type));
}

void ReplSession::listEvents() const {
  for (const auto& f : lp_->graph().feedback) {
    std::string params;
    for (const auto& p : f.params) params += (params.empty() ? "" : ", ") + p.name + ": " + p.type.spelling;
    fmt::print(out_, "  {}({})  {}\n", f.name, params, spanText(lp_->program(), f.span));
  }
}

std::vector<std::string> ReplSession::namesOf(const std::string& kind) const {
  std::vector<std::string> names;
  if (kind == "command") {
    for (const auto& c : commands()) names.push_back(c.name);
    return names;
  }
  if (kind == "list") return kListKinds;
  if (kind == "show") return kShowKinds;
  if (kind == "help") return namesOf("command");
  if (!lp_) return names;
  const auto& g = lp_->graph();
  if (kind == "solve") {
    for (const auto& t : g.tasks) names.push_back(t.name);
    names.insert(names.end(), kSolveModes.begin(), kSolveModes.end());
  } else if (kind == "observe") {
    for (const auto& [name, slot] : lp_->program().observationSlots()) names.push_back(name);
    names.push_back("simulator");
    names.push_back("file");
  } else if (kind == "eval") {
    // An expression's names: variables of a task's scope, observations (by family) and members.
    const auto base = [](const std::string& n) { return n.substr(0, n.find('[')); };
    for (const auto& v : g.variables)
      if (v.name.find('.') == std::string::npos) names.push_back(base(v.name));
    for (const auto& [name, slot] : lp_->program().observationSlots()) names.push_back(base(name));
    const auto members = namesOf("member");
    names.insert(names.end(), members.begin(), members.end());
  } else if (kind == "why-not") {
    for (const auto& v : g.variables) names.push_back(v.name);
  } else if (kind == "feedback") {
    for (const auto& f : g.feedback) names.push_back(f.name + "(");
  } else if (kind == "member") {
    for (const auto& e : g.enums) names.insert(names.end(), e.members.begin(), e.members.end());
    for (const auto& s : g.itemSets)
      for (const auto& entry : s.entries) names.push_back(entry.name);
  } else if (kind == "profile") {
    names = {"show", "save", "load"};
  }
  return names;
}

// The values a variable or observation named `name` can take, as the REPL reads them: an enum's members, an item
// set's entries, true/false; empty for numbers and vectors (nothing to offer); nullopt for a name it does not know.
std::optional<std::vector<std::string>> ReplSession::valuesOf(const std::string& name) const {
  if (!lp_) return std::nullopt;
  const ir::ConstraintGraph& g = lp_->graph();
  std::optional<ir::TypeDesc> type;
  // A skill's variable may be named without its instance (`why-not dip = ...` for acquireBite.dip).
  for (const auto& v : g.variables)
    if (v.name == name ||
        (v.name.size() > name.size() && v.name.compare(v.name.size() - name.size(), name.size(), name) == 0 &&
         v.name[v.name.size() - name.size() - 1] == '.'))
      type = v.type;
  const std::string family = name.substr(0, name.find('['));
  for (const auto& o : g.observations)
    if (o.name == name || o.name == family) type = o.type;
  if (!type) return std::nullopt;
  if (type->kind == ir::TypeKind::Bool) return std::vector<std::string>{"true", "false"};
  for (const auto& e : g.enums)
    if (type->kind == ir::TypeKind::Enum && e.name == type->spelling) return e.members;
  std::vector<std::string> entries;
  for (const auto& s : g.itemSets)
    if (type->kind == ir::TypeKind::Item && s.itemType == type->spelling)
      for (const auto& entry : s.entries) entries.push_back(entry.name);
  return entries;
}

std::vector<std::string> ReplSession::completions(const std::string& line) const {
  const auto start = line.find_last_of(" \t(,={") == std::string::npos ? 0 : line.find_last_of(" \t(,={") + 1;
  const std::string word = line.substr(start);
  const auto w = words(line.substr(0, start));
  std::vector<std::string> candidates;
  if (w.empty()) {
    candidates = namesOf("command");
  } else {
    std::string command = w[0];
    if (!command.empty() && command[0] == ':') command = command.substr(1);
    const bool inValue = line.find_first_of("(=", line.find(command) + command.size()) < start;
    if (command == "load" || (command == "profile" && w.size() >= 2 && w[1] != "show")) {
      return pathsStartingWith(word);
    } else if (command == "eval") {
      candidates = namesOf("eval");
    } else if (inValue) {
      // After `NAME =` (observe, why-not): the values of NAME's type only; elsewhere (an event's arguments) any.
      const std::size_t equals = line.rfind('=', start);
      std::optional<std::vector<std::string>> typed;
      if (equals != std::string::npos && w.size() >= 2) typed = valuesOf(w[1].substr(0, w[1].find('=')));
      candidates = typed ? *typed : namesOf("member");
    } else if (command == "profile" && w.size() == 1) {
      candidates = namesOf("profile");
    } else if (w.size() == 1 || command == "solve") {
      candidates = namesOf(command);
    }
  }
  std::vector<std::string> out;
  for (const auto& c : candidates)
    if (c.rfind(word, 0) == 0) out.push_back(c);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cbtl::app::repl
