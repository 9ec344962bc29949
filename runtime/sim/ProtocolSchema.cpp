#include "runtime/sim/ProtocolSchema.h"

#include "runtime/core/Values.h"  // rt::RuntimeError

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cbtl::sim {

namespace {

using nlohmann::json;

std::string where(const ir::Span& s) {
  if (s.file.empty()) return {};
  return fmt::format("{}:{}:{}", s.file, s.line, s.column);
}

// The names an enum or item type allows; empty when `name` is neither (text).
std::vector<std::string> membersOf(const ir::ConstraintGraph& g, const std::string& name) {
  for (const ir::Enum& e : g.enums)
    if (e.name == name) return e.members;
  std::vector<std::string> entries;
  for (const ir::ItemSet& set : g.itemSets)
    if (set.itemType == name)
      for (const ir::ItemEntry& entry : set.entries) entries.push_back(entry.name);
  return entries;
}

// The number between `open` and the last '>' of a spelling such as "vec<3>"; 0 when there is none.
std::size_t widthIn(const std::string& spelling) {
  const auto lt = spelling.find('<');
  const auto gt = spelling.rfind('>');
  if (lt == std::string::npos || gt == std::string::npos || gt <= lt + 1) return 0;
  try {
    return static_cast<std::size_t>(std::stoul(spelling.substr(lt + 1, gt - lt - 1)));
  } catch (const std::exception&) {
    return 0;
  }
}

std::string innerOf(const std::string& spelling) {
  const auto lt = spelling.find('<');
  const auto gt = spelling.rfind('>');
  if (lt == std::string::npos || gt == std::string::npos || gt <= lt + 1) return {};
  return spelling.substr(lt + 1, gt - lt - 1);
}

WireType wireType(const ir::ConstraintGraph& g, const ir::TypeDesc& t) {
  WireType w;
  w.spelling = t.spelling;
  switch (t.kind) {
    case ir::TypeKind::Real:
      w.kind = WireType::Kind::Real;
      return w;
    case ir::TypeKind::Int:
      w.kind = WireType::Kind::Int;
      return w;
    case ir::TypeKind::Bool:
      w.kind = WireType::Kind::Bool;
      return w;
    case ir::TypeKind::Text:
      w.kind = WireType::Kind::Name;
      return w;
    case ir::TypeKind::Enum:
    case ir::TypeKind::Item:
      w.kind = WireType::Kind::Name;
      w.members = membersOf(g, t.spelling);
      return w;
    case ir::TypeKind::Vec:
      w.kind = WireType::Kind::Vector;
      w.width = widthIn(t.spelling);
      return w;
    case ir::TypeKind::SE2:
      w.kind = WireType::Kind::Vector;
      w.width = 3;
      return w;
    case ir::TypeKind::SE3:
      w.kind = WireType::Kind::Vector;
      w.width = 7;
      return w;
    case ir::TypeKind::Conf: {
      w.kind = WireType::Kind::Vector;
      const std::string robot = innerOf(t.spelling);
      w.width = 0;
      for (const ir::Robot& r : g.robots)
        if (r.name == robot) w.width = static_cast<std::size_t>(r.dof);
      return w;
    }
    case ir::TypeKind::Set:
      w.kind = WireType::Kind::Names;
      w.members = membersOf(g, innerOf(t.spelling));
      return w;
    default:
      throw rt::RuntimeError("", fmt::format("values of type '{}' cannot cross the simulator protocol", t.spelling));
  }
}

WireSignature signatureOf(const ir::ConstraintGraph& g, const ir::Function& f) {
  WireSignature s;
  s.name = f.name;
  s.declaredAt = where(f.span);
  for (const ir::Param& p : f.params) s.params.push_back({p.name, wireType(g, p.type)});
  return s;
}

void collectCalls(const std::vector<ir::Action>& actions, std::set<std::string>& names) {
  for (const ir::Action& a : actions) {
    if (a.kind == ir::ActionKind::Call) names.insert(a.name);
    collectCalls(a.body, names);
    collectCalls(a.elseBody, names);
  }
}

std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? (names.size() > 2 ? ", or " : " or ") : ", ";
    out += names[i];
  }
  return out;
}

std::string shortJson(const json& j) {
  std::string s = j.dump();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

bool isMember(const WireType& t, const std::string& name) {
  return t.members.empty() || std::find(t.members.begin(), t.members.end(), name) != t.members.end();
}

}  // namespace

ProtocolSchema ProtocolSchema::fromProgram(const ir::ConstraintGraph& g, const std::vector<std::string>& keys) {
  ProtocolSchema s;
  s.domain = g.domain;
  std::map<std::string, const ir::Observation*> declared;
  for (const ir::Observation& o : g.observations) {
    declared[o.name] = &o;
    s.observationNames[o.name] = where(o.span);
  }
  for (const std::string& key : keys) {
    const std::string base = key.substr(0, key.find('['));
    const auto it = declared.find(base);
    if (it == declared.end()) throw rt::RuntimeError("", fmt::format("the program reads no observation '{}'", key));
    s.observations[key] = wireType(g, it->second->type);
  }
  std::set<std::string> called;
  for (const ir::Task& t : g.tasks) {
    s.tasks.push_back(t.name);
    for (const ir::SkillInstance& i : t.instances) collectCalls(i.actions, called);
  }
  for (const ir::Function& f : g.functions)
    if (f.kind == ir::FunctionKind::Action && called.count(f.name) > 0) s.actions[f.name] = signatureOf(g, f);
  for (const ir::Function& f : g.feedback) s.feedback[f.name] = signatureOf(g, f);
  for (const ir::Generator& gen : g.generators)
    for (const ir::LearnRule& r : gen.learnRules) s.learnedEvents.insert(r.event);
  return s;
}

json encodeValue(const WireType& type, const Value& value) {
  switch (type.kind) {
    case WireType::Kind::Real:
      return value.number;
    case WireType::Kind::Int:
      return static_cast<std::int64_t>(std::llround(value.number));
    case WireType::Kind::Bool:
      return value.number != 0;
    case WireType::Kind::Name:
      return value.text;
    case WireType::Kind::Vector:
      return value.vector;
    case WireType::Kind::Names:
      return value.members;
  }
  return nullptr;
}

std::optional<Value> decodeValue(const WireType& type, const json& j, std::string& error) {
  switch (type.kind) {
    case WireType::Kind::Real:
      if (j.is_number() && std::isfinite(j.get<double>())) return Value::num(j.get<double>());
      error = fmt::format("expected a finite number ({}), got {}", type.spelling, shortJson(j));
      return std::nullopt;
    case WireType::Kind::Int:
      if (j.is_number_integer()) return Value::num(static_cast<double>(j.get<std::int64_t>()));
      if (j.is_number_float() && std::isfinite(j.get<double>()) && j.get<double>() == std::floor(j.get<double>()) &&
          std::fabs(j.get<double>()) < 9.0e15)
        return Value::num(j.get<double>());
      error = fmt::format("expected an integer ({}), got {}", type.spelling, shortJson(j));
      return std::nullopt;
    case WireType::Kind::Bool:
      if (j.is_boolean()) return Value::num(j.get<bool>() ? 1.0 : 0.0);
      error = fmt::format("expected true or false ({}), got {}", type.spelling, shortJson(j));
      return std::nullopt;
    case WireType::Kind::Name:
      if (!j.is_string()) {
        error = fmt::format("expected a string ({}), got {}", type.spelling, shortJson(j));
        return std::nullopt;
      }
      if (!isMember(type, j.get<std::string>())) {
        error =
            fmt::format("'{}' is not a {} (expected {})", j.get<std::string>(), type.spelling, listed(type.members));
        return std::nullopt;
      }
      return Value::name(j.get<std::string>());
    case WireType::Kind::Vector: {
      if (!j.is_array() || j.size() != type.width) {
        error = fmt::format("expected an array of {} numbers ({}), got {}", type.width, type.spelling, shortJson(j));
        return std::nullopt;
      }
      std::vector<double> v;
      for (const json& e : j) {
        if (!e.is_number() || !std::isfinite(e.get<double>())) {
          error = fmt::format("expected an array of {} finite numbers ({}), got {}", type.width, type.spelling,
                              shortJson(j));
          return std::nullopt;
        }
        v.push_back(e.get<double>());
      }
      return Value::vec(std::move(v));
    }
    case WireType::Kind::Names: {
      if (!j.is_array()) {
        error = fmt::format("expected an array of names ({}), got {}", type.spelling, shortJson(j));
        return std::nullopt;
      }
      std::vector<std::string> names;
      for (const json& e : j) {
        if (!e.is_string()) {
          error = fmt::format("expected an array of names ({}), got {}", type.spelling, shortJson(j));
          return std::nullopt;
        }
        if (!isMember(type, e.get<std::string>())) {
          error = fmt::format("'{}' is not an element of {} (expected {})", e.get<std::string>(), type.spelling,
                              listed(type.members));
          return std::nullopt;
        }
        names.push_back(e.get<std::string>());
      }
      return Value::names(std::move(names));
    }
  }
  return std::nullopt;
}

std::optional<std::vector<Value>> decodeArguments(const WireSignature& sig, const json& args, std::string& error) {
  std::vector<Value> out;
  if (args.is_array()) {
    if (args.size() != sig.params.size()) {
      error = fmt::format("{} takes {} argument(s), got {}", sig.name, sig.params.size(), args.size());
      return std::nullopt;
    }
    for (std::size_t i = 0; i < args.size(); ++i) {
      auto v = decodeValue(sig.params[i].type, args[i], error);
      if (!v) {
        error = fmt::format("{} argument {} '{}': {}", sig.name, i + 1, sig.params[i].name, error);
        return std::nullopt;
      }
      out.push_back(std::move(*v));
    }
    return out;
  }
  if (!args.is_object()) {
    error = fmt::format("{}'s arguments must be an object by parameter name or an array, got {}", sig.name,
                        shortJson(args));
    return std::nullopt;
  }
  for (const auto& [key, _] : args.items()) {
    const bool known =
        std::any_of(sig.params.begin(), sig.params.end(), [&](const WireParam& p) { return p.name == key; });
    if (!known) {
      std::vector<std::string> names;
      for (const WireParam& p : sig.params) names.push_back(p.name);
      error = fmt::format("{} has no parameter '{}' (its parameters: {})", sig.name, key,
                          names.empty() ? std::string("none") : listed(names));
      return std::nullopt;
    }
  }
  for (const WireParam& p : sig.params) {
    const auto it = args.find(p.name);
    if (it == args.end()) {
      error = fmt::format("{} is missing its argument '{}' ({})", sig.name, p.name, p.type.spelling);
      return std::nullopt;
    }
    auto v = decodeValue(p.type, *it, error);
    if (!v) {
      error = fmt::format("{} argument '{}': {}", sig.name, p.name, error);
      return std::nullopt;
    }
    out.push_back(std::move(*v));
  }
  return out;
}

json encodeArguments(const WireSignature& sig, const std::vector<Value>& args) {
  json out = json::object();
  for (std::size_t i = 0; i < sig.params.size() && i < args.size(); ++i)
    out[sig.params[i].name] = encodeValue(sig.params[i].type, args[i]);
  return out;
}

std::optional<Observation> decodeObservation(const ProtocolSchema& schema, const json& j, std::string& error) {
  if (!j.is_object()) {
    error = fmt::format("the observation must be an object by observation name, got {}", shortJson(j));
    return std::nullopt;
  }
  Observation out;
  std::vector<std::string> problems;
  auto readOne = [&](const std::string& key, const json& value) {
    const auto it = schema.observations.find(key);
    std::string why;
    if (auto v = decodeValue(it->second, value, why)) {
      out[key] = std::move(*v);
    } else {
      problems.push_back(fmt::format("'{}': {}", key, why));
    }
  };
  for (const auto& [name, value] : j.items()) {
    if (schema.observations.count(name) > 0) {
      readOne(name, value);
    } else if (value.is_object() && schema.observationNames.count(name) > 0) {
      for (const auto& [member, v] : value.items()) {
        const std::string key = name + "[" + member + "]";
        if (schema.observations.count(key) > 0)
          readOne(key, v);
        else
          problems.push_back(fmt::format("'{}' has no member '{}'", name, member));
      }
    } else if (schema.observationNames.count(name) > 0) {
      problems.push_back(fmt::format("'{}' is a family: give an object by member, got {}", name, shortJson(value)));
    } else {
      problems.push_back(fmt::format("'{}' is not an observation of the program", name));
    }
  }
  for (const auto& [key, _] : schema.observations)
    if (out.count(key) == 0 && std::none_of(problems.begin(), problems.end(),
                                            [&](const std::string& p) { return p.rfind("'" + key + "'", 0) == 0; }))
      problems.push_back(fmt::format("'{}' is missing", key));
  if (!problems.empty()) {
    error = problems.front();
    for (std::size_t i = 1; i < problems.size() && i < 8; ++i) error += "; " + problems[i];
    if (problems.size() > 8) error += fmt::format("; and {} more", problems.size() - 8);
    return std::nullopt;
  }
  return out;
}

json encodeObservation(const ProtocolSchema& schema, const Observation& observation) {
  json out = json::object();
  for (const auto& [key, value] : observation) {
    const auto type = schema.observations.find(key);
    if (type == schema.observations.end()) continue;
    const auto open = key.find('[');
    if (open == std::string::npos) {
      out[key] = encodeValue(type->second, value);
    } else {
      const std::string member = key.substr(open + 1, key.size() - open - 2);
      out[key.substr(0, open)][member] = encodeValue(type->second, value);
    }
  }
  return out;
}

}  // namespace cbtl::sim
