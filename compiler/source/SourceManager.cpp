#include "compiler/source/SourceManager.h"

#include <algorithm>

namespace cbtl {

SourceRange SourceRange::to(const SourceRange& other) const {
  if (!valid()) return other;
  if (!other.valid() || other.file != file) return *this;
  return SourceRange{file, std::min(begin, other.begin), std::max(end, other.end)};
}

FileId SourceManager::add(std::string path, std::string text, bool embedded) {
  SourceFile f;
  f.path = std::move(path);
  f.text = std::move(text);
  f.embedded = embedded;
  f.lineStarts.push_back(0);
  for (std::uint32_t i = 0; i < f.text.size(); ++i) {
    if (f.text[i] == '\n') f.lineStarts.push_back(i + 1);
  }
  files_.push_back(std::move(f));
  return static_cast<FileId>(files_.size() - 1);
}

LineCol SourceManager::position(FileId id, std::uint32_t offset) const {
  const SourceFile& f = files_.at(id);
  offset = std::min<std::uint32_t>(offset, static_cast<std::uint32_t>(f.text.size()));
  auto it = std::upper_bound(f.lineStarts.begin(), f.lineStarts.end(), offset);
  const auto lineIndex = static_cast<std::uint32_t>(std::distance(f.lineStarts.begin(), it) - 1);
  std::uint32_t column = 1;
  for (std::uint32_t i = f.lineStarts[lineIndex]; i < offset; ++i) {
    // Count code points: skip UTF-8 continuation bytes (10xxxxxx).
    if ((static_cast<unsigned char>(f.text[i]) & 0xC0) != 0x80) ++column;
  }
  return LineCol{lineIndex + 1, column};
}

std::string_view SourceManager::lineText(FileId id, std::uint32_t line) const {
  const SourceFile& f = files_.at(id);
  if (line == 0 || line > f.lineStarts.size()) return {};
  const std::uint32_t begin = f.lineStarts[line - 1];
  std::uint32_t end = line < f.lineStarts.size() ? f.lineStarts[line] : static_cast<std::uint32_t>(f.text.size());
  while (end > begin && (f.text[end - 1] == '\n' || f.text[end - 1] == '\r')) --end;
  return std::string_view(f.text).substr(begin, end - begin);
}

std::string_view SourceManager::text(const SourceRange& range) const {
  if (!range.valid()) return {};
  const SourceFile& f = files_.at(range.file);
  const std::uint32_t b = std::min<std::uint32_t>(range.begin, static_cast<std::uint32_t>(f.text.size()));
  const std::uint32_t e = std::min<std::uint32_t>(std::max(range.end, b), static_cast<std::uint32_t>(f.text.size()));
  return std::string_view(f.text).substr(b, e - b);
}

SourceRange SourceManager::insertionPoint(FileId id, std::uint32_t offset) const {
  const auto size = static_cast<std::uint32_t>(files_.at(id).text.size());
  if (size == 0) return SourceRange{id, 0, 0};
  const std::uint32_t at = std::min(offset, size - 1);
  return SourceRange{id, at, at + 1};
}

}  // namespace cbtl
