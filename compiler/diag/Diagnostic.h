// Diagnostic.h — one message about the user's input: severity, stable code, primary range, message,
// and note/help children (each optionally with its own range).
//
// Every diagnostic carries a valid, non-empty primary range inside its file (a position between
// characters, such as a missing ';', uses SourceManager::insertionPoint). The span-robustness unit test
// checks this on every golden input and thousands of mutations of them, and the fuzzer on random input.
#pragma once

#include "compiler/source/SourceManager.h"

#include <string>
#include <vector>

namespace cbtl {

enum class Severity { Error, Warning };

enum class ChildKind { Note, Help };

struct DiagnosticChild {
  ChildKind kind = ChildKind::Note;
  std::string message;
  SourceRange range;  // optional: invalid when the child has no location of its own
};

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string code;  // "E0201", "W0401"
  SourceRange range;
  std::string message;
  std::vector<DiagnosticChild> children;

  Diagnostic& note(std::string msg, SourceRange at = {}) {
    children.push_back({ChildKind::Note, std::move(msg), at});
    return *this;
  }
  Diagnostic& help(std::string msg, SourceRange at = {}) {
    children.push_back({ChildKind::Help, std::move(msg), at});
    return *this;
  }
};

}  // namespace cbtl
