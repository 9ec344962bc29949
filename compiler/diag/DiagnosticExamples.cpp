#include "compiler/diag/DiagnosticExamples.h"

#include <algorithm>

namespace cbtl {

// Each wrong program produces its code; each right one compiles with no diagnostic at all
// (tests/unit/compiler/DiagnosticExamplesTest.cpp). Programs are whole files, as small as the code allows.
const std::vector<DiagnosticExample>& diagnosticExamples() {
  static const std::vector<DiagnosticExample> examples = {
      {"E0101",
       R"cbtl(var x : real in 0 .. 1;
require x < ;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require x < 1;
)cbtl"},
      {"E0102",
       R"cbtl(var x : real in 0 .. 1
require x < 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require x < 1;
)cbtl"},
      {"E0103",
       R"cbtl(simulator "python3 sim.py;
)cbtl",
       R"cbtl(simulator "python3 sim.py";
)cbtl"},
      {"E0104",
       R"cbtl(/* the cup
var x : real in 0 .. 1;
require x < 1;
)cbtl",
       R"cbtl(/* the cup */
var x : real in 0 .. 1;
require x < 1;
)cbtl"},
      {"E0105",
       R"cbtl(var x : real in 0 .. 1;
require x < 1 && x > 0;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require x < 1 and x > 0;
)cbtl"},
      {"E0106",
       R"cbtl(var x : real in 0 .. 1;
require x < 1 2;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require x < 1;
)cbtl"},
      {"E0107",
       R"cbtl(const big = 1e999;
)cbtl",
       R"cbtl(const big = 1e300;
)cbtl"},
      {"E0108",
       R"cbtl(const deep = (((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((1)))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))));
)cbtl",
       R"cbtl(const deep = ((1));
)cbtl"},
      {"E0201",
       R"cbtl(var speed : real in 0 .. 2;
require sped < 1;
)cbtl",
       R"cbtl(var speed : real in 0 .. 2;
require speed < 1;
)cbtl"},
      {"E0202",
       R"cbtl(var x : real in 0 .. 1;
var x : int in 0 .. 3;
require x < 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
var n : int in 0 .. 3;
require x < 1 and n < 2;
)cbtl"},
      {"E0203",
       R"cbtl(import std.geometri;
)cbtl",
       R"cbtl(import std.geometry;
)cbtl"},
      {"E0204",
       R"cbtl(import "no_such_file.cbtl";
)cbtl",
       R"cbtl(import "shared.cbtl";
)cbtl",
       "shared.cbtl", "",
       R"cbtl(const shared = 1;
)cbtl"},
      {"E0205",
       R"cbtl(import "other.cbtl";
const a = 1;
)cbtl",
       R"cbtl(import "other.cbtl";
const a = 1;
)cbtl",
       "other.cbtl",
       R"cbtl(import "example.cbtl";
const b = 2;
)cbtl",
       R"cbtl(const b = 2;
)cbtl"},
      {"E0206",
       R"cbtl(var x : reel in 0 .. 1;
require x < 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require x < 1;
)cbtl"},
      {"E0207",
       R"cbtl(var x : real in 0 .. 1;
require x < abs;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require abs(x) < 1;
)cbtl"},
      {"E0208",
       R"cbtl(enum Dip { ketchup, ranch }
var dip : Dip;
require dip != Dip.ranchh;
)cbtl",
       R"cbtl(enum Dip { ketchup, ranch }
var dip : Dip;
require dip != Dip.ranch;
)cbtl"},
      {"E0209",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill fetchPlate { do { serve(x); } }
task dinner = fetchPlat;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill fetchPlate { do { serve(x); } }
task dinner = fetchPlate;
)cbtl"},
      {"E0210",
       R"cbtl(feedback tooFast(s: real);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(s: real) {
  when s ~ "speed";
  model interval(s, 0 .. 2);
  learn tooFats(s) => false;
}
)cbtl",
       R"cbtl(feedback tooFast(s: real);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(s: real) {
  when s ~ "speed";
  model interval(s, 0 .. 2);
  learn tooFast(s) => false;
}
)cbtl"},
      {"E0211",
       R"cbtl(var x : real in 0 .. 1;
domain cup;
require x < 1;
)cbtl",
       R"cbtl(domain cup;
var x : real in 0 .. 1;
require x < 1;
)cbtl"},
      {"E0301",
       R"cbtl(var x : real in 0 .. 1;
require x + 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
require x + 1 < 2;
)cbtl"},
      {"E0302",
       R"cbtl(var x : real in -1 .. 1;
require abs(x, 1) < 1;
)cbtl",
       R"cbtl(var x : real in -1 .. 1;
require abs(x) < 1;
)cbtl"},
      {"E0303",
       R"cbtl(var ready : bool;
sample ready ~ uniform;
require ready + 1 > 0;
)cbtl",
       R"cbtl(var ready : bool;
sample ready ~ uniform;
require ready or not ready;
)cbtl"},
      {"E0304",
       R"cbtl(var p : vec<2> in 0 .. 1;
sample p ~ uniform;
require p.x < 1;
)cbtl",
       R"cbtl(var p : vec<2> in [0 .. 1, 0 .. 1];
sample p ~ uniform;
require p.x < 1;
)cbtl"},
      {"E0305",
       R"cbtl(var x : real in 0 .. 1;
var y : real in 0 .. x;
require y < 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
var y : real in 0 .. 1;
require y < x;
)cbtl"},
      {"E0306",
       R"cbtl(enum Ing { salt, pepper }
var temp[Ing] : real in 0 .. 5;
require temp[3] < 4;
)cbtl",
       R"cbtl(enum Ing { salt, pepper }
var temp[Ing] : real in 0 .. 5;
require temp[salt] < 4;
)cbtl"},
      {"E0307",
       R"cbtl(var x : real in -1 .. 2;
require clamp(x, lo: 0, high: 1) < 1;
)cbtl",
       R"cbtl(var x : real in -1 .. 2;
require clamp(x, 0, 1) < 1;
)cbtl"},
      {"E0308",
       R"cbtl(fn f(x: real) -> real = g(x);
fn g(x: real) -> real = f(x);
var x : real in 0 .. 1;
require f(x) < 1;
)cbtl",
       R"cbtl(fn f(x: real) -> real = 2 * x;
var x : real in 0 .. 1;
require f(x) < 1;
)cbtl"},
      {"E0309",
       R"cbtl(var v : vec<0>;
)cbtl",
       R"cbtl(var v : vec<2> in [0 .. 1, 0 .. 1];
sample v ~ uniform;
require v.x < 1;
)cbtl"},
      {"E0310",
       R"cbtl(var speed : real;
sample speed ~ uniform;
require speed < 1;
)cbtl",
       R"cbtl(var speed : real in 0 .. 2;
sample speed ~ uniform;
require speed < 1;
)cbtl"},
      {"E0311",
       R"cbtl(var x : real in 1 .. 0;
sample x ~ uniform;
require x < 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
require x < 1;
)cbtl"},
      {"E0312",
       R"cbtl(enum Pot { a, b, c }
const radius[Pot] : real = [0.5, 1.0];
)cbtl",
       R"cbtl(enum Pot { a, b, c }
const radius[Pot] : real = [0.5, 1.0, 0.5];
)cbtl"},
      {"E0313",
       R"cbtl(var n : int in 0 .. 3;
require n == uniformInt(0, 3);
)cbtl",
       R"cbtl(var n : int in 0 .. 3;
sample n ~ uniformInt(0, 3);
require n < 3;
)cbtl"},
      {"E0314",
       R"cbtl(item Food { name: text; spicy: bool; }
items foods : Food { curry { name: "curry", spicey: true } }
)cbtl",
       R"cbtl(item Food { name: text; spicy: bool; }
items foods : Food { curry { name: "curry", spicy: true } }
)cbtl"},
      {"E0315",
       R"cbtl(robot arm { dof: 0; }
)cbtl",
       R"cbtl(robot arm { dof: 6; }
)cbtl"},
      {"E0316",
       R"cbtl(const a = b + 1;
const b = a * 2;
)cbtl",
       R"cbtl(const a = 1;
const b = a * 2;
)cbtl"},
      {"E0317",
       R"cbtl(var slot[0 .. 1000000] : bool;
)cbtl",
       R"cbtl(var slot[0 .. 9] : bool;
sample slot ~ uniform;
require slot[0] or slot[1];
)cbtl"},
      {"E0318",
       R"cbtl(extern fn warmth(t: real) -> real;
var t : real in 40 .. 90;
sample t ~ uniform;
require warmth(t) > 0.5;
)cbtl",
       R"cbtl(fn warmth(t: real) -> real = clamp((t - 40) / 50, 0, 1);
var t : real in 40 .. 90;
sample t ~ uniform;
require warmth(t) > 0.5;
)cbtl"},
      {"E0401",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "{oops";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0402",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when s ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0403",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0404",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model intervall(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0405",
       R"cbtl(feedback rated(c: bool, good: bool);
var ready : bool;
sample ready ~ uniform;
personal p(c: bool) {
  when c ~ "ready";
  model interval(c, 0 .. 1);
  learn rated(c, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(c: bool, good: bool);
var ready : bool;
sample ready ~ uniform;
personal p(c: bool) {
  when c ~ "ready";
  model table(c);
  learn rated(c, good) => good;
}
)cbtl"},
      {"E0406",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model threshold(x, 0 .. 2, sideways);
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model threshold(x, 0 .. 2, below);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0407",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x) => true;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0408",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(good, x) => true;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0409",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => 1;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0410",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(_, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0411",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
  accept 1.5;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
  accept 0.8;
}
)cbtl"},
      {"E0412",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2) per who;
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0413",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy() {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0414",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
  accept 0.6;
  accept 0.7;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
  accept 0.7;
}
)cbtl"},
      {"E0415",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(xs: set<real>) {
  when xs ~ "speed";
  model table(xs);
  learn rated(xs, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"E0416",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
  explore inside;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
  explore accepted;
}
)cbtl"},
      {"E0417",
       R"cbtl(feedback rated(s: real, t: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
var turnRate : real in 0 .. 1;
sample turnRate ~ uniform;
personal comfy(s: real, t: real) {
  when s ~ "speed";
  model a = interval(s, 0 .. 2) * b = interval(t, 0 .. 1);
  learn rated(s, t, good) => a: good, b: good;
}
)cbtl",
       R"cbtl(feedback rated(s: real, t: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
var turnRate : real in 0 .. 1;
sample turnRate ~ uniform;
personal comfy(s: real, t: real) {
  when s ~ "speed", t ~ "turnRate";
  model a = interval(s, 0 .. 2) * b = interval(t, 0 .. 1);
  learn rated(s, t, good) => a: good, b: good;
}
)cbtl"},
      {"E0501",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
task t = pour then pour;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
task t = pour then pour as pourAgain;
)cbtl"},
      {"E0502",
       R"cbtl(var x : real in 0 .. 1;
var n : int in 0 .. 3;
sample x ~ uniform;
sample n ~ uniform;
extern action serve(v: real);
skill pour(v: real) { do { serve(v); } }
task t {
  run pour(n);
}
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
var n : int in 0 .. 3;
sample x ~ uniform;
sample n ~ uniform;
extern action serve(v: real);
skill pour(v: real) { do { serve(v); } }
task t {
  run pour(x);
}
require n >= 0;
)cbtl"},
      {"E0503",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serv(x); } }
task t = pour;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
task t = pour;
)cbtl"},
      {"E0504",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
skill wipe { do { serve(x); } }
task t = pour as step then wipe as step;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
skill wipe { do { serve(x); } }
task t = pour as first then wipe as second;
)cbtl"},
      {"W0201",
       R"cbtl(var x : real in 0 .. 1;
var forgotten : real in 0 .. 1;
sample x ~ uniform;
require x < 1;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
require x < 1;
)cbtl"},
      {"W0401",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "sped";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"W0402",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
}
)cbtl",
       R"cbtl(feedback rated(x: real, good: bool);
var speed : real in 0 .. 2;
sample speed ~ uniform;
personal comfy(x: real) {
  when x ~ "speed";
  model interval(x, 0 .. 2);
  learn rated(x, good) => good;
}
)cbtl"},
      {"W0403",
       R"cbtl(enum Ing { salt, pepper }
enum Pot { small, large }
feedback tasted(u: bool, q: real, good: bool);
var used[Ing] : bool;
var amount[Pot] : real in 0 .. 1;
sample used ~ uniform;
sample amount ~ uniform;
personal tasty(u: bool, q: real) {
  when u ~ "used[{i}]", q ~ "amount[{i}]";
  model interval(q, 0 .. 1);
  learn tasted(u, q, good) => good;
}
)cbtl",
       R"cbtl(enum Ing { salt, pepper }
feedback tasted(u: bool, q: real, good: bool);
var used[Ing] : bool;
var amount[Ing] : real in 0 .. 1;
sample used ~ uniform;
sample amount ~ uniform;
personal tasty(u: bool, q: real) {
  when u ~ "used[{i}]", q ~ "amount[{i}]";
  model interval(q, 0 .. 1);
  learn tasted(u, q, good) => good;
}
)cbtl"},
      {"W0501",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
skill unused { do { serve(x); } }
task t = pour;
)cbtl",
       R"cbtl(var x : real in 0 .. 1;
sample x ~ uniform;
extern action serve(v: real);
skill pour { do { serve(x); } }
task t = pour;
)cbtl"},
      {"W0502",
       R"cbtl(var free : real;
require free > 1;
)cbtl",
       R"cbtl(var free : real in 0 .. 5;
sample free ~ uniform;
require free > 1;
)cbtl"},
  };
  return examples;
}

const DiagnosticExample* exampleFor(std::string_view code) {
  const auto& all = diagnosticExamples();
  const auto it = std::find_if(all.begin(), all.end(), [&](const DiagnosticExample& e) { return e.code == code; });
  return it == all.end() ? nullptr : &*it;
}

}  // namespace cbtl
