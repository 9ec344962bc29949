#include "compiler/ast/Ast.h"

namespace cbtl {

const char* toString(BinaryOp op) {
  switch (op) {
    case BinaryOp::Add:
      return "+";
    case BinaryOp::Sub:
      return "-";
    case BinaryOp::Mul:
      return "*";
    case BinaryOp::Div:
      return "/";
    case BinaryOp::Mod:
      return "%";
    case BinaryOp::Pow:
      return "^";
    case BinaryOp::Eq:
      return "==";
    case BinaryOp::Ne:
      return "!=";
    case BinaryOp::Lt:
      return "<";
    case BinaryOp::Le:
      return "<=";
    case BinaryOp::Gt:
      return ">";
    case BinaryOp::Ge:
      return ">=";
    case BinaryOp::And:
      return "and";
    case BinaryOp::Or:
      return "or";
    case BinaryOp::Implies:
      return "=>";
    case BinaryOp::Iff:
      return "<=>";
  }
  return "?";
}

const char* toString(UnaryOp op) { return op == UnaryOp::Neg ? "-" : "not"; }

const char* toString(DeclKind kind) {
  switch (kind) {
    case DeclKind::Domain:
      return "domain";
    case DeclKind::Import:
      return "import";
    case DeclKind::World:
      return "world";
    case DeclKind::Simulator:
      return "simulator";
    case DeclKind::Robot:
      return "robot";
    case DeclKind::Clearance:
      return "clearance";
    case DeclKind::Const:
      return "constant";
    case DeclKind::Enum:
      return "enum";
    case DeclKind::ItemType:
      return "item type";
    case DeclKind::ItemSet:
      return "item set";
    case DeclKind::Observe:
      return "observation";
    case DeclKind::Feedback:
      return "feedback event";
    case DeclKind::Function:
      return "function";
    case DeclKind::Sampler:
      return "sampler";
    case DeclKind::Action:
      return "action";
    case DeclKind::Var:
      return "variable";
    case DeclKind::Require:
      return "constraint";
    case DeclKind::Sample:
      return "sample";
    case DeclKind::Cost:
      return "cost";
    case DeclKind::Personal:
      return "generator";
    case DeclKind::Skill:
      return "skill";
    case DeclKind::Task:
      return "task";
  }
  return "declaration";
}

}  // namespace cbtl
