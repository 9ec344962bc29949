// Values.h — how the runtime stores values: every value is a short run of doubles in a flat array.
//
//   real, int, bool (0/1)          1 double
//   enum member, item entry        1 double: the member's / entry's index in declaration order
//   text                           1 double: the id of the string in the program's StringTable
//   vec<N>                         N doubles
//   SE2                            3 doubles: x, y (m), yaw (rad)
//   SE3                            7 doubles: x, y, z (m), qx, qy, qz, qw
//   Conf<robot>                    dof doubles (rad)
//
// An assignment of a CSP is one std::vector<double> over the program's variable layout; nothing in the
// solve loop looks a name up or allocates.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace cbtl::rt {

enum class ValueKind { Real, Int, Bool, Enum, Item, Text, Vec, SE2, SE3, Conf, Set, Range, Void };

const char* toString(ValueKind k);

// A value's kind and width as the layout knows it. `typeName` is the enum / item type for Enum / Item.
struct ValueType {
  ValueKind kind = ValueKind::Real;
  std::uint16_t width = 1;
  std::string typeName;
};

// Interned strings: text values are ids into this table, so comparing texts compares doubles.
class StringTable {
 public:
  std::uint32_t intern(const std::string& s) {
    auto [it, inserted] = ids_.try_emplace(s, static_cast<std::uint32_t>(names_.size()));
    if (inserted) names_.push_back(s);
    return it->second;
  }
  const std::string& name(std::uint32_t id) const { return names_.at(id); }
  std::size_t size() const { return names_.size(); }

 private:
  std::unordered_map<std::string, std::uint32_t> ids_;
  std::vector<std::string> names_;
};

// An error found while preparing a graph for execution (an unsupported construct, a missing built-in, a
// bad observation). `where` is "file:line:col" when known.
struct RuntimeError : std::runtime_error {
  RuntimeError(const std::string& where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), location(where) {}
  std::string location;
};

}  // namespace cbtl::rt
