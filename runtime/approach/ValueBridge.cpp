#include "runtime/approach/ValueBridge.h"

#include <fmt/format.h>

namespace cbtl::approach {

using rt::ValueKind;

sim::Value toSimValue(const rt::Program& program, const rt::ValueType& type, const double* v) {
  switch (type.kind) {
    case ValueKind::Enum:
    case ValueKind::Item:
    case ValueKind::Text:
      return sim::Value::name(program.render(type, v));
    case ValueKind::Vec:
    case ValueKind::SE2:
    case ValueKind::SE3:
    case ValueKind::Conf:
      return sim::Value::vec(std::vector<double>(v, v + type.width));
    default:
      return sim::Value::num(v[0]);
  }
}

bool fromSimValue(const rt::Program& program, const rt::ValueType& type, const sim::Value& value, double* out,
                  std::string& error) {
  switch (type.kind) {
    case ValueKind::Enum:
    case ValueKind::Item:
    case ValueKind::Text:
      if (value.kind != sim::Value::Kind::Name) {
        error = fmt::format("expected a name of {}", type.typeName.empty() ? "text" : type.typeName);
        return false;
      }
      if (!program.parseName(type, value.text, out[0])) {
        error = fmt::format("'{}' is not a member of {}", value.text, type.typeName);
        return false;
      }
      return true;
    case ValueKind::Vec:
    case ValueKind::SE2:
    case ValueKind::SE3:
    case ValueKind::Conf:
      if (value.kind != sim::Value::Kind::Vector || value.vector.size() != type.width) {
        error = fmt::format("expected {} numbers", type.width);
        return false;
      }
      std::copy(value.vector.begin(), value.vector.end(), out);
      return true;
    case ValueKind::Set: {
      if (value.kind != sim::Value::Kind::Names) {
        error = fmt::format("expected a set of {}", type.typeName);
        return false;
      }
      std::fill(out, out + type.width, 0.0);
      const rt::ValueType elem = program.setElementType(type);
      for (const auto& m : value.members) {
        double index = 0;
        if (!program.parseName(elem, m, index) || index < 0 || index >= type.width) {
          error = fmt::format("'{}' is not a member of {}", m, type.typeName);
          return false;
        }
        out[static_cast<std::size_t>(index)] = 1;
      }
      return true;
    }
    default:
      if (value.kind != sim::Value::Kind::Number) {
        error = fmt::format("expected a number ({})", rt::toString(type.kind));
        return false;
      }
      out[0] = value.number;
      return true;
  }
}

std::vector<double> observationVector(const rt::Program& program, const sim::Observation& observation) {
  std::vector<double> out(program.observationWidth(), 0.0);
  for (const auto& [key, slot] : program.observationSlots()) {
    auto it = observation.find(key);
    if (it == observation.end()) {
      throw rt::RuntimeError("", fmt::format("the simulator did not provide the observation '{}'", key));
    }
    std::string error;
    if (!fromSimValue(program, slot.type, it->second, out.data() + slot.offset, error)) {
      throw rt::RuntimeError("", fmt::format("observation '{}': {}", key, error));
    }
  }
  return out;
}

}  // namespace cbtl::approach
