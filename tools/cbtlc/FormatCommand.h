// FormatCommand.h — `cbtlc fmt`: lays out .cbtl files canonically (compiler/format/SourceFormatter.h).
//
//   cbtlc fmt FILE            the formatted file on stdout (FILE unchanged); `-` or no FILE reads stdin
//   cbtlc fmt --write FILE... rewrites each file that is not formatted (atomically: a temporary file renamed over it)
//   cbtlc fmt --check FILE... lists the files that are not formatted; exit 1 if any
// A file with syntax errors is not formatted: its diagnostics are printed and the file is left as it is (exit 1).
// Exit codes as for every cbtlc command: 0 ok, 1 errors in the input (or files to format, with --check), 2 usage,
// 70 internal error.
#pragma once

#include <CLI/CLI.hpp>

namespace cbtl::cli {

// Adds `fmt` to `app`; its callback stores its exit code in `exitCode`.
void addFormatCommand(CLI::App& app, int& exitCode);

}  // namespace cbtl::cli
