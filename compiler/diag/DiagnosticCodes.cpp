#include "compiler/diag/DiagnosticCodes.h"

#include <algorithm>
#include <cctype>

namespace cbtl {

const std::vector<DiagnosticCodeInfo>& diagnosticCodes() {
  static const std::vector<DiagnosticCodeInfo> codes = {
      // --- E01xx: syntax ------------------------------------------------------------------------
      {"E0101", "syntax error",
       "The parser found a token it cannot use at this point. The message says what was expected.\n"
       "Example:  var x : real in 0 .. 1   (no ';' at the end)\n"
       "Fix: complete the declaration; every declaration ends with ';' or a '{ ... }' block."},
      {"E0102", "missing token",
       "A required token is missing, most often a ';' or a closing bracket.\n"
       "Example:  require x < 1\n"
       "Fix: add the token named in the message."},
      {"E0103", "unterminated string",
       "A string literal has no closing '\"' before the end of the line.\n"
       "Example:  world \"feeding.xml;\n"
       "Fix: close the string on the same line; use \\\" for a quote inside it."},
      {"E0104", "unterminated block comment",
       "A '/*' comment is never closed with '*/'.\nFix: close the comment, or use '//' line comments."},
      {"E0105", "invalid character",
       "The character cannot start any token of the language.\n"
       "Example:  var x : real @ 2;\nFix: remove the character."},
      {"E0106", "unexpected input",
       "Extra input was found where the declaration or expression should already be complete.\n"
       "Example:  var x : real;;   or   require x < 1 2;\nFix: remove the extra tokens."},
      {"E0107", "invalid number",
       "A number literal is too large to be represented (beyond about 1.8e308, the range of a double).\n"
       "Example:  const big = 1e999;\nFix: write a finite decimal number."},
      {"E0108", "nesting too deep",
       "Brackets or prefix operators are nested more than 200 levels deep, or an expression has more than\n"
       "1000 levels. The compiler refuses such input rather than risk running out of stack.\n"
       "Fix: split the expression into constants or functions."},
      // --- E02xx: names and imports --------------------------------------------------------------
      {"E0201", "unknown name",
       "A name is used that no declaration in scope defines. Names are looked up in the innermost scope first\n"
       "(quantifier binders, parameters, skill and task variables), then the file and its imports.\n"
       "Example:  require tmep < 3;   (declared as 'temp')\n"
       "Fix: correct the spelling (the help line suggests the closest name) or declare it."},
      {"E0202", "duplicate declaration",
       "Two declarations in the same scope have the same name.\n"
       "Example:  var x : real;  var x : int;\nFix: rename one of them. The note points at the first one."},
      {"E0203", "unknown module",
       "An 'import std.NAME;' names a standard-library module that does not exist.\n"
       "Fix: use one of the modules listed in the help line, or import a file with import \"path.cbtl\";"},
      {"E0204", "cannot read imported file",
       "An 'import \"path\";' names a file that cannot be read. Paths are relative to the importing file.\n"
       "Fix: correct the path."},
      {"E0205", "import cycle",
       "Files import each other in a cycle. Each file is read once, so a cycle is almost always a mistake.\n"
       "Fix: move the shared declarations into a third file that both import."},
      {"E0206", "unknown type",
       "A type name is neither a built-in type (real, int, bool, text, vec<N>, SE2, SE3, Conf<R>, set<T>) nor\n"
       "a declared enum or item type.\nExample:  var x : reel;\nFix: correct the name."},
      {"E0207", "wrong kind of name",
       "A name refers to a declaration that cannot be used here, such as a skill or an action in an\n"
       "expression, or a variable where a type is expected.\nFix: use a name of the kind the message asks for."},
      {"E0208", "unknown member",
       "A '.member' access names a field that the value's type does not have.\n"
       "Example:  book.titel   (Book has 'title')\n"
       "Fix: use a field of the type; vec has x, y, z; SE2 has x, y, yaw; SE3 has x, y, z, position."},
      {"E0209", "unknown skill",
       "A task runs a skill that is not declared.\nFix: correct the name or declare the skill."},
      {"E0210", "unknown feedback event",
       "A learning rule names an event that no 'feedback' declaration defines.\n"
       "Example:  learn viewBlockd(c) => false;\nFix: correct the name or declare: feedback viewBlocked(c: "
       "Conf<gen3>);"},
      {"E0211", "misplaced or repeated domain header",
       "A file has more than one 'domain NAME;' header, or it is not the first declaration.\n"
       "Fix: keep one header at the top of the file."},
      // --- E03xx: types and domains --------------------------------------------------------------
      {"E0301", "type mismatch",
       "An expression has a different type from the one its context needs.\n"
       "Example:  require x + 1;   (a constraint must be bool)\nFix: change the expression or the declaration."},
      {"E0302", "wrong number of arguments",
       "A call passes more or fewer arguments than the function, sampler, action, skill or model declares.\n"
       "Fix: match the declaration shown in the note."},
      {"E0303", "operator does not apply",
       "An operator is used with operand types it does not accept, such as 'and' on numbers or '<' on enums.\n"
       "Fix: convert the operands or use another operator."},
      {"E0304", "invalid domain",
       "The 'in ...' part of a variable declaration does not fit the variable's type. Reals and ints take a\n"
       "range lo .. hi; vec<N> a list of N ranges; SE2 box(x:, y:, yaw:); SE3 box(x:, y:, z:); enums a list of\n"
       "members; items an item set, an observed set or a list of items; text a list of strings. Constant\n"
       "bounds are finite numbers (a bound like 0.0 / 0.0 or 1.0 / 0.0 leaves nothing to sample).\n"
       "Example:  var p : vec<2> in 0 .. 1;\nFix: write the domain in the form for the type."},
      {"E0305", "not a constant",
       "A value that must be known when the file is compiled (a constant, a domain bound that is not an\n"
       "observation, an index set) depends on a variable.\nFix: use constants or observations only."},
      {"E0306", "cannot index",
       "An index expression is applied to something that is not a family, a vector or a list, or the index\n"
       "has the wrong type.\nExample:  temp[3] when temp is indexed by an enum.\nFix: index with a member of the "
       "family's index set."},
      {"E0307", "bad named argument",
       "A named argument does not match any parameter, is given twice, or comes before a positional one.\n"
       "Fix: use the parameter names of the declaration."},
      {"E0308", "recursive function",
       "A user function calls itself, directly or through others. Functions are expanded during solving and\n"
       "recursion could not terminate.\nFix: rewrite without recursion."},
      {"E0309", "invalid type arguments",
       "A type is given the wrong arguments: vec needs a positive integer, Conf a declared robot, set a type.\n"
       "Example:  vec<0>, Conf<ur5> without 'robot ur5 { dof: 6; }'\nFix: correct the arguments."},
      {"E0310", "invalid sample statement",
       "A sample statement's targets are not variables of the scope, or the sampler's result type does not\n"
       "match them, or the sampler is not a sampler (use 'uniform' or an 'extern sampler'), or 'uniform' is\n"
       "asked to draw a number-valued variable that has no lower or upper bound.\n"
       "Example:  var speed : real;  sample speed ~ uniform;\n"
       "Fix:      var speed : real in 0 .. 2;  sample speed ~ uniform;"},
      {"E0311", "empty or inverted range",
       "A constant range has its lower bound above its upper bound, so the domain is empty; a variable\n"
       "family's index set is empty, so it declares no variable; or a model's prior is inverted or a single\n"
       "point, so there is nothing to learn.\n"
       "Example:  var x : real in 1 .. 0;      model interval(t, 85 .. 40);\n"
       "Fix:      var x : real in 0 .. 1;      model interval(t, 40 .. 85);"},
      {"E0312", "wrong number of values",
       "An indexed constant or item list gives a different number of values from the size of its index set.\n"
       "Example:  const r[Pot] : real = [0.5, 1.0];  with four pots.\nFix: give one value per index."},
      {"E0313", "not callable here",
       "Something that is not a function is called in an expression, or an action is called outside a 'do'\n"
       "block, or a sampler is called outside a 'sample' statement.\nFix: use the right kind of declaration."},
      {"E0314", "invalid item",
       "An item entry misses a field of its type, gives an unknown field, or gives a value of the wrong type.\n"
       "Fix: give every field of the item type exactly once."},
      {"E0315", "invalid declaration value",
       "A constant, robot field, or initial value has a type the declaration does not accept.\n"
       "Fix: match the declared type."},
      {"E0316", "recursive constant",
       "A constant's value uses the constant itself, directly or through other constants, so it has no value.\n"
       "Example:  const a = b + 1;  const b = a * 2;\nFix: give one of the constants a value that does not depend on "
       "the others."},
      {"E0317", "too large",
       "A declaration expands into more than the compiler accepts: an integer range used as a family index or a\n"
       "sample statement's 'for' set may have at most 100000 members, and the whole constraint graph at most\n"
       "2000000 variables, constraints, samplers, costs, actions and expression nodes. (A top-level 'forall'\n"
       "with more than 10000 instances is not an error: it is kept as one quantified constraint.)\n"
       "Example:  var slot[0 .. 1000000] : bool;\nFix: use smaller sets, or a quantified constraint over an "
       "observation."},
      // --- E04xx: personalized constraint generators -------------------------------------------------
      {"E0318", "extern without an implementation",
       "A program uses an 'extern fn' or 'extern sampler' that it declares itself. cbtl's runtime implements\n"
       "exactly the externs of the standard library (std.prelude, std.geometry, ...), so the program could\n"
       "be checked but never run.\n"
       "Example:  extern fn warmth(t: real) -> real;   require warmth(temperature) > 0.5;\n"
       "Fix:      fn warmth(t: real) -> real = clamp((t - 50) / 30, 0, 1);   (written in the language)"},
      {"E0319", "function expands too much",
       "The runtime inlines every call of a user function: the call is replaced by the function's body. A\n"
       "function whose body, with all its calls inlined, has more than 100000 expression nodes or more than\n"
       "1000 levels, or a call of which inlines more than 64 nested calls (the runtime's own limit), is\n"
       "refused where it is declared. A function that calls another twice doubles its size at each level, so a few\n"
       "lines can ask for more memory than any machine has.\n"
       "Example:  fn f1(v: real) -> real = f0(v) + f0(v + 1);  ...  fn f20(v: real) -> real = f19(v) + f19(v + 1);\n"
       "Fix: compute a value used twice once (pass it as an argument, make it a constant), or write the\n"
       "expression without the nested calls."},
      {"E0320", "quantifier ranges over too many values",
       "The runtime evaluates a quantifier's body once per combination of its binders' values, every time it\n"
       "checks a candidate. A nest of quantifiers (calls into functions included) whose sets, known at compile\n"
       "time, have more than 1000000 combinations in all is refused at the innermost quantifier that goes over.\n"
       "Example:  require forall a, b in Big: a != b or a == pick;   (Big has 200000 members)\n"
       "Fix: range over a smaller set, or over the members that matter (a 'where' clause does not reduce the\n"
       "work: every combination is still tried)."},
      {"E0401", "malformed initiation pattern",
       "A glob or regular expression in a 'when' clause is not well formed: an unclosed '{' capture, an empty\n"
       "capture name, or a regex syntax error.\nFix: correct the pattern. Globs: * any run, ? one character,\n"
       "{name} a named capture; brackets are literal."},
      {"E0402", "pattern for unknown parameter",
       "A 'when' clause gives a pattern for a name that is not a parameter of the generator, or gives two\n"
       "patterns for the same parameter.\nFix: one pattern per parameter, named as in the parameter list."},
      {"E0403", "missing or repeated model",
       "A generator must have exactly one 'model' clause (which may be a product of factors).\n"
       "Fix: add one model clause, or merge several into a product with '*'."},
      {"E0404", "unknown model kind",
       "A model factor names a kind the compiler does not know. Known kinds: interval, threshold, table, text.\n"
       "Fix: use a known kind."},
      {"E0405", "feature must be real-valued",
       "The feature of an interval or threshold model must be a real (or int) expression of the generator's\n"
       "parameters.\nExample:  model interval(c, 0 .. 1)   where c : Conf<gen3>\n"
       "Fix: compute a number from the parameters, e.g. interval(occlusion(c), 0 .. 1)."},
      {"E0406", "invalid model arguments",
       "A model factor's arguments do not fit its kind: interval(feature, lo .. hi), threshold(feature,\n"
       "lo .. hi, above|below), table(key), text(subject, prompt:, learning:, scale:, rating:).\n"
       "Fix: follow the form in the message."},
      {"E0407", "learning rule arity",
       "A learning rule lists a different number of binders from the event's parameters.\n"
       "Fix: one binder per event parameter; use '_' for those you do not need."},
      {"E0408", "learning rule binder type",
       "A learning-rule binder has the name of a generator parameter or key, but the event's parameter in\n"
       "that position has a different type.\nFix: rename the binder or change the event's parameter type."},
      {"E0409", "invalid label",
       "A learning rule's label is not bool, names a factor that the model does not have, or is unnamed\n"
       "while the model is a product (say which factor it labels: '=> temp: good').\nFix: correct the label."},
      {"E0410", "learning rule leaves a parameter unbound",
       "A learning rule labels a factor whose feature needs a generator parameter or key that the rule does\n"
       "not bind, or the generator has a 'per' key that reads such a parameter, so the label cannot be\n"
       "turned into a data point.\n"
       "Fix: name the binder after the parameter, e.g. learn viewBlocked(c) => false;"},
      {"E0411", "probability out of range",
       "'accept' and 'fallback' take a constant probability in [0, 1] ('accept' in (0, 1]).\nFix: use such a number."},
      {"E0412", "invalid key",
       "A 'per' key names one model per distinct value: it must be a {capture} of the generator's patterns,\n"
       "a parameter, or an expression over the parameters, observations and constants (an item's field as\n"
       "p.kind, a constant family as kindOf[p]), of a discrete type (enum, item, int, bool or text), reading\n"
       "no decision variable (the key must not change while the solver moves the candidate).\n"
       "Fix: name a capture or a discrete parameter, or compute a discrete value from the parameters."},
      {"E0413", "generator without parameters",
       "A personalized constraint generator needs at least one parameter: its arity is the number of\n"
       "parameters, and a constraint is made for each matching tuple of variables.\nFix: add parameters."},
      {"E0414", "repeated clause",
       "A generator has more than one 'accept', 'fallback', 'explore' or 'when' clause.\nFix: keep one."},
      {"E0415", "parameter type cannot be a variable's",
       "A generator parameter's type must be a type that CSP variables can have (real, int, bool, text,\n"
       "vec, SE2, SE3, Conf, an enum or an item type).\nFix: change the type."},
      {"E0416", "unknown exploration mode",
       "A generator's 'explore' clause names a mode other than 'accepted' (CBTL explores only where the\n"
       "model accepts) or 'anywhere' (the default).\nFix: write one of the two."},
      {"E0417", "parameter without a pattern",
       "A generator parameter has no pattern in the 'when' clause. It would match every variable of its type,\n"
       "so the generator would judge variables nobody meant it to (and silently multiply its instances).\n"
       "Example:  personal comfy(s: real, t: real) { when s ~ \"speed\"; ... }   (no pattern for t)\n"
       "Fix:      personal comfy(s: real, t: real) { when s ~ \"speed\", t ~ \"turnRate\"; ... }\n"
       "          (write t ~ \"*\" if every real variable is really meant)"},
      {"E0418", "too many generator instances",
       "The runtime makes one personalized constraint instance for every tuple of distinct variables that a\n"
       "generator's patterns match, in every task. All generators together may make at most 100000 instances,\n"
       "and finding them may take at most 2000000 steps (a variable looked at, a candidate tried, a pattern\n"
       "tested). The error is at the 'when' clause of the generator that goes over.\n"
       "Example:  personal balanced(a: real, b: real, c: real) { when a ~ \"*\", b ~ \"*\", c ~ \"*\"; ... }\n"
       "          over 100 real variables: 970200 triples\n"
       "Fix: make the patterns match fewer variables; a capture the parameters share\n"
       "(a ~ \"low[{i}]\", b ~ \"high[{i}]\") pairs only the variables with the same index."},
      // --- E05xx: skills and tasks ---------------------------------------------------------------
      {"E0501", "skill used twice",
       "A task runs the same skill twice without naming the instances, so their variables would clash.\n"
       "Example:  task t = pick then pick;\nFix: name instances: task t = pick then pick as pick2;"},
      {"E0502", "skill argument mismatch",
       "A skill instance passes the wrong number of arguments, or an argument that is not a variable of the\n"
       "parameter's type. Skill parameters are variables that the task shares with the skill.\n"
       "Fix: pass variables of the declared types."},
      {"E0503", "unknown action",
       "A 'do' block calls something that is not an 'extern action'.\nFix: declare the action or correct the name."},
      {"E0504", "duplicate instance name",
       "Two skill instances in one task have the same name.\nFix: give one of them another name with 'as'."},
      // --- E06xx: the world: clearances and allow statements ---------------------------------------
      {"E0601", "distance without a unit",
       "A clearance's distance, or an allow's, is a number without a unit or with a unit the language does not\n"
       "take. Distances are written with their unit, m, cm or mm, so that nobody has to guess what 5 means.\n"
       "Example:  clearance person: \"user\" >= 5;\n"
       "Fix:      clearance person: \"user\" >= 5 cm;"},
      {"E0602", "negative distance",
       "A clearance's distance or an allow's distance is negative. A clearance is a separation the robot keeps\n"
       "(0 or more); an allow's 'near' distance is how close the part may come, and a 'touch' distance how deep it\n"
       "may sink in, both written as positive lengths.\n"
       "Example:  allow held near person -5 mm { ... }\n"
       "Fix:      allow held touch person 5 mm { ... }   (or near with a positive distance)"},
      {"E0603", "clearance without a world",
       "A program declares a clearance, or uses an allow, but has no 'world \"scene.xml\";' line in its root file:\n"
       "the bodies a clearance names are bodies of that scene, and without one there is nothing to keep clear of.\n"
       "Example:  clearance person: \"user\" >= 5 cm;   (and no world line)\n"
       "Fix:      world \"scene.xml\";   clearance person: \"user\" >= 5 cm;"},
      {"E0604", "invalid allow statement",
       "An allow statement names a part other than robot, gripper or held, a mode other than near or touch,\n"
       "or has no action in its block (it would allow nothing).\n"
       "Example:  allow hand near person 1 cm { say(\"hello\"); }\n"
       "Fix:      allow gripper near person 1 cm { say(\"hello\"); }"},
      {"E0605", "invalid allow target",
       "The target of an allow is neither the name of a declared clearance nor a text naming a scene body or\n"
       "geom (a string, or a text-valued constant, parameter or variable).\n"
       "Example:  const userHeight = 1.7;   allow held near userHeight 1 cm { ... }\n"
       "Fix:      allow held near \"user\" 1 cm { ... }"},
      {"E0606", "cannot read the world",
       "The program declares clearances or allows, so its world file is read to check the scene names they use,\n"
       "and the file (or a file it includes) cannot be read or is not well-formed XML. The world's path is\n"
       "relative to the root file, an include's to the including file. A program without clearances and allows\n"
       "never reads its world.\n"
       "Example:  world \"scene.xml\";   with a <body> in scene.xml that is never closed\n"
       "Fix:      correct the path, or the XML at the line the message names."},
      {"E0607", "unknown scene name",
       "A clearance names a body that the world file does not declare (a <body name=...>), or an allow's target,\n"
       "given as a string or a constant, is neither a body nor a geom of the world. A clearance names bodies\n"
       "only: each covers the bodies attached below it, and so all their geoms.\n"
       "Example:  clearance person: \"usr\" >= 5 cm;\n"
       "Fix:      clearance person: \"user\" >= 5 cm;   (the help line suggests the closest name)"},
      // --- E09xx: internal ----------------------------------------------------------------------
      {"E0901", "invalid constraint graph (internal)",
       "The constraint graph produced by the compiler failed validation. This is a bug in cbtlc, not in your\n"
       "file; please report it together with the file."},
      // --- warnings ------------------------------------------------------------------------------
      {"W0201", "unused variable",
       "A variable is declared but no constraint, sampler, cost, action or personalized constraint generator\n"
       "reads it, so its value never matters. Reported once per declaration (all members of a family, all\n"
       "instances of a skill).\nExample:  var forgotten : real in 0 .. 1;   (and nothing mentions it)\n"
       "Fix: use it or remove it."},
      {"W0401", "pattern matches no variable",
       "A generator's initiation pattern (with its parameter types) matches no variable of any task, so the\n"
       "generator never produces a constraint.\nFix: check the pattern against the names in 'cbtlc emit'."},
      {"W0402", "generator never learns",
       "A personalized constraint generator has no learning rule, so its parameter stays at the prior.\n"
       "Fix: add 'learn EVENT(...) => label;'."},
      {"W0403", "patterns never match together",
       "Each parameter's pattern matches some variable, but no task holds a tuple of them that agrees on the\n"
       "patterns' captures (or a variable for every parameter), so the generator creates no constraint.\n"
       "Example:  var used[Ingredient] : bool;  var amount[Pot] : real;\n"
       "          when u ~ \"used[{i}]\", q ~ \"amount[{i}]\";   ({i} is an ingredient in one, a pot in the other)\n"
       "Fix:      var amount[Ingredient] : real;   (index both families by the same set)"},
      {"W0501", "skill never used", "A skill is declared but no task runs it.\nFix: run it in a task or remove it."},
      {"W0502", "variable has no sampler",
       "A variable that is used but has an unbounded domain (a real, int, vec, SE2, SE3 or text without 'in')\n"
       "has neither a sampler nor an initial value, so the solver cannot produce values for it.\n"
       "Example:  var free : real;  require free > 1;\nFix: add 'sample x ~ ...;', an initial value, or bound its "
       "domain."},
      {"W0503", "variable is never sampled",
       "A variable that is used has an initial value or a bounded or finite domain (bool, an enum, an item,\n"
       "Conf<R>, or 'in ...') but no sampler writes it. The solver changes variables only through samplers, so\n"
       "every candidate keeps its starting value (the initial value, else zero moved into the domain) and a\n"
       "constraint that needs another value fails after the whole budget. When a solve fails, cbtl names these\n"
       "variables.\n"
       "Example:  var watered : bool;  require watered;\n"
       "Fix:      sample watered ~ uniform;   (over the declared domain; 'uniformReal(lo, hi)' for an unbounded\n"
       "          real), or 'const' when the value is meant to be fixed."},
  };
  return codes;
}

const DiagnosticCodeInfo* findDiagnosticCode(std::string_view code) {
  for (const auto& info : diagnosticCodes()) {
    if (info.code.size() != code.size()) continue;
    bool same = true;
    for (std::size_t i = 0; i < code.size(); ++i) {
      if (std::toupper(static_cast<unsigned char>(code[i])) != info.code[i]) {
        same = false;
        break;
      }
    }
    if (same) return &info;
  }
  return nullptr;
}

}  // namespace cbtl
