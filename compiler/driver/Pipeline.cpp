#include "compiler/driver/Pipeline.h"

#include "compiler/driver/AstPrinter.h"
#include "compiler/driver/EmbeddedStdlib.h"
#include "compiler/lower/Lowering.h"
#include "compiler/parse/Parser.h"
#include "compiler/sema/GeneratorChecker.h"
#include "compiler/sema/NameResolver.h"
#include "compiler/sema/TypeChecker.h"
#include "compiler/util/Suggest.h"
#include "ir/GraphPrinter.h"
#include "ir/Validator.h"
#include "support/InputFile.h"

#include <fmt/format.h>

#include <filesystem>
#include <functional>
#include <set>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

struct Pass {
  std::string name;
  std::function<bool(TranslationUnit&)> run;
  std::function<std::string(const TranslationUnit&)> dump;
};

// Reads a source file, at most support::kMaxSourceBytes. Anything else (a directory, a FIFO, /dev/zero,
// /dev/stdin) is refused: an import must never block or read without end. False, with the reason in `why` when
// the file exists but is not one to read (not regular, too large); a missing file needs no more words.
bool readFile(const std::string& path, std::string& out, std::string* why = nullptr) {
  try {
    out = support::readInputFile(path, support::kMaxSourceBytes, "source file");
    return true;
  } catch (const support::InputFileError& e) {
    if (why != nullptr && e.kind != support::InputFileError::Kind::CannotOpen) *why = e.reason;
    return false;
  }
}

// Loads the imports of every parsed module, depth first, detecting cycles. The prelude is implicit.
class Loader {
 public:
  explicit Loader(TranslationUnit& tu) : tu_(tu) {}

  void loadAll() {
    std::vector<std::string> stack;
    loadImports(0, stack);
    // The prelude is imported by every file; loaded last so the root's own names come first in dumps.
    if (!tu_.modules.empty() && !loaded_.count("std.prelude")) loadStd("std.prelude", SourceRange{}, stack);
  }

 private:
  std::size_t addModule(std::string path, std::string text, bool embedded, const std::string& key) {
    FileId id = tu_.sources.add(std::move(path), std::move(text), embedded);
    ParseOutput out = parseModule(tu_.sources, id, tu_.diags, dumpTrees_);
    if (dumpTrees_) tu_.parseTrees[id] = out.treeDump;
    tu_.modules.push_back(std::move(out.module));
    loaded_[key] = tu_.modules.size() - 1;
    return tu_.modules.size() - 1;
  }

  void loadStd(const std::string& name, SourceRange at, std::vector<std::string>& stack) {
    std::string text;
    std::string path;
    bool found = false;
    if (!tu_.options.stdlibDir.empty()) {
      path = (fs::path(tu_.options.stdlibDir) / "std" / (name.substr(4) + ".cbtl")).string();
      found = readFile(path, text);
    } else {
      auto it = embeddedStdlib().find(name);
      if (it != embeddedStdlib().end()) {
        text = std::string(it->second);
        path = "<stdlib>/" + name.substr(4) + ".cbtl";
        found = true;
      }
    }
    if (!found) {
      if (!at.valid()) return;  // the implicit prelude is optional
      if (!tu_.options.stdlibDir.empty()) {
        tu_.diags.error("E0204", at, fmt::format("cannot read standard-library module '{}' from '{}'", name, path))
            .note("--stdlib DIR reads std.NAME from DIR/std/NAME.cbtl");
        return;
      }
      Diagnostic& d = tu_.diags.error("E0203", at, fmt::format("unknown standard-library module '{}'", name));
      std::vector<std::string> names;
      for (const auto& [n, t] : embeddedStdlib()) names.push_back(n);
      const std::string guess = closestMatch(name, names);
      if (!guess.empty())
        d.help(fmt::format("did you mean '{}'?", guess));
      else {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        d.help("available modules: " + list);
      }
      return;
    }
    const std::size_t index = addModule(path, std::move(text), tu_.options.stdlibDir.empty(), name);
    tu_.modules[index]->isStd = true;
    loadImports(index, stack);
  }

  void loadImports(std::size_t index, std::vector<std::string>& stack) {
    const FileId file = tu_.modules[index]->file;
    const std::string self = keyOf(index);
    stack.push_back(self);
    // Copy the import list: loading appends to tu_.modules and may reallocate.
    std::vector<const ImportDecl*> imports;
    for (const auto& d : tu_.modules[index]->decls) {
      if (d->kind == DeclKind::Import) imports.push_back(static_cast<const ImportDecl*>(d.get()));
    }
    for (const ImportDecl* imp : imports) {
      // Error recovery may leave an import without a target (the syntax error is already reported).
      if (imp->target.empty() || !imp->targetRange.valid()) continue;
      std::string key;
      if (imp->isPath) {
        const fs::path base = fs::path(tu_.sources.file(file).path).parent_path();
        key = (base / imp->target).lexically_normal().string();
      } else {
        key = imp->target;
      }
      if (std::find(stack.begin(), stack.end(), key) != stack.end()) {
        tu_.diags.error("E0205", imp->range, fmt::format("import cycle: '{}' is already being imported", imp->target))
            .help("move the shared declarations into a file that both import");
        continue;
      }
      if (loaded_.count(key)) continue;
      if (!imp->isPath) {
        if (imp->target.rfind("std.", 0) != 0) {
          tu_.diags.error("E0203", imp->targetRange, fmt::format("unknown module '{}'", imp->target))
              .help("standard modules are named std.NAME; files are imported with a string: import \"file.cbtl\";");
          continue;
        }
        loadStd(key, imp->targetRange, stack);
        continue;
      }
      if (tu_.sources.file(file).embedded) continue;
      std::string text, why;
      if (!readFile(key, text, &why)) {
        tu_.diags.error("E0204", imp->targetRange, fmt::format("cannot read imported file '{}'", key))
            .note(why.empty() ? std::string("paths are relative to the importing file") : why);
        continue;
      }
      const std::size_t child = addModule(key, std::move(text), false, key);
      loadImports(child, stack);
    }
    stack.pop_back();
  }

  std::string keyOf(std::size_t index) const {
    for (const auto& [k, i] : loaded_) {
      if (i == index) return k;
    }
    return tu_.sources.file(tu_.modules[index]->file).path;
  }

 public:
  bool dumpTrees_ = false;
  std::map<std::string, std::size_t> loaded_;

 private:
  TranslationUnit& tu_;
};

std::string dumpModules(const TranslationUnit& tu) {
  std::string out;
  for (const auto& m : tu.modules) {
    if (tu.sources.file(m->file).embedded) continue;  // the standard library is the same for everyone
    out += dumpAst(*m, tu.sources);
  }
  return out;
}

}  // namespace

const std::vector<std::string>& passNames() {
  static const std::vector<std::string> names = {
      "parse", "build-ast", "resolve-names", "check-types", "check-generators", "check-world", "lower", "validate-ir"};
  return names;
}

PipelineResult compileSource(TranslationUnit& tu, const std::string& path, std::string text,
                             const std::string& dumpAfter, const std::string& stopAfter) {
  PipelineResult result;
  bool syntaxErrors = false;
  std::vector<Pass> passes = {
      {"parse",
       [&](TranslationUnit& t) {
         Loader loader(t);
         loader.dumpTrees_ = dumpAfter == "parse";
         t.root = t.sources.add(path, std::move(text));
         ParseOutput out = parseModule(t.sources, t.root, t.diags, loader.dumpTrees_);
         if (loader.dumpTrees_) t.parseTrees[t.root] = out.treeDump;
         t.modules.push_back(std::move(out.module));
         loader.loaded_[path] = 0;
         loader.loadAll();
         syntaxErrors = t.diags.hasErrors();
         return !syntaxErrors;
       },
       [](const TranslationUnit& t) {
         std::string out;
         for (const auto& [file, tree] : t.parseTrees) {
           if (t.sources.file(file).embedded) continue;
           out += t.sources.file(file).path + ":\n" + tree + "\n";
         }
         return out;
       }},
      // The AST is built while parsing (one visitor pass over each parse tree); this pass names the
      // result so it can be dumped before any semantic annotation.
      {"build-ast", [](TranslationUnit&) { return true; }, dumpModules},
      {"resolve-names", [](TranslationUnit& t) { return resolveNames(t.modules, t.types, t.symbols, t.diags); },
       dumpModules},
      {"check-types", [](TranslationUnit& t) { return checkTypes(t.modules, t.types, t.symbols, t.diags); },
       dumpModules},
      {"check-generators", [](TranslationUnit& t) { return checkGenerators(t.modules, t.diags); }, dumpModules},
      {"check-world", [&](TranslationUnit& t) { return checkWorld(t.modules, t.symbols, path, t.diags, t.world); },
       [](const TranslationUnit& t) { return dumpWorldCheck(t.world); }},
      {"lower", [](TranslationUnit& t) { return lowerToGraph(t.modules, t.symbols, t.sources, t.diags, t.graph); },
       [](const TranslationUnit& t) { return ir::toText(t.graph); }},
      {"validate-ir",
       [&](TranslationUnit& t) {
         const auto problems = ir::validate(t.graph);
         if (problems.empty()) return true;
         Diagnostic& d = t.diags.error("E0901", t.sources.insertionPoint(t.root, 0),
                                       "the compiler produced an invalid constraint graph");
         for (const auto& p : problems) d.note(p);
         result.outcome = PipelineOutcome::InternalError;
         return false;
       },
       [](const TranslationUnit& t) { return ir::toText(t.graph); }},
  };
  // The semantic checks (names, types, generators, the world) report everything they find in one run: each one
  // tolerates what an earlier one could not resolve (error types do not cascade), so after a semantic error the next
  // check still runs. A syntax error stops everything (the tree is a guess), and so does any error before lowering.
  auto tolerant = [](const std::string& name) {
    return name == "check-types" || name == "check-generators" || name == "check-world";
  };
  bool failed = false;
  for (auto& pass : passes) {
    if (failed && !tolerant(pass.name)) break;
    result.lastPass = pass.name;
    const bool ok = pass.run(tu);
    if (ok && !failed && pass.name == dumpAfter) result.dump = pass.dump(tu);
    if (!ok || tu.diags.hasErrors()) {
      if (result.outcome == PipelineOutcome::Ok) result.outcome = PipelineOutcome::InputErrors;
      if (pass.name == "parse" || pass.name == "validate-ir") return result;
      failed = true;
    }
    if (pass.name == stopAfter) break;
  }
  return result;
}

PipelineResult compileFile(TranslationUnit& tu, const std::string& path, const std::string& dumpAfter,
                           const std::string& stopAfter) {
  std::string text;
  PipelineResult unread;
  if (!readFile(path, text, &unread.inputError)) {
    unread.outcome = PipelineOutcome::InputErrors;
    unread.rootUnread = true;
    return unread;
  }
  return compileSource(tu, path, std::move(text), dumpAfter, stopAfter);
}

}  // namespace cbtl
