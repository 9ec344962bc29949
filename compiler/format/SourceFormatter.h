// SourceFormatter.h — the canonical layout of a .cbtl file: what `cbtlc fmt` writes.
//
// The formatter works on tokens (comments included), never on the AST, so it keeps every token and every comment
// exactly, and it keeps the author's line breaks: it decides only the whitespace between tokens (the parse tree only
// tells it which `<`, `>` and `-` are binary operators). Rules:
//   - Indentation: a line that starts a declaration, a statement of a block or an entry of a list (items, enum)
//     is indented two spaces per enclosing block (`{` ending its line); a closing bracket that starts a line sits
//     at the indentation of the line that opened it.
//   - Continuation lines (a statement that goes on, or the inside of a bracket opened earlier on a line that
//     goes on after it) keep their layout relative to the statement's first line: they move with it when its
//     indentation is fixed. One at or left of its statement's indentation is put four spaces in from it.
//   - A comment-only line that lined up with the trailing comment of the line above keeps lining up with it.
//   - Within a line: no space after `(` `[`, before `)` `]` `,` `;`, around `.`, inside `{}`, or before the `(` of
//     a call or parameter list and the `[` of an index; one space after `,` and `:`, inside `{ ... }`, before `{`,
//     and around the keywords and operators that join phrases (= == != <= >= => <=> -> .. ~ + * / % and or then
//     as in where if else) and the comparison and arithmetic operators the parse finds binary (`a < b`, `a - b`),
//     and between a length's number and its unit (`5 cm`);
//     none after a unary minus (`-x`) and none around the brackets of type arguments (`vec<2>`, `box<N>(lo)`);
//     elsewhere one space if the author put any, none if not (`x : T` or `x: T`). A run of two or more spaces is
//     alignment when the line above or below has a token of the same kind in the column it reaches (a table's
//     column, `{` under `{`) and that token stays there too: it keeps its column, moved with its line; otherwise
//     it is one space. Before a trailing comment a run of two or more spaces is always alignment (comment columns
//     line up across groups of lines), and a trailing comment is at least one space from the code.
//   - No trailing whitespace, tabs only inside comments and strings, at most one blank line in a row, none at the
//     start or end of the file, a final newline; CR LF line ends become LF; a line comment loses its trailing blanks.
// Formatting is idempotent (a formatted file formats to itself), and the output lexes to the same tokens as the
// input; formatSource checks that and throws std::logic_error if it ever did not (a bug here, never bad input).
#pragma once

#include <string>
#include <string_view>

namespace cbtl {

// The canonical layout of `text`, a file that lexes without error tokens (the caller checks its syntax first:
// layout is only defined for a file that parses). UTF-8; columns count code points.
std::string formatSource(std::string_view text);

}  // namespace cbtl
