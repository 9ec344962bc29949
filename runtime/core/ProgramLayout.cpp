// Program's type facts and value layout: ValueType of an IR type, enum/item look-ups, rendering and parsing
// of values, where variables and observations sit in their vectors, and the initial assignment.
#include "runtime/core/Program.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cbtl::rt {

const char* toString(ValueKind k) {
  switch (k) {
    case ValueKind::Real:
      return "real";
    case ValueKind::Int:
      return "int";
    case ValueKind::Bool:
      return "bool";
    case ValueKind::Enum:
      return "enum";
    case ValueKind::Item:
      return "item";
    case ValueKind::Text:
      return "text";
    case ValueKind::Vec:
      return "vec";
    case ValueKind::SE2:
      return "SE2";
    case ValueKind::SE3:
      return "SE3";
    case ValueKind::Conf:
      return "Conf";
    case ValueKind::Set:
      return "set";
    case ValueKind::Range:
      return "range";
    case ValueKind::Void:
      return "void";
  }
  return "?";
}

namespace {

int angleParam(const std::string& spelling) {
  const auto lt = spelling.find('<'), gt = spelling.rfind('>');
  if (lt == std::string::npos || gt == std::string::npos || gt <= lt + 1) return -1;
  try {
    return std::stoi(spelling.substr(lt + 1, gt - lt - 1));
  } catch (...) {
    return -1;
  }
}

std::string innerName(const std::string& spelling) {
  const auto lt = spelling.find('<'), gt = spelling.rfind('>');
  if (lt == std::string::npos || gt == std::string::npos) return {};
  return spelling.substr(lt + 1, gt - lt - 1);
}

}  // namespace

std::string Program::where(const ir::Span& s) {
  if (s.file.empty()) return {};
  return fmt::format("{}:{}:{}", s.file, s.line, s.column);
}

const ir::Enum* Program::findEnum(const std::string& name) const {
  for (const auto& e : graph_.enums) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

const ir::ItemSet* Program::findItemSetOfType(const std::string& itemType) const {
  for (const auto& s : graph_.itemSets) {
    if (s.itemType == itemType) return &s;
  }
  return nullptr;
}

const ir::ItemSet* Program::findItemSet(const std::string& name) const {
  for (const auto& s : graph_.itemSets) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

const ir::Task* Program::findTask(const std::string& name) const {
  for (const auto& t : graph_.tasks) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

ValueType Program::typeOf(const ir::TypeDesc& t) const {
  ValueType v;
  switch (t.kind) {
    case ir::TypeKind::Real:
      v.kind = ValueKind::Real;
      break;
    case ir::TypeKind::Int:
      v.kind = ValueKind::Int;
      break;
    case ir::TypeKind::Bool:
      v.kind = ValueKind::Bool;
      break;
    case ir::TypeKind::Text:
      v.kind = ValueKind::Text;
      break;
    case ir::TypeKind::Enum:
      v.kind = ValueKind::Enum;
      v.typeName = t.spelling;
      break;
    case ir::TypeKind::Item:
      v.kind = ValueKind::Item;
      v.typeName = t.spelling;
      break;
    case ir::TypeKind::Vec: {
      v.kind = ValueKind::Vec;
      const int n = angleParam(t.spelling);
      v.width = static_cast<std::uint16_t>(n > 0 ? n : 1);
      break;
    }
    case ir::TypeKind::SE2:
      v.kind = ValueKind::SE2;
      v.width = 3;
      break;
    case ir::TypeKind::SE3:
      v.kind = ValueKind::SE3;
      v.width = 7;
      break;
    case ir::TypeKind::Conf:
      v.kind = ValueKind::Conf;
      v.typeName = innerName(t.spelling);
      v.width = 7;
      for (const auto& r : graph_.robots) {
        if (r.name == v.typeName) v.width = static_cast<std::uint16_t>(r.dof);
      }
      break;
    case ir::TypeKind::Set:
      v.kind = ValueKind::Set;
      v.width = 0;
      v.typeName = innerName(t.spelling);
      break;
    case ir::TypeKind::Range:
      v.kind = ValueKind::Range;
      v.width = 0;
      break;
    case ir::TypeKind::Error:  // no value at run time
    case ir::TypeKind::Tuple:
    case ir::TypeKind::Void:
      v.kind = ValueKind::Void;
      v.width = 0;
      break;
  }
  return v;
}

std::optional<double> Program::memberIndex(const std::string& typeName, const std::string& member) const {
  if (const auto* e = findEnum(typeName)) {
    for (std::size_t i = 0; i < e->members.size(); ++i) {
      if (e->members[i] == member) return static_cast<double>(i);
    }
  }
  const ir::ItemSet* s = findItemSet(typeName);
  if (s == nullptr) s = findItemSetOfType(typeName);
  if (s != nullptr) {
    for (std::size_t i = 0; i < s->entries.size(); ++i) {
      if (s->entries[i].name == member) return static_cast<double>(i);
    }
  }
  return std::nullopt;
}

bool Program::parseName(const ValueType& t, const std::string& name, double& out) const {
  if (t.kind == ValueKind::Text) {
    out = strings_.intern(name);
    return true;
  }
  const auto index = memberIndex(t.typeName, name);
  if (index) out = *index;
  return index.has_value();
}

std::string Program::render(const ValueType& t, const double* v) const {
  switch (t.kind) {
    case ValueKind::Bool:
      return v[0] != 0 ? "true" : "false";
    case ValueKind::Int:
      return fmt::format("{}", static_cast<long long>(std::llround(v[0])));
    case ValueKind::Real:
      return fmt::format("{:.6g}", v[0]);
    case ValueKind::Text: {
      const auto id = static_cast<std::uint32_t>(v[0]);
      return id < strings_.size() ? strings_.name(id) : "?";
    }
    case ValueKind::Enum: {
      const auto* e = findEnum(t.typeName);
      const auto i = static_cast<std::size_t>(v[0]);
      return e != nullptr && i < e->members.size() ? e->members[i] : "?";
    }
    case ValueKind::Item: {
      const auto* s = findItemSetOfType(t.typeName);
      const auto i = static_cast<std::size_t>(v[0]);
      return s != nullptr && i < s->entries.size() ? s->entries[i].name : "?";
    }
    default: {
      std::string out = "(";
      for (std::size_t i = 0; i < t.width; ++i) out += fmt::format("{}{:.6g}", i ? ", " : "", v[i]);
      return out + ")";
    }
  }
}

std::optional<std::uint32_t> Program::observationOffset(const std::string& key) const {
  auto it = obsSlots_.find(key);
  if (it == obsSlots_.end()) return std::nullopt;
  return it->second.offset;
}

// --- layout -------------------------------------------------------------------------------------------

void Program::layoutVariables() {
  slots_.resize(graph_.variables.size());
  for (const auto& v : graph_.variables) {
    if (v.id >= slots_.size()) throw RuntimeError(where(v.span), "variable ids are not dense");
    VarSlot& s = slots_[v.id];
    s.type = typeOf(v.type);
    s.offset = static_cast<std::uint32_t>(assignmentWidth_);
    assignmentWidth_ += s.type.width;
  }
}

std::vector<double> Program::initialAssignment(const std::vector<double>& observation) const {
  std::vector<double> x(assignmentWidth_, 0.0);
  std::vector<double> obs = observation;
  obs.resize(std::max(obsWidth_, std::size_t{1}), 0.0);
  std::vector<double> frame(frameSize_, 0.0);
  EvalContext ctx{x.data(), obs.data(), frame.data(), &callContext_};
  // A variable with no `= init` starts at zero moved into its declared domain: each bounded component
  // clamped to its bounds, a set domain's first member when zero is not one. Zero alone could lie outside a
  // domain such as 1 .. 2, and a variable that no sampler writes would keep it.
  for (const auto& v : graph_.variables) {
    if (v.init) continue;
    const DomainCheck& d = domainChecks_[v.id];
    double* at = x.data() + slots_[v.id].offset;
    for (std::size_t c = 0; c < d.lo.size() && c < slots_[v.id].type.width; ++c) {
      if (d.lo[c] != UINT32_MAX) at[c] = std::max(at[c], pool_.evalScalar(d.lo[c], ctx));
      if (d.hi[c] != UINT32_MAX) at[c] = std::min(at[c], pool_.evalScalar(d.hi[c], ctx));
      if (slots_[v.id].type.kind == ValueKind::Int) at[c] = std::ceil(at[c]);
    }
    if (d.members && !d.members->empty() &&
        std::find(d.members->begin(), d.members->end(), at[0]) == d.members->end()) {
      at[0] = d.members->front();
    }
  }
  double value[kMaxValueWidth];
  for (const auto& [var, node] : inits_) {
    const VarSlot& s = slots_[var];
    pool_.eval(node, ctx, value);
    std::copy_n(value, s.type.width, x.begin() + s.offset);
  }
  return x;
}

ValueType Program::setElementType(const ValueType& set) const {
  if (findEnum(set.typeName) != nullptr) return ValueType{ValueKind::Enum, 1, set.typeName};
  return ValueType{ValueKind::Item, 1, set.typeName};
}

std::size_t Program::setElementCount(const ValueType& set) const {
  if (const auto* e = findEnum(set.typeName)) return e->members.size();
  if (const auto* s = findItemSetOfType(set.typeName)) return s->entries.size();
  return 0;
}

void Program::layoutObservations() {
  for (const auto& o : graph_.observations) {
    ValueType t = typeOf(o.type);
    if (t.kind == ValueKind::Set) {
      const std::size_t n = setElementCount(t);
      if (n == 0 || o.indexSet) {
        throw RuntimeError(
            where(o.span),
            fmt::format("observation '{}': only a set of enum members or items can be observed", o.name));
      }
      t.width = static_cast<std::uint16_t>(n);
    }
    if (!o.indexSet) {
      obsSlots_[o.name] = VarSlot{static_cast<std::uint32_t>(obsWidth_), t};
      obsWidth_ += t.width;
      continue;
    }
    const auto* e = o.indexSet->op == ir::Op::EnumSet ? findEnum(o.indexSet->text) : nullptr;
    const auto* items = o.indexSet->op == ir::Op::ItemSet ? findItemSet(o.indexSet->text) : nullptr;
    std::vector<std::string> members;
    if (e != nullptr) members = e->members;
    if (items != nullptr) {
      for (const auto& en : items->entries) members.push_back(en.name);
    }
    if (members.empty())
      throw RuntimeError(where(o.span), fmt::format("observation family '{}' needs an enum or item index set", o.name));
    for (const auto& m : members) {
      obsSlots_[o.name + "[" + m + "]"] = VarSlot{static_cast<std::uint32_t>(obsWidth_), t};
      obsWidth_ += t.width;
    }
  }
}

}  // namespace cbtl::rt
