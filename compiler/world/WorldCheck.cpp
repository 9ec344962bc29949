// The `check-world` pass: collects the program's clearances and allow statements, and only if there are any
// reads the world file (compiler/world/WorldNames.h) and checks the scene names they use.
#include "compiler/world/WorldCheck.h"

#include "compiler/util/Suggest.h"

#include <fmt/format.h>

#include <filesystem>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

// Every allow statement of every skill, nested ones included, in source order.
void collectAllows(const std::vector<std::unique_ptr<ActionStmt>>& stmts, std::vector<const ActionStmt*>& out) {
  for (const auto& s : stmts) {
    if (s->kind == ActionStmtKind::Allow) out.push_back(s.get());
    collectAllows(s->body, out);
    collectAllows(s->elseBody, out);
  }
}

// The head of an allow statement, `allow PART MODE TARGET LENGTH`, without its block.
SourceRange allowHead(const ActionStmt& s) {
  const SourceRange& end = s.allow->length.range;
  return end.valid() && end.file == s.range.file ? SourceRange{s.range.file, s.range.begin, end.end} : s.range;
}

class WorldChecker {
 public:
  WorldChecker(const GlobalSymbols& symbols, DiagnosticEngine& diags, WorldCheckResult& result)
      : symbols_(symbols), diags_(diags), result_(result) {}

  void run(const std::vector<std::unique_ptr<Module>>& modules, const std::string& rootPath) {
    for (const auto& m : modules) {
      for (const auto& d : m->decls) {
        if (d->kind == DeclKind::Clearance) clearances_.push_back(static_cast<const ClearanceDecl*>(d.get()));
        if (d->kind == DeclKind::Skill) collectAllows(static_cast<const SkillDecl&>(*d).actions, allows_);
      }
    }
    if (clearances_.empty() && allows_.empty()) return;
    result_.ran = true;
    if (symbols_.world == nullptr) {
      noWorld();
      return;
    }
    result_.path = (fs::path(rootPath).parent_path() / symbols_.world->path).lexically_normal().string();
    WorldReadResult read = readWorldNames(result_.path);
    if (!read.ok) {
      unreadable(read.error);
      return;
    }
    result_.names = std::move(read.names);
    for (const ClearanceDecl* c : clearances_) {
      for (std::size_t i = 0; i < c->bodies.size(); ++i) checkBody(c->bodies[i], c->bodyRanges[i]);
    }
    for (const ActionStmt* s : allows_) checkTarget(*s->allow);
  }

 private:
  void noWorld() {
    for (const ClearanceDecl* c : clearances_) {
      diags_
          .error("E0603", c->name.range,
                 fmt::format("clearance '{}' needs a world, but the program declares none", c->name.name))
          .help("name the scene the bodies belong to in the root file: world \"scene.xml\";");
    }
    for (const ActionStmt* s : allows_) {
      diags_.error("E0603", allowHead(*s), "an allow needs a world, but the program declares none")
          .help("name the scene in the root file: world \"scene.xml\";");
    }
  }

  void unreadable(const WorldReadError& e) {
    const WorldDecl& world = *symbols_.world;
    const SourceRange at = world.pathRange.valid() ? world.pathRange : world.range;
    std::string message;
    switch (e.kind) {
      case WorldReadError::Kind::Unreadable:
        message = fmt::format("cannot read the world file '{}': {}", e.file, e.message);
        break;
      case WorldReadError::Kind::Malformed:
        message = fmt::format("the world file '{}' is not well-formed XML at line {}: {}", e.file, e.line, e.message);
        break;
      case WorldReadError::Kind::Include:
        message = fmt::format("the world file '{}' has {} at line {}", e.file, e.message, e.line);
        break;
    }
    Diagnostic& d = diags_.error("E0606", at, message);
    for (auto it = e.includedFrom.rbegin(); it != e.includedFrom.rend(); ++it) {
      d.note(fmt::format("'{}' is included by '{}' (line {})",
                         it == e.includedFrom.rbegin() ? e.file : std::prev(it)->first, it->first, it->second));
    }
    d.note(
        "the world is read to check the program's clearances and allows; its path is relative to this file's folder, "
        "an include's to the including file's");
  }

  void checkBody(const std::string& body, SourceRange at) {
    const WorldNames& w = result_.names;
    if (w.bodies.count(body)) return;
    Diagnostic& d =
        diags_.error("E0607", at, fmt::format("\"{}\" is not a body of the world '{}'", body, result_.path));
    if (auto it = w.geomBody.find(body); it != w.geomBody.end()) {
      d.note(fmt::format("\"{}\" is a geom; a clearance names bodies, each with the bodies attached below it", body));
      if (!it->second.empty()) d.help(fmt::format("name its body: \"{}\"", it->second));
      return;
    }
    const std::string guess = closestMatch(body, std::vector<std::string>(w.bodies.begin(), w.bodies.end()));
    if (!guess.empty()) d.help(fmt::format("did you mean \"{}\"?", guess));
  }

  // A target known at compile time: a string literal, or a plain constant whose value is one.
  void checkTarget(const AllowClause& a) {
    if (a.clearance != nullptr || a.target == nullptr) return;
    const Expr& t = *a.target;
    const Expr* literal = nullptr;
    const ConstDecl* constant = nullptr;
    if (t.kind == ExprKind::String) {
      literal = &t;
    } else if (t.kind == ExprKind::Name && t.ref.kind == RefKind::Const) {
      constant = static_cast<const ConstDecl*>(t.ref.decl);
      if (constant->index == nullptr && constant->value && constant->value->kind == ExprKind::String)
        literal = constant->value.get();
    }
    if (literal == nullptr) return;
    const WorldNames& w = result_.names;
    if (w.bodies.count(literal->text) || w.geoms.count(literal->text)) return;
    Diagnostic& d = diags_.error(
        "E0607", t.range,
        constant == nullptr
            ? fmt::format("\"{}\" is neither a body nor a geom of the world '{}'", literal->text, result_.path)
            : fmt::format("'{}' is \"{}\", which is neither a body nor a geom of the world '{}'", constant->name.name,
                          literal->text, result_.path));
    std::vector<std::string> names(w.bodies.begin(), w.bodies.end());
    names.insert(names.end(), w.geoms.begin(), w.geoms.end());
    const std::string guess = closestMatch(literal->text, names);
    if (!guess.empty()) d.help(fmt::format("did you mean \"{}\"?", guess));
    if (constant != nullptr) d.note("the constant's value is here", literal->range);
  }

  const GlobalSymbols& symbols_;
  DiagnosticEngine& diags_;
  WorldCheckResult& result_;
  std::vector<const ClearanceDecl*> clearances_;
  std::vector<const ActionStmt*> allows_;
};

}  // namespace

bool checkWorld(const std::vector<std::unique_ptr<Module>>& modules, const GlobalSymbols& symbols,
                const std::string& rootPath, DiagnosticEngine& diags, WorldCheckResult& result) {
  const std::size_t before = diags.errorCount();
  WorldChecker(symbols, diags, result).run(modules, rootPath);
  return diags.errorCount() == before;
}

std::string dumpWorldCheck(const WorldCheckResult& result) {
  if (!result.ran) return "world not read: the program declares no clearance and no allow\n";
  std::string out = fmt::format("world {}\n", result.path.empty() ? "<none>" : result.path);
  for (const auto& f : result.names.files) out += fmt::format("  file {}\n", f);
  for (const auto& b : result.names.bodies) out += fmt::format("  body {}\n", b);
  for (const auto& g : result.names.geoms) {
    const auto it = result.names.geomBody.find(g);
    const bool inBody = it != result.names.geomBody.end() && !it->second.empty();
    out += fmt::format("  geom {}{}\n", g, inBody ? " (body " + it->second + ")" : "");
  }
  return out;
}

}  // namespace cbtl
