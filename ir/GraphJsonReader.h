// GraphJsonReader.h — reads the JSON that toJson (ir/GraphPrinter.h) writes back into a ConstraintGraph, so
// that the runtime can execute an emitted graph without the front end.
//
// Reading never throws and never trusts the input: text that is not JSON, a wrong "format" tag or "version",
// a missing or mistyped field, an unknown discriminator (an expression's op, a type kind, a factor kind...),
// an index out of range (a variable, constraint, sampler or cost id) or an inconsistent shape (an operator
// with the wrong number of operands, an id that is not its position) is reported with the JSON Pointer
// (RFC 6901) of the offending field, e.g. "/tasks/0/constraints/3". A graph that reads cleanly has every id
// in range and every expression shaped as the runtime expects; the caller may still run ir::validate for
// the semantic checks (hyperedges equal to read sets, ...).
#pragma once

#include "ir/ConstraintGraph.h"

#include <string>
#include <string_view>

namespace cbtl::ir {

enum class GraphReadOutcome {
  Ok,
  NotJson,       // the text does not parse as JSON
  WrongFormat,   // not an object, or its "format" is not kGraphJsonFormat
  WrongVersion,  // a "version" this reader does not read
  MissingField,  // a required field is absent
  WrongType,     // a field has the wrong JSON type (or a number out of its type's range)
  UnknownName,   // a discriminator names nothing this reader knows ("op": "foo")
  OutOfRange,    // an index names no variable / constraint / sampler / cost / parameter, a name no clearance
  Inconsistent,  // fields that disagree: operand counts, ids versus positions, arity versus parameters
};

const char* toString(GraphReadOutcome outcome);

struct GraphReadResult {
  GraphReadOutcome outcome = GraphReadOutcome::Ok;
  ConstraintGraph graph;  // complete only when ok()
  std::string pointer;    // JSON Pointer of the offending field; empty: the document itself
  std::string message;    // what is wrong there

  bool ok() const { return outcome == GraphReadOutcome::Ok; }
  // "FILE: POINTER: MESSAGE" (without the pointer when it is empty); "" when ok().
  std::string describe(const std::string& file) const;
};

GraphReadResult readGraphJson(std::string_view text);

// Whether `text` is meant as an emitted graph rather than .cbtl source: its first character after white space
// (and a UTF-8 byte-order mark) is '{', which no .cbtl program can start with.
bool looksLikeGraphJson(std::string_view text);

}  // namespace cbtl::ir
