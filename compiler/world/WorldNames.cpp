// The MJCF name reader: expat over the scene file, then over each file it includes, depth first. Only element
// names and two attributes matter, so the reader is a pair of element callbacks; everything it does not know it
// skips, which keeps it independent of MuJoCo's version of the format.
#include "compiler/world/WorldNames.h"

#include <expat.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>

namespace cbtl {
namespace {

namespace fs = std::filesystem;

// Includes nested deeper than this are refused (a scene and its robot are two or three levels).
constexpr std::size_t kMaxIncludeDepth = 32;

// What the callbacks of one file collect.
struct FileState {
  XML_Parser parser = nullptr;
  WorldNames* names = nullptr;
  int defaultDepth = 0;                               // inside <default>: geoms there are templates
  std::vector<std::string> bodies;                    // the <body> elements open, by name (empty: unnamed)
  std::vector<std::pair<std::string, int>> includes;  // each <include>: its file attribute and line
  int includeWithoutFile = 0;                         // the line of an <include> without a file, if any
};

const char* attribute(const XML_Char** attrs, std::string_view key) {
  for (std::size_t i = 0; attrs[i] != nullptr; i += 2) {
    if (key == attrs[i]) return attrs[i + 1];
  }
  return nullptr;
}

void XMLCALL onStart(void* data, const XML_Char* element, const XML_Char** attrs) {
  auto* s = static_cast<FileState*>(data);
  const std::string_view name(element);
  if (name == "default") {
    ++s->defaultDepth;
    return;
  }
  const char* value = attribute(attrs, "name");
  const bool named = value != nullptr && *value != '\0';
  if (name == "body") {
    if (named) s->names->bodies.insert(value);
    s->bodies.emplace_back(named ? value : "");
  } else if (name == "geom" && named && s->defaultDepth == 0) {
    s->names->geoms.insert(value);
    s->names->geomBody[value] = s->bodies.empty() ? "" : s->bodies.back();
  } else if (name == "include") {
    const int line = static_cast<int>(XML_GetCurrentLineNumber(s->parser));
    const char* file = attribute(attrs, "file");
    if (file == nullptr || *file == '\0') {
      if (s->includeWithoutFile == 0) s->includeWithoutFile = line;
    } else {
      s->includes.emplace_back(file, line);
    }
  }
}

void XMLCALL onEnd(void* data, const XML_Char* element) {
  auto* s = static_cast<FileState*>(data);
  const std::string_view name(element);
  if (name == "default" && s->defaultDepth > 0) --s->defaultDepth;
  if (name == "body" && !s->bodies.empty()) s->bodies.pop_back();
}

class Reader {
 public:
  explicit Reader(WorldReadResult& result) : result_(result) {}

  // Reads one file and, after it, the files it includes. False once result_.error is set.
  bool read(const std::string& path) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(fs::path(path), ec);
    const std::string keyText = ec ? path : key.string();
    if (std::find(stack_.begin(), stack_.end(), keyText) != stack_.end())
      return fail(Kind::Unreadable, path, 0, "the file includes itself (an include cycle)");
    if (stack_.size() >= kMaxIncludeDepth)
      return fail(Kind::Unreadable, path, 0, fmt::format("includes nest deeper than {} files", kMaxIncludeDepth));
    FileState state;
    state.names = &result_.names;
    if (!parse(path, state)) return false;
    result_.names.files.push_back(path);
    if (state.includeWithoutFile != 0)
      return fail(Kind::Include, path, state.includeWithoutFile, "an <include> element without a 'file' attribute");
    stack_.push_back(keyText);
    for (const auto& [file, line] : state.includes) {
      const std::string child = (fs::path(path).parent_path() / file).lexically_normal().string();
      chain_.emplace_back(path, line);
      if (!read(child)) return false;
      chain_.pop_back();
    }
    stack_.pop_back();
    return true;
  }

 private:
  using Kind = WorldReadError::Kind;

  bool fail(Kind kind, const std::string& file, int line, std::string message) {
    result_.error = WorldReadError{kind, file, line, std::move(message), chain_};
    return false;
  }

  // Streams the file through expat. A directory, a FIFO or a device is refused: reading must never block.
  bool parse(const std::string& path, FileState& state) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return fail(Kind::Unreadable, path, 0, "no such file");
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(Kind::Unreadable, path, 0, "the file cannot be opened");
    XML_Parser parser = XML_ParserCreate(nullptr);
    if (parser == nullptr) return fail(Kind::Unreadable, path, 0, "out of memory");
    state.parser = parser;
    XML_SetUserData(parser, &state);
    XML_SetElementHandler(parser, onStart, onEnd);
    std::array<char, 1 << 16> buffer{};
    bool ok = true;
    for (;;) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      const auto got = static_cast<int>(in.gcount());
      const bool last = got < static_cast<int>(buffer.size());
      if (XML_Parse(parser, buffer.data(), got, last ? XML_TRUE : XML_FALSE) == XML_STATUS_ERROR) {
        ok = fail(Kind::Malformed, path, static_cast<int>(XML_GetCurrentLineNumber(parser)),
                  XML_ErrorString(XML_GetErrorCode(parser)));
        break;
      }
      if (last) break;
    }
    XML_ParserFree(parser);
    return ok;
  }

  WorldReadResult& result_;
  std::vector<std::string> stack_;                  // canonical paths of the files being read
  std::vector<std::pair<std::string, int>> chain_;  // the includes that led to the file being read
};

}  // namespace

WorldReadResult readWorldNames(const std::string& path) {
  WorldReadResult result;
  result.ok = Reader(result).read(path);
  if (!result.ok) result.names = WorldNames{};
  return result;
}

}  // namespace cbtl
