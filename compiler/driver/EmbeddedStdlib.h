// EmbeddedStdlib.h — the standard-library modules compiled into the binary (stdlib/CMakeLists.txt,
// cmake/EmbedFiles.cmake).
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace cbtl {

// Module name ("std.geometry") -> source text, sorted by name.
const std::map<std::string, std::string_view>& embeddedStdlib();

}  // namespace cbtl
