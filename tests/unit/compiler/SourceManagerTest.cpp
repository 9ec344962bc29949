// SourceManager: byte offsets to 1-based lines and code-point columns, line text, range text, and the
// one-byte insertion points that diagnostics use between characters.
#include "compiler/source/SourceManager.h"

#include <gtest/gtest.h>

namespace cbtl {
namespace {

TEST(SourceManager, LinesAndColumnsAreOneBased) {
  SourceManager sm;
  const FileId f = sm.add("a.cbtl", "var x;\nrequire x;\n");
  EXPECT_EQ(sm.position(f, 0).line, 1u);
  EXPECT_EQ(sm.position(f, 0).column, 1u);
  EXPECT_EQ(sm.position(f, 4).column, 5u);  // 'x'
  EXPECT_EQ(sm.position(f, 7).line, 2u);    // 'r' of require
  EXPECT_EQ(sm.position(f, 7).column, 1u);
  EXPECT_EQ(sm.position(f, 6).line, 1u);  // the newline belongs to line 1
  EXPECT_EQ(sm.position(f, 6).column, 7u);
}

TEST(SourceManager, ColumnsCountCodePointsNotBytes) {
  SourceManager sm;
  // "ñ" is 2 bytes, "€" 3 bytes, "𝄞" 4 bytes: 'x' is at byte offset 10 but is the 5th character.
  const std::string text = "ñ€𝄞 x";
  const FileId f = sm.add("u.cbtl", text);
  const auto x = static_cast<std::uint32_t>(text.find('x'));
  EXPECT_EQ(x, 10u);
  EXPECT_EQ(sm.position(f, x).line, 1u);
  EXPECT_EQ(sm.position(f, x).column, 5u);
  // An offset inside a multi-byte character counts that character once (continuation bytes never count).
  EXPECT_EQ(sm.position(f, 1).column, 2u);
}

TEST(SourceManager, OffsetsPastTheEndAreClamped) {
  SourceManager sm;
  const FileId f = sm.add("a.cbtl", "ab\ncd");
  EXPECT_EQ(sm.position(f, 100).line, 2u);
  EXPECT_EQ(sm.position(f, 100).column, 3u);
}

TEST(SourceManager, LineTextHasNoTerminator) {
  SourceManager sm;
  const FileId f = sm.add("a.cbtl", "first\r\nsecond\nlast");
  EXPECT_EQ(sm.lineText(f, 1), "first");
  EXPECT_EQ(sm.lineText(f, 2), "second");
  EXPECT_EQ(sm.lineText(f, 3), "last");
  EXPECT_EQ(sm.lineText(f, 0), "");
  EXPECT_EQ(sm.lineText(f, 4), "");
}

TEST(SourceManager, TextOfARange) {
  SourceManager sm;
  const FileId f = sm.add("a.cbtl", "var speed : real;");
  EXPECT_EQ(sm.text(SourceRange{f, 4, 9}), "speed");
  EXPECT_EQ(sm.text(SourceRange{f, 15, 400}), "l;");  // clamped
  EXPECT_EQ(sm.text(SourceRange{}), "");
}

TEST(SourceManager, InsertionPointsAreOneByteInsideTheFile) {
  SourceManager sm;
  const FileId f = sm.add("a.cbtl", "var x\n");
  const SourceRange mid = sm.insertionPoint(f, 5);
  EXPECT_EQ(mid.begin, 5u);
  EXPECT_EQ(mid.end, 6u);
  const SourceRange end = sm.insertionPoint(f, 6);  // at the end of the file: its last byte
  EXPECT_EQ(end.begin, 5u);
  EXPECT_EQ(end.end, 6u);
  const FileId empty = sm.add("e.cbtl", "");
  const SourceRange none = sm.insertionPoint(empty, 0);
  EXPECT_TRUE(none.valid());
  EXPECT_EQ(none.begin, 0u);
  EXPECT_EQ(none.end, 0u);
}

TEST(SourceRange, ToCoversBothRangesOfOneFile) {
  const SourceRange a{0, 4, 6}, b{0, 10, 12}, other{1, 0, 1};
  const SourceRange ab = a.to(b);
  EXPECT_EQ(ab.begin, 4u);
  EXPECT_EQ(ab.end, 12u);
  EXPECT_EQ(a.to(other).end, 6u);  // another file: unchanged
  EXPECT_EQ(SourceRange{}.to(b).begin, 10u);
}

}  // namespace
}  // namespace cbtl
