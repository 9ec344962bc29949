// Program.h — a constraint graph prepared for execution: the value layout of every variable and
// observation, interned strings, type facts, and every constraint, sampler, cost and generator expression
// compiled once into an ExprPool (by runtime/core/ProgramCompiler.h).
//
// Built once per graph; read-only afterwards, so any number of solvers may share it. Everything the solve
// loop touches is an index or an offset. Expressions compiled later (personalized instances, actions) go
// through a ProgramCompiler over the same program before it is shared.
#pragma once

#include "runtime/core/Builtins.h"
#include "runtime/core/Expression.h"
#include "runtime/core/ItemDescriptors.h"
#include "runtime/core/Values.h"

#include "ir/ConstraintGraph.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::rt {

struct VarSlot {
  std::uint32_t offset = 0;
  ValueType type;
};

// How a variable is drawn by `sample x ~ uniform`: one entry per component.
struct UniformPlan {
  enum class Kind { Real, Int, Bool, Choice } kind = Kind::Real;
  std::vector<std::uint32_t> lo, hi;  // Real/Int: one bound node per component (`uniform` needs both bounds)
  std::vector<double> choices;        // Choice: the allowed values (enum indices, text ids, ...)
  // Choice over an observed set (`var b : Book in pickable`): the observation offset of its membership flags
  // (one per member, in member order); the draw is uniform over the members the observation lists.
  std::optional<std::uint32_t> observedFlags;
};

struct CompiledSampler {
  const ir::Sampler* source = nullptr;
  std::vector<ir::VarId> writes;
  SamplerImpl impl = nullptr;       // extern sampler; null for `uniform`
  std::vector<std::uint32_t> args;  // argument nodes
  std::vector<std::uint16_t> argWidths;
  std::vector<UniformPlan> uniform;  // per written variable, for `uniform`
  std::size_t outWidth = 0;          // doubles it writes: the widths of `writes`, added up
  std::size_t argsWidth = 0;         // doubles its arguments take
};

// A variable's declared domain compiled for the independent re-check of solutions (solver/Recheck.h): per
// bounded component its bound nodes (UINT32_MAX: that side is unbounded), and the allowed values of a set
// domain. Observed-set domains are checked by their `.domain` constraints instead.
struct DomainCheck {
  std::vector<std::uint32_t> lo, hi;  // component order as declared (SE3: x y z)
  std::optional<std::vector<double>> members;
};

struct CompiledConstraint {
  const ir::Constraint* source = nullptr;
  std::uint32_t root = 0;
};

// A text factor's `context:` compiled against one scope (TextContext.h): one scalar node per entry.
struct CompiledContext {
  std::vector<std::string> names;    // per entry: the key the models see (the name as written)
  std::vector<std::uint32_t> nodes;  // per entry
  std::vector<ValueType> types;      // per entry
  bool empty() const { return nodes.empty(); }
};

struct CompiledFactor {
  const ir::ModelFactor* source = nullptr;
};

// A learning rule compiled against its frame: the event's arguments laid out one after another, binders
// and the generator parameters they bind read from there.
struct CompiledLearnRule {
  const ir::LearnRule* source = nullptr;
  std::uint32_t eventIndex = 0;            // into graph.feedback
  std::vector<std::uint32_t> binderFrame;  // frame offset of each event argument
  std::vector<ValueType> binderTypes;
  std::vector<std::pair<int, std::uint32_t>> labels;  // (factor index, label node)
  std::vector<std::uint32_t> features;                // per label: the factor's feature node, or UINT32_MAX
  std::vector<CompiledContext> contexts;              // per label: a text factor's context, over the rule's frame
  std::vector<std::uint32_t> keys;                    // per `per` key: its expression's node, or UINT32_MAX (a name)
  std::vector<ValueType> keyTypes;                    // per `per` key: the expression's type
  std::optional<std::uint32_t> condition;
  std::uint32_t frameWidth = 0;
};

struct CompiledGenerator {
  const ir::Generator* source = nullptr;
  std::vector<ValueType> paramTypes;
  std::vector<CompiledFactor> factors;
  std::vector<CompiledLearnRule> rules;
};

class Program {
 public:
  // Throws RuntimeError (with the offending source location) for anything it cannot execute.
  Program(const ir::ConstraintGraph& graph, Builtins builtins);

  const ir::ConstraintGraph& graph() const { return graph_; }
  const ExprPool& pool() const { return pool_; }
  ExprPool& pool() { return pool_; }
  StringTable& strings() const { return strings_; }
  const Builtins& builtins() const { return builtins_; }
  // What every evaluation of this program hands its built-ins: the string table and the registry's host.
  const CallContext* callContext() const { return &callContext_; }
  BuiltinHost* host() const { return builtins_.host().get(); }

  const VarSlot& slot(ir::VarId v) const { return slots_.at(v); }
  std::size_t assignmentWidth() const { return assignmentWidth_; }
  // Initial values of every variable for a CSP whose world reads `observation` (laid out as
  // observationSlots() says): declared `= init` (which may read observations), else zero (false, the first
  // enum member or item, the empty text).
  std::vector<double> initialAssignment(const std::vector<double>& observation = {}) const;

  // Observations: "name" or "name[member]" -> offset; width of the whole observation vector.
  std::optional<std::uint32_t> observationOffset(const std::string& key) const;
  const std::map<std::string, VarSlot>& observationSlots() const { return obsSlots_; }
  std::size_t observationWidth() const { return obsWidth_; }

  const std::vector<CompiledConstraint>& constraints() const { return constraints_; }
  const DomainCheck& domainCheck(ir::VarId v) const { return domainChecks_.at(v); }
  const std::vector<CompiledSampler>& samplers() const { return samplers_; }
  const std::vector<CompiledGenerator>& generators() const { return generators_; }
  const std::vector<std::uint32_t>& costs() const { return costs_; }
  // Frame slots any expression compiled so far may touch (quantifier binders, event arguments): an
  // EvalContext's frame must hold at least this many. Grows when a ProgramCompiler compiles more
  // expressions (personalized instances, actions), so read it after preparing everything.
  std::size_t frameSize() const { return frameSize_; }
  // The widest sampler output and argument list of the program: the solver's buffers for a draw.
  std::size_t maxSamplerOutWidth() const { return maxSamplerOut_; }
  std::size_t maxSamplerArgsWidth() const { return maxSamplerArgs_; }
  // The textpref::Item of every subject value a text factor can be asked about (ItemDescriptors.h).
  const ItemDescriptors& itemDescriptors() const { return itemDescriptors_; }

  // Type facts.
  ValueType typeOf(const ir::TypeDesc& t) const;
  const ir::Enum* findEnum(const std::string& name) const;
  // The element type of a set type (enum member or item entry, one double), and how many values it has
  // (an observed set is laid out as that many 0/1 membership flags in member order). 0 when the element
  // type is neither an enum nor an item type.
  ValueType setElementType(const ValueType& set) const;
  std::size_t setElementCount(const ValueType& set) const;
  const ir::ItemSet* findItemSetOfType(const std::string& itemType) const;
  const ir::ItemSet* findItemSet(const std::string& name) const;
  const ir::Task* findTask(const std::string& name) const;
  const ir::Constant* findConstant(const std::string& name) const;
  const ir::Function* findFunction(const std::string& name) const;
  const ir::Observation* findObservation(const std::string& name) const;
  // The index of an enum member or item entry (`typeName`: the enum, the item set or the item type);
  // nullopt when it is not one.
  std::optional<double> memberIndex(const std::string& typeName, const std::string& member) const;

  // Whether evaluating node `root` reads the built-ins' host (the robot world's state): it calls a built-in
  // registered with readsHost. Such expressions are evaluated in the state of their skill (solver/StagedPlan.h).
  bool readsWorld(std::uint32_t root) const {
    return pool_.callsAny(root, [this](FunctionImpl f) { return builtins_.readsHost(f); });
  }
  // The same for a sampler: its implementation reads the host, or one of its arguments does.
  bool samplerReadsWorld(std::uint32_t sampler) const;

  // Renders a value (width doubles) for people: enum member names, strings, vectors "(x, y)".
  std::string render(const ValueType& t, const double* v) const;
  // Converts a value to the form the simulator boundary uses and back (enum members and texts by name).
  // Returns false when a name is not a member of its type.
  bool parseName(const ValueType& t, const std::string& name, double& out) const;

  static std::string where(const ir::Span& s);

 private:
  // The compiler appends to pool_ and grows frameSize_; everything else it reads through the accessors.
  friend class ProgramCompiler;

  void layoutVariables();
  void layoutObservations();

  const ir::ConstraintGraph& graph_;
  Builtins builtins_;
  ExprPool pool_;
  mutable StringTable strings_;
  CallContext callContext_;
  std::vector<VarSlot> slots_;
  std::size_t assignmentWidth_ = 0;
  std::vector<std::pair<ir::VarId, std::uint32_t>> inits_;  // variable, its initial value's node
  std::map<std::string, VarSlot> obsSlots_;
  std::size_t obsWidth_ = 0;
  std::vector<CompiledConstraint> constraints_;
  std::vector<DomainCheck> domainChecks_;
  std::vector<CompiledSampler> samplers_;
  std::vector<CompiledGenerator> generators_;
  std::vector<std::uint32_t> costs_;
  ItemDescriptors itemDescriptors_;
  std::map<std::string, const ir::Constant*> constants_;
  std::map<std::string, const ir::Function*> functions_;
  std::size_t frameSize_ = 1;
  std::size_t maxSamplerOut_ = 0, maxSamplerArgs_ = 0;
};

}  // namespace cbtl::rt
