#include "app/ScenePath.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace cbtl::app {

namespace fs = std::filesystem;

namespace {

std::string normal(const fs::path& p) { return p.lexically_normal().string(); }

// Folders of the graph's own source files, first appearance first.
std::vector<fs::path> sourceFolders(const ir::ConstraintGraph& g) {
  std::vector<fs::path> folders;
  auto add = [&](const ir::Span& s) {
    if (s.file.empty() || s.file.rfind("<stdlib>", 0) == 0) return;
    const fs::path folder = fs::path(s.file).parent_path();
    if (std::find(folders.begin(), folders.end(), folder) == folders.end()) folders.push_back(folder);
  };
  for (const auto& x : g.tasks) add(x.span);
  for (const auto& x : g.generators) add(x.span);
  for (const auto& x : g.constraints) add(x.span);
  for (const auto& x : g.variables) add(x.span);
  for (const auto& x : g.constants) add(x.span);
  for (const auto& x : g.itemSets) add(x.span);
  for (const auto& x : g.enums) add(x.span);
  return folders;
}

}  // namespace

std::string sceneOfSource(const std::string& sourcePath, const std::string& world) {
  return normal(fs::path(sourcePath).parent_path() / world);
}

SceneLookup sceneOfEmittedGraph(const std::string& jsonPath, const ir::ConstraintGraph& graph) {
  SceneLookup lookup;
  const fs::path world(graph.world);
  if (world.is_absolute()) {
    lookup.tried.push_back(normal(world));
  } else {
    lookup.tried.push_back(sceneOfSource(jsonPath, graph.world));
    for (const auto& folder : sourceFolders(graph)) {
      const std::string candidate = normal(folder / world);
      if (std::find(lookup.tried.begin(), lookup.tried.end(), candidate) == lookup.tried.end())
        lookup.tried.push_back(candidate);
    }
  }
  for (const auto& candidate : lookup.tried) {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) {
      lookup.path = candidate;
      break;
    }
  }
  return lookup;
}

}  // namespace cbtl::app
