// SourceManager.h — owns the text of every file a translation unit reads and maps byte offsets to
// human positions.
//
// Ranges are byte offsets [begin, end) into one file. Lines and columns are 1-based; columns count
// Unicode code points (UTF-8 continuation bytes are skipped), which is what editors show. File paths
// are kept exactly as the user (or the importing file) gave them, so output is portable across machines.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl {

using FileId = std::uint32_t;
inline constexpr FileId kNoFile = 0xffffffffu;

struct SourceRange {
  FileId file = kNoFile;
  std::uint32_t begin = 0;  // byte offset of the first byte
  std::uint32_t end = 0;    // byte offset one past the last byte; end >= begin

  bool valid() const { return file != kNoFile; }
  // The smallest range covering both; both must be in the same file (otherwise returns *this).
  SourceRange to(const SourceRange& other) const;
};

struct LineCol {
  std::uint32_t line = 0;    // 1-based
  std::uint32_t column = 0;  // 1-based, in code points
};

struct SourceFile {
  std::string path;  // as given
  std::string text;
  bool embedded = false;                  // a standard-library module compiled into the binary
  std::vector<std::uint32_t> lineStarts;  // byte offset of each line's first byte
};

class SourceManager {
 public:
  // Adds a file's text; returns its id. Never fails.
  FileId add(std::string path, std::string text, bool embedded = false);

  const SourceFile& file(FileId id) const { return files_.at(id); }
  std::size_t fileCount() const { return files_.size(); }

  // Position of a byte offset (clamped to the file's size).
  LineCol position(FileId id, std::uint32_t offset) const;
  // The text of one 1-based line, without its line terminator.
  std::string_view lineText(FileId id, std::uint32_t line) const;
  // Text covered by a range.
  std::string_view text(const SourceRange& range) const;
  // A one-byte range for a diagnostic that points between characters (a missing ';' after a token, the end
  // of the file): the byte at `offset`, or the file's last byte when `offset` is at (or past) its end. Only
  // an empty file gives an empty range. Diagnostics never carry empty spans otherwise.
  SourceRange insertionPoint(FileId id, std::uint32_t offset) const;

 private:
  std::vector<SourceFile> files_;
};

}  // namespace cbtl
