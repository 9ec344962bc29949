// ItemDescriptors.h — what a `model text(subject, ...)` factor shows its text-preference model about a subject.
//
// A text factor's subject is an item, an enum member or a text (docs/language.md). The text-preference library
// (runtime/textpref) is asked about a textpref::Item: a name plus descriptor fields. The conversion is:
//   item entry   -> Item{entry name, one descriptor per declared field}: a text field gives one string, a
//                   list/set field one string per element, a number, bool, enum member or item its text;
//                   fields whose value is an empty list are left out;
//   enum member  -> Item{member name, {}};
//   text         -> Item{the text, {}} (texts have no fixed domain, so they are converted where they are read).
// The items of every item type and enum that some generator's text factor has as its subject type, or as the
// type of one of its context entries (TextContext.h), are built once, when the Program is prepared, so the solve
// loop only indexes a vector. An item type's domain is the entries of its first item set (the set Program::render
// names values by), in declaration order.
#pragma once

#include "runtime/core/Values.h"

#include "ir/ConstraintGraph.h"
#include "runtime/textpref/Item.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace cbtl::rt {

class ItemDescriptors {
 public:
  // Turns a field value that is not a literal (a constant reference, arithmetic, ...) into its strings. The
  // Program supplies it, since only the Program can evaluate constant expressions.
  using RenderConstant = std::function<std::vector<std::string>(const ir::Expr&)>;

  ItemDescriptors() = default;
  // Builds the items of every text-factor subject and context type of `graph`. Throws what `renderOther` throws.
  ItemDescriptors(const ir::ConstraintGraph& graph, const RenderConstant& renderOther);

  // Every item of a subject type with a fixed domain (item type or enum), in value order; null for any other
  // type, and for types no text factor reads.
  const std::vector<textpref::Item>* domain(const ValueType& type) const;
  // The item a value (entry or member index) stands for; null when `type` has no domain here or the value is
  // not an index into it.
  const textpref::Item* item(const ValueType& type, double value) const;

  // The strings of one field value (the conversion above); exposed for tests.
  static std::vector<std::string> fieldStrings(const ir::Expr& value, const RenderConstant& renderOther);

 private:
  void addType(const ir::ConstraintGraph& graph, const ir::TypeDesc& type, const RenderConstant& renderOther);

  std::map<std::string, std::vector<textpref::Item>> itemTypes_;  // by item type name
  std::map<std::string, std::vector<textpref::Item>> enums_;      // by enum name
};

}  // namespace cbtl::rt
