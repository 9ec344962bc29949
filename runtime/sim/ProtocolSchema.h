// ProtocolSchema.h — what a program lets a simulator say, and how each value is written on the wire of the
// external simulator protocol (SimulatorProtocol.h, docs/simulator-protocol.md).
//
// The schema is read from the program's declarations: its observations (by the keys the runtime reads, a
// family's members as "name[member]"), the extern actions its tasks call, its feedback events (and which of them
// a `learn` rule uses), and its tasks. Every value that crosses the protocol is checked against the declared
// type here, so a wrong value is reported by name and type where it arrives, never as a wrong number later.
//
// Values on the wire (JSON):  real -> number;  int -> integer;  bool -> true/false;  text, enum member, item
// entry -> string;  vec<N>, SE2 (x y yaw), SE3 (x y z qx qy qz qw), Conf (joint angles, rad) -> array of numbers;
// set<Enum|Item> -> array of strings.
#pragma once

#include "ir/ConstraintGraph.h"
#include "runtime/sim/DomainSimulator.h"

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace cbtl::sim {

// The type of one value on the wire.
struct WireType {
  enum class Kind { Real, Int, Bool, Name, Vector, Names };
  Kind kind = Kind::Real;
  std::size_t width = 1;             // Vector: its components
  std::string spelling;              // as the program writes it: "real", "Size", "vec<2>", "set<Book>"
  std::vector<std::string> members;  // Name / Names of an enum or item type: the allowed names; empty: any text
};

struct WireParam {
  std::string name;
  WireType type;
};

// An extern action or a feedback event: its parameters in declaration order.
struct WireSignature {
  std::string name;
  std::vector<WireParam> params;
  std::string declaredAt;  // "file:line:col"
};

struct ProtocolSchema {
  std::string domain;
  std::map<std::string, WireType> observations;         // by the runtime's key: "hour", "stock[salt]"
  std::map<std::string, std::string> observationNames;  // declared name ("stock") -> where it is declared
  std::map<std::string, WireSignature> actions;         // the extern actions some task of the program calls
  std::map<std::string, WireSignature> feedback;        // every declared feedback event
  std::set<std::string> learnedEvents;                  // the events some `learn` rule reads
  std::vector<std::string> tasks;                       // in declaration order

  // `observationKeys`: the keys the runtime reads (rt::Program::observationSlots()). Throws rt::RuntimeError (bad
  // input) for a type the protocol cannot carry (none of the language's declarable types).
  static ProtocolSchema fromProgram(const ir::ConstraintGraph& graph, const std::vector<std::string>& observationKeys);
};

// `value` as `type` on the wire.
nlohmann::json encodeValue(const WireType& type, const Value& value);

// The wire value `json` read as `type`; nullopt with `error` saying what was expected ("an integer", "one of
// small, medium, large", ...) when it does not fit.
std::optional<Value> decodeValue(const WireType& type, const nlohmann::json& json, std::string& error);

// Arguments by parameter name ({"size": "large", "temp": 72}) or in declaration order ([...]), read as the
// signature's parameters (declaration order); nullopt with `error` naming the first that does not fit.
std::optional<std::vector<Value>> decodeArguments(const WireSignature& signature, const nlohmann::json& args,
                                                  std::string& error);

// Arguments written by parameter name.
nlohmann::json encodeArguments(const WireSignature& signature, const std::vector<Value>& args);

// An observation object ({"hour": 7, "stock": {"salt": 12.5, ...}}: a family as an object by member) read
// against every key of the schema; nullopt with `error` listing what is missing, undeclared or ill-typed.
std::optional<Observation> decodeObservation(const ProtocolSchema& schema, const nlohmann::json& json,
                                             std::string& error);

// The observation written as decodeObservation reads it (a family as an object by member).
nlohmann::json encodeObservation(const ProtocolSchema& schema, const Observation& observation);

}  // namespace cbtl::sim
