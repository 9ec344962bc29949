#include "compiler/driver/AstPrinter.h"

#include "compiler/sema/Type.h"

#include <fmt/format.h>

namespace cbtl {
namespace {

class Printer {
 public:
  explicit Printer(const SourceManager& s) : sources_(s) {}

  std::string run(const Module& m) {
    line(0,
         fmt::format("module {}{}", sources_.file(m.file).path, m.domainName.empty() ? "" : " domain " + m.domainName));
    for (const auto& d : m.decls) decl(*d, 1);
    return out_;
  }

 private:
  std::string at(SourceRange r) const {
    if (!r.valid()) return "";
    LineCol p = sources_.position(r.file, r.begin);
    return fmt::format(" @{}:{}", p.line, p.column);
  }
  void line(int depth, const std::string& text) {
    out_ += std::string(static_cast<std::size_t>(depth) * 2, ' ') + text + "\n";
  }

  static std::string typeOf(const Expr& e) { return e.type ? " : " + e.type->spelling : ""; }

  void expr(const Expr* e, int depth) {
    if (e == nullptr) {
      line(depth, "<none>");
      return;
    }
    std::string head;
    switch (e->kind) {
      case ExprKind::Number:
        head = "number " + e->text;
        break;
      case ExprKind::String:
        head = "string \"" + e->text + "\"";
        break;
      case ExprKind::Bool:
        head = e->boolean ? "bool true" : "bool false";
        break;
      case ExprKind::Name:
        head = "name " + e->text + ref(e->ref);
        break;
      case ExprKind::Member:
        head = "member ." + e->text + ref(e->ref);
        break;
      case ExprKind::Call:
        head = "call";
        break;
      case ExprKind::Index:
        head = "index";
        break;
      case ExprKind::Unary:
        head = std::string("unary ") + toString(e->unaryOp);
        break;
      case ExprKind::Binary:
        head = std::string("binary ") + toString(e->binaryOp);
        break;
      case ExprKind::Range:
        head = "range";
        break;
      case ExprKind::In:
        head = "in";
        break;
      case ExprKind::Quantifier:
        head = e->quant == QuantKind::Forall ? "forall" : "exists";
        break;
      case ExprKind::If:
        head = "if";
        break;
      case ExprKind::Tuple:
        head = "tuple";
        break;
      case ExprKind::List:
        head = "list";
        break;
    }
    line(depth, head + typeOf(*e) + at(e->range));
    if (e->binder) {
      std::string names;
      for (const auto& n : e->binder->names) names += " " + n->name.name;
      line(depth + 1, "binder" + names);
      expr(e->binder->set.get(), depth + 2);
    }
    for (const auto& op : e->operands) {
      if (op) expr(op.get(), depth + 1);
    }
    for (const auto& a : e->args) {
      line(depth + 1, a.name.name.empty() ? "arg" : "arg " + a.name.name);
      expr(a.value.get(), depth + 2);
    }
  }

  static std::string ref(const NameRef& r) {
    switch (r.kind) {
      case RefKind::Unresolved:
        return "";
      case RefKind::Binder:
        return " -> binder";
      case RefKind::Builtin:
        return " -> builtin";
      case RefKind::Param:
        return fmt::format(" -> param {}", r.index);
      case RefKind::EnumMember:
      case RefKind::ItemEntry:
        return fmt::format(" -> {} {}[{}]", toString(r.decl->kind), r.decl->name.name, r.index);
      default:
        return fmt::format(" -> {} {}", r.decl ? toString(r.decl->kind) : "?", r.decl ? r.decl->name.name : "?");
    }
  }

  void decl(const Decl& d, int depth) {
    line(depth, fmt::format("{} {}{}", toString(d.kind), d.name.name, at(d.range)));
    switch (d.kind) {
      case DeclKind::Import:
        line(depth + 1, "target " + static_cast<const ImportDecl&>(d).target);
        break;
      case DeclKind::World:
        line(depth + 1, "path " + static_cast<const WorldDecl&>(d).path);
        break;
      case DeclKind::Simulator:
        line(depth + 1, "command " + static_cast<const SimulatorDecl&>(d).command);
        break;
      case DeclKind::Const:
        expr(static_cast<const ConstDecl&>(d).value.get(), depth + 1);
        break;
      case DeclKind::Enum:
        for (const auto& m : static_cast<const EnumDecl&>(d).members) line(depth + 1, "member " + m.name);
        break;
      case DeclKind::Var: {
        const auto& v = static_cast<const VarDecl&>(d);
        line(depth + 1, "type " + v.type.name.name + (v.type.resolved ? " = " + v.type.resolved->spelling : ""));
        if (v.index) {
          line(depth + 1, "index");
          expr(v.index->set.get(), depth + 2);
        }
        if (v.domain) {
          line(depth + 1, "domain");
          expr(v.domain.get(), depth + 2);
        }
        if (v.init) {
          line(depth + 1, "init");
          expr(v.init.get(), depth + 2);
        }
        break;
      }
      case DeclKind::Require:
        expr(static_cast<const RequireDecl&>(d).condition.get(), depth + 1);
        break;
      case DeclKind::Cost:
        expr(static_cast<const CostDecl&>(d).value.get(), depth + 1);
        break;
      case DeclKind::Sample: {
        const auto& s = static_cast<const SampleDecl&>(d);
        for (const auto& t : s.targets) expr(t.get(), depth + 1);
        line(depth + 1, "sampler " + s.sampler.name);
        for (const auto& a : s.args) expr(a.value.get(), depth + 2);
        break;
      }
      case DeclKind::Function:
      case DeclKind::Sampler:
      case DeclKind::Action: {
        const auto& c = static_cast<const CallableDecl&>(d);
        for (const auto& p : c.params)
          line(depth + 1,
               "param " + p.name.name + " : " + (p.type.resolved ? p.type.resolved->spelling : p.type.name.name));
        if (c.body) expr(c.body.get(), depth + 1);
        break;
      }
      case DeclKind::Personal: {
        const auto& p = static_cast<const PersonalDecl&>(d);
        for (const auto& prm : p.params) line(depth + 1, "param " + prm.name.name);
        for (const auto& pat : p.patterns) line(depth + 1, "when " + pat.param.name + " ~ \"" + pat.pattern + "\"");
        for (const auto& f : p.factors) {
          line(depth + 1, "factor " + (f.label.name.empty() ? "" : f.label.name + " = ") + f.kind.name);
          for (const auto& a : f.args) expr(a.value.get(), depth + 2);
        }
        for (const auto& c : p.guards) {
          line(depth + 1, "if");
          expr(c.get(), depth + 2);
        }
        for (const auto& r : p.learnRules) {
          line(depth + 1, "learn " + r.event.name);
          for (const auto& l : r.labels) expr(l.value.get(), depth + 2);
        }
        break;
      }
      case DeclKind::Skill: {
        const auto& sk = static_cast<const SkillDecl&>(d);
        for (const auto& b : sk.body) decl(*b, depth + 1);
        for (const auto& a : sk.actions) action(*a, depth + 1);
        break;
      }
      case DeclKind::Clearance: {
        const auto& c = static_cast<const ClearanceDecl&>(d);
        for (std::size_t i = 0; i < c.bodies.size(); ++i)
          line(depth + 1, "body \"" + c.bodies[i] + "\"" + at(c.bodyRanges[i]));
        line(depth + 1, "distance " + length(c.distance));
        break;
      }
      case DeclKind::Task: {
        const auto& t = static_cast<const TaskDecl&>(d);
        for (const auto& b : t.body) decl(*b, depth + 1);
        for (const auto& i : t.instances) line(depth + 1, "run " + i.skill.name + " as " + i.instanceName());
        break;
      }
      default:
        break;
    }
  }

  static std::string length(const Length& l) {
    return (l.negative ? "-" : "") + l.spelling + (l.unit.name.empty() ? "" : " " + l.unit.name);
  }

  // A `do` statement and what it holds.
  void action(const ActionStmt& s, int depth) {
    switch (s.kind) {
      case ActionStmtKind::Call:
        line(depth, "do " + s.callee.name + ref(s.calleeRef) + at(s.range));
        for (const auto& a : s.args) expr(a.value.get(), depth + 1);
        break;
      case ActionStmtKind::For: {
        std::string names;
        for (const auto& n : s.forBinder->names) names += " " + n->name.name;
        line(depth, "do for" + names + at(s.range));
        expr(s.forBinder->set.get(), depth + 1);
        break;
      }
      case ActionStmtKind::If:
        line(depth, "do if" + at(s.range));
        expr(s.condition.get(), depth + 1);
        break;
      case ActionStmtKind::Block:
        line(depth, "do block" + at(s.range));
        break;
      case ActionStmtKind::Allow: {
        const AllowClause& a = *s.allow;
        line(depth, fmt::format("do allow {} {} {}{}", a.part.name, a.mode.name, length(a.length), at(s.range)));
        if (a.clearance != nullptr)
          line(depth + 1, "clearance " + a.clearance->name.name);
        else
          expr(a.target.get(), depth + 1);
        break;
      }
    }
    for (const auto& b : s.body) action(*b, depth + 1);
    if (s.hasElse) line(depth, "else");
    for (const auto& b : s.elseBody) action(*b, depth + 1);
  }

  const SourceManager& sources_;
  std::string out_;
};

}  // namespace

std::string dumpAst(const Module& module, const SourceManager& sources) { return Printer(sources).run(module); }

}  // namespace cbtl
