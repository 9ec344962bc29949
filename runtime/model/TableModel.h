// TableModel.h — a per-key tri-state table: unknown (P = 0.5, one bit of uncertainty), holds (1), fails (0).
//
// Keys are the rendered values of the factor's key expression (an enum member, an item entry, ...). The latest
// label for a key wins, so a user who changes their mind is believed (the reference kept the first).
#pragma once

#include <map>
#include <string>

namespace cbtl::model {

class TableModel {
 public:
  void observe(const std::string& key, bool holds) { table_[key] = holds; }
  void reset() { table_.clear(); }
  double probability(const std::string& key) const {
    auto it = table_.find(key);
    return it == table_.end() ? 0.5 : (it->second ? 1.0 : 0.0);
  }
  const std::map<std::string, bool>& entries() const { return table_; }

 private:
  std::map<std::string, bool> table_;
};

}  // namespace cbtl::model
