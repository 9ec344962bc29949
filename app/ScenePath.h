// ScenePath.h — where the scene of a program's `world "scene.xml";` line is on disk.
//
// In a .cbtl file the path is relative to that file's folder. An emitted graph (cbtlc emit --format json)
// keeps the path as written, so the scene of a graph is looked for, in this order:
//   1. the path itself when it is absolute;
//   2. relative to the JSON file's folder (the graph was emitted beside its .cbtl, or shipped with its scene);
//   3. relative to the folder of each source file the graph's spans name (files of the standard library
//      excepted), in the order tasks, generators, constraints, variables, constants, item sets, enums. Span
//      files are as the user wrote them to cbtlc, so relative ones resolve against the current directory:
//      a graph emitted to another folder finds its scene when cbtl runs where cbtlc ran.
// The first candidate that exists wins.
#pragma once

#include "ir/ConstraintGraph.h"

#include <string>
#include <vector>

namespace cbtl::app {

// The scene of a .cbtl file at `sourcePath` whose world line says `world`.
std::string sceneOfSource(const std::string& sourcePath, const std::string& world);

struct SceneLookup {
  std::string path;                // the scene found; empty when no candidate exists
  std::vector<std::string> tried;  // every candidate, in order (for the message when none exists)
};

// The scene of the graph read from the JSON file at `jsonPath` (graph.world must not be empty).
SceneLookup sceneOfEmittedGraph(const std::string& jsonPath, const ir::ConstraintGraph& graph);

}  // namespace cbtl::app
