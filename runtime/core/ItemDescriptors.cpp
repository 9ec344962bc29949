#include "runtime/core/ItemDescriptors.h"

#include <fmt/format.h>

#include <cmath>

namespace cbtl::rt {

namespace {

const std::vector<textpref::Item>* findIn(const std::map<std::string, std::vector<textpref::Item>>& m,
                                          const std::string& name) {
  auto it = m.find(name);
  return it == m.end() ? nullptr : &it->second;
}

}  // namespace

std::vector<std::string> ItemDescriptors::fieldStrings(const ir::Expr& value, const RenderConstant& renderOther) {
  const ir::Op op = value.op;
  if (op == ir::Op::Str || op == ir::Op::Enum || op == ir::Op::Item) return {value.text};
  if (op == ir::Op::Bool) return {value.number != 0 ? "true" : "false"};
  if (op == ir::Op::Num) {
    // The same spelling Program::render gives the value at run time.
    if (value.type.kind == ir::TypeKind::Int)
      return {fmt::format("{}", static_cast<long long>(std::llround(value.number)))};
    return {fmt::format("{:.6g}", value.number)};
  }
  if (op == ir::Op::List) {
    std::vector<std::string> out;
    for (const auto& element : value.children) {
      auto strings = fieldStrings(element, renderOther);
      out.insert(out.end(), strings.begin(), strings.end());
    }
    return out;
  }
  if (renderOther) return renderOther(value);
  return {};
}

void ItemDescriptors::addType(const ir::ConstraintGraph& graph, const ir::TypeDesc& t,
                              const RenderConstant& renderOther) {
  if (t.kind == ir::TypeKind::Enum && !enums_.count(t.spelling)) {
    std::vector<textpref::Item> items;
    for (const auto& e : graph.enums) {
      if (e.name != t.spelling) continue;
      for (const auto& member : e.members) items.push_back(textpref::Item{member, {}});
      break;
    }
    enums_.emplace(t.spelling, std::move(items));
  } else if (t.kind == ir::TypeKind::Item && !itemTypes_.count(t.spelling)) {
    std::vector<textpref::Item> items;
    for (const auto& set : graph.itemSets) {
      if (set.itemType != t.spelling) continue;
      for (const auto& entry : set.entries) {
        textpref::Item item{entry.name, {}};
        for (const auto& [field, value] : entry.fields) {
          auto strings = fieldStrings(value, renderOther);
          if (!strings.empty()) item.descriptors[field] = std::move(strings);
        }
        items.push_back(std::move(item));
      }
      break;  // the first set of the type, as Program::render
    }
    itemTypes_.emplace(t.spelling, std::move(items));
  }
}

ItemDescriptors::ItemDescriptors(const ir::ConstraintGraph& graph, const RenderConstant& renderOther) {
  for (const auto& g : graph.generators) {
    for (const auto& f : g.factors) {
      if (f.kind != ir::FactorKind::Text) continue;
      if (f.feature) addType(graph, f.feature->type, renderOther);
      for (const auto& entry : f.context) addType(graph, entry.value.type, renderOther);
    }
  }
}

const std::vector<textpref::Item>* ItemDescriptors::domain(const ValueType& type) const {
  if (type.kind == ValueKind::Item) return findIn(itemTypes_, type.typeName);
  if (type.kind == ValueKind::Enum) return findIn(enums_, type.typeName);
  return nullptr;
}

const textpref::Item* ItemDescriptors::item(const ValueType& type, double value) const {
  const auto* items = domain(type);
  if (items == nullptr || !(value >= 0) || value >= static_cast<double>(items->size())) return nullptr;
  return &(*items)[static_cast<std::size_t>(value)];
}

}  // namespace cbtl::rt
