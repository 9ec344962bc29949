// WorldNames.h — the names a MuJoCo scene (MJCF) gives its bodies and geoms, as the compiler needs them to check
// clearances and allow targets against the world a program declares.
//
// Reads the scene file and every file it includes (`<include file="..."/>`, the path relative to the including
// file, followed wherever the element appears), with expat: the files must be well-formed XML, nothing else of
// MJCF is checked. A body is a `<body>` element with a `name` attribute; a geom a `<geom>` with a `name` outside
// `<default>` (defaults are templates, not geoms). Unnamed bodies and geoms have no name to check against and are
// left out; MuJoCo's implicit world body ("world") is not listed.
#pragma once

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cbtl {

struct WorldNames {
  std::set<std::string> bodies;
  std::set<std::string> geoms;
  // Each named geom's body: the named <body> around it in its file; empty for a geom of the world body, of an
  // unnamed body, or at the top of an included file.
  std::map<std::string, std::string> geomBody;
  std::vector<std::string> files;  // every file read, the scene first, then includes in the order they were met
};

struct WorldReadError {
  enum class Kind {
    Unreadable,  // missing, not a regular file, an include cycle or includes nested too deep (line 0)
    Malformed,   // not well-formed XML: `message` is expat's, `line` where it stopped
    Include,     // an <include> without a file attribute, at `line`
  };
  Kind kind = Kind::Unreadable;
  std::string file;  // the file at fault: the scene or an included file
  int line = 0;      // 1-based line in `file`; 0: the file as a whole (it cannot be read)
  std::string message;
  // How `file` was reached: each (including file, line of its <include>), the scene's include first; empty for
  // the scene itself.
  std::vector<std::pair<std::string, int>> includedFrom;
};

struct WorldReadResult {
  bool ok = false;
  WorldNames names;      // complete only when ok
  WorldReadError error;  // when not ok
};

// Reads the scene at `path` (as given, or relative to the working directory) and its includes. Fails on the first
// file that cannot be read (missing, not a regular file), is not well-formed XML, or includes itself, or when
// includes nest deeper than 32 files.
WorldReadResult readWorldNames(const std::string& path);

}  // namespace cbtl
