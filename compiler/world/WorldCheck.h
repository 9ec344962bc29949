// WorldCheck.h — the `check-world` pass: the scene names a program uses exist in its world.
//
// Runs only when the program declares a clearance or uses an `allow` (a program without either compiles whatever
// its `world` line names, as before). Then the program must have a world (the root file's `world "..."`, E0603),
// the world file and what it includes must be readable, well-formed XML (E0606, at the `world` path, with the line
// of the XML error), every body of every clearance must be a body of the world (E0607), and an allow target
// written as a string literal, or as a constant whose value is one, must name a body or a geom (E0607). Targets
// computed from variables, parameters or families are left to the runtime.
#pragma once

#include "compiler/ast/Ast.h"
#include "compiler/diag/DiagnosticEngine.h"
#include "compiler/sema/Symbols.h"
#include "compiler/world/WorldNames.h"

#include <memory>
#include <string>
#include <vector>

namespace cbtl {

// What the pass read, for its dump.
struct WorldCheckResult {
  bool ran = false;  // false: the program has no clearance and no allow, and nothing was read
  std::string path;  // the world file as opened (relative to the working directory when the root file's path is)
  WorldNames names;  // the names read (empty if the world could not be read)
};

// `rootPath` is the root file's path as given; the world's path is relative to its folder. Returns false if errors
// were reported.
bool checkWorld(const std::vector<std::unique_ptr<Module>>& modules, const GlobalSymbols& symbols,
                const std::string& rootPath, DiagnosticEngine& diags, WorldCheckResult& result);

// The pass's dump: the files read and every body and geom name, or a line saying the check did not run.
std::string dumpWorldCheck(const WorldCheckResult& result);

}  // namespace cbtl
