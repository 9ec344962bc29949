# Precompiled headers for the project's own libraries and executables: the standard-library, fmt and nlohmann-json
# headers that nearly every file includes are parsed once per target instead of once per file. A file of the `cbtl`
# executable spent 7 of its 10-15 s of compilation in the front end (`-fsyntax-only`), most of it reading headers:
# 168k lines preprocessed, 118k of them the standard library. With them and -g1, `make demo` on a fresh clone took
# 7 min 41 s instead of 13 min 27 s (README).
#
# They ride on cbtl_warnings (every target of ours links it, PRIVATE), so no CMakeLists names them again; test and
# benchmark targets opt out (tests/CMakeLists.txt says why). Off with -DCBTL_PRECOMPILED_HEADERS=OFF, as `make asan`
# builds: a precompiled header is included into every file, so it would hide a file that forgets one of these
# includes; the sanitizer build keeps that check.
option(CBTL_PRECOMPILED_HEADERS "Precompile the common standard-library, fmt and json headers" ON)
if(CBTL_PRECOMPILED_HEADERS)
  target_precompile_headers(
    cbtl_warnings
    INTERFACE
    <algorithm>
    <cstdint>
    <functional>
    <map>
    <memory>
    <optional>
    <set>
    <sstream>
    <string>
    <string_view>
    <unordered_map>
    <utility>
    <vector>
    <fmt/format.h>
    <nlohmann/json.hpp>)
endif()
