#include "runtime/core/Builtins.h"

#include "runtime/core/PoseBuiltins.h"

#include <algorithm>
#include <cmath>

namespace cbtl::rt {

namespace {

using Args = std::span<const double>;
using Widths = std::span<const std::uint16_t>;
using Out = std::span<double>;

#define CBTL_UNARY(NAME, EXPR)                           \
  void NAME(const CallContext&, Args a, Widths, Out o) { \
    const double x = a[0];                               \
    o[0] = (EXPR);                                       \
  }
#define CBTL_BINARY(NAME, EXPR)                          \
  void NAME(const CallContext&, Args a, Widths, Out o) { \
    const double x = a[0], y = a[1];                     \
    o[0] = (EXPR);                                       \
  }

CBTL_UNARY(fAbs, std::fabs(x))
CBTL_UNARY(fSign, x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0))
CBTL_UNARY(fSqrt, std::sqrt(x))
CBTL_UNARY(fExp, std::exp(x))
CBTL_UNARY(fLn, std::log(x))
CBTL_UNARY(fFloor, std::floor(x))
CBTL_UNARY(fCeil, std::ceil(x))
CBTL_UNARY(fRound, std::round(x))
CBTL_UNARY(fSin, std::sin(x))
CBTL_UNARY(fCos, std::cos(x))
CBTL_UNARY(fTan, std::tan(x))
CBTL_UNARY(fAsin, std::asin(x))
CBTL_UNARY(fAcos, std::acos(x))
CBTL_UNARY(fWrap, std::remainder(x, 2 * M_PI))
CBTL_BINARY(fMin, std::min(x, y))
CBTL_BINARY(fMax, std::max(x, y))
CBTL_BINARY(fAtan2, std::atan2(x, y))
#undef CBTL_UNARY
#undef CBTL_BINARY

void fClamp(const CallContext&, Args a, Widths, Out o) {
  o[0] = std::clamp(a[0], std::min(a[1], a[2]), std::max(a[1], a[2]));
}
void fVec2(const CallContext&, Args a, Widths, Out o) {
  o[0] = a[0];
  o[1] = a[1];
}
void fVec3(const CallContext&, Args a, Widths, Out o) {
  o[0] = a[0];
  o[1] = a[1];
  o[2] = a[2];
}
void fNorm(const CallContext&, Args a, Widths, Out o) {
  double s = 0;
  for (double x : a) s += x * x;
  o[0] = std::sqrt(s);
}
void fDistance(const CallContext&, Args a, Widths w, Out o) {
  double s = 0;
  for (std::size_t i = 0; i < w[0]; ++i) s += (a[i] - a[w[0] + i]) * (a[i] - a[w[0] + i]);
  o[0] = std::sqrt(s);
}
void fDot(const CallContext&, Args a, Widths w, Out o) {
  double s = 0;
  for (std::size_t i = 0; i < w[0]; ++i) s += a[i] * a[w[0] + i];
  o[0] = s;
}
void fCross(const CallContext&, Args a, Widths, Out o) {
  o[0] = a[1] * a[5] - a[2] * a[4];
  o[1] = a[2] * a[3] - a[0] * a[5];
  o[2] = a[0] * a[4] - a[1] * a[3];
}
void fNormalize(const CallContext&, Args a, Widths, Out o) {
  double s = 0;
  for (double x : a) s += x * x;
  s = std::sqrt(s);
  for (std::size_t i = 0; i < a.size(); ++i) o[i] = s > 0 ? a[i] / s : 0;
}
void fGen3Conf(const CallContext&, Args a, Widths, Out o) {
  for (std::size_t i = 0; i < 7; ++i) o[i] = a[i];
}
void fXy(const CallContext&, Args a, Widths, Out o) {
  o[0] = a[0];
  o[1] = a[1];
}
void fSe2(const CallContext&, Args a, Widths, Out o) {
  o[0] = a[0];
  o[1] = a[1];
  o[2] = a[2];
}

bool sUniformInt(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  const auto lo = static_cast<std::int64_t>(std::ceil(a[0])), hi = static_cast<std::int64_t>(std::floor(a[1]));
  if (lo > hi) return false;
  o[0] = static_cast<double>(rng.uniformInt(lo, hi));
  return true;
}
bool sUniformReal(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  if (!(a[0] <= a[1])) return false;
  o[0] = rng.uniform(a[0], a[1]);
  return true;
}
bool sBernoulli(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  o[0] = rng.coin(a[0]) ? 1 : 0;
  return true;
}
bool sUniformInBox(const CallContext&, Args a, Widths w, Rng& rng, Out o) {
  const std::size_t n = w[0];
  for (std::size_t i = 0; i < n; ++i) {
    if (!(a[i] <= a[n + i])) return false;
  }
  for (std::size_t i = 0; i < n; ++i) o[i] = rng.uniform(a[i], a[n + i]);
  return true;
}
// `keep` with probability pKeep (when it lies in the box), else a uniform point of [lo, hi]. Both draws are always
// made, so the stream does not branch on the choice.
bool sKeepOrUniformInBox(const CallContext&, Args a, Widths w, Rng& rng, Out o) {
  const std::size_t n = w[0];
  const double pKeep = a[3 * n];
  if (!(pKeep >= 0.0 && pKeep <= 1.0)) return false;
  bool keepInBox = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(a[n + i] <= a[2 * n + i])) return false;
    keepInBox = keepInBox && a[n + i] <= a[i] && a[i] <= a[2 * n + i];
  }
  const bool keep = rng.uniform(0.0, 1.0) < pKeep;
  for (std::size_t i = 0; i < n; ++i) o[i] = rng.uniform(a[n + i], a[2 * n + i]);
  if (keep && keepInBox)
    for (std::size_t i = 0; i < n; ++i) o[i] = a[i];
  return true;
}
// A point of the rectangle [lo, hi] at least `margin` from its edges (e.g. a pot's centre on the stove).
bool sPointInRectInset(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  const double m = a[4];
  const double x0 = a[0] + m, y0 = a[1] + m, x1 = a[2] - m, y1 = a[3] - m;
  if (!(x0 <= x1 && y0 <= y1)) return false;
  o[0] = rng.uniform(x0, x1);
  o[1] = rng.uniform(y0, y1);
  return true;
}

// std.text. Texts are string ids in cx.strings. Case folding is ASCII (bytes A-Z); other bytes, including
// UTF-8 sequences, are kept as they are. A missing string table (no program) reads every text as "".
const std::string& textArg(const CallContext& cx, double id) {
  static const std::string empty;
  const auto i = static_cast<std::uint32_t>(id);
  return cx.strings != nullptr && id >= 0 && i < cx.strings->size() ? cx.strings->name(i) : empty;
}

std::string asciiLower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

void fContainsText(const CallContext& cx, Args a, Widths, Out o) {
  o[0] = asciiLower(textArg(cx, a[0])).find(asciiLower(textArg(cx, a[1]))) != std::string::npos ? 1.0 : 0.0;
}

void fLowercase(const CallContext& cx, Args a, Widths, Out o) {
  o[0] = cx.strings == nullptr ? 0.0 : static_cast<double>(cx.strings->intern(asciiLower(textArg(cx, a[0]))));
}

// Characters are Unicode code points of the UTF-8 text: every byte that does not continue a sequence.
void fTextLength(const CallContext& cx, Args a, Widths, Out o) {
  std::int64_t n = 0;
  for (const char c : textArg(cx, a[0])) {
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  }
  o[0] = static_cast<double>(n);
}

}  // namespace

void concatTexts(const CallContext& cx, Args a, Widths, Out o) {
  if (cx.strings == nullptr) {
    o[0] = 0;
    return;
  }
  const auto& x = cx.strings->name(static_cast<std::uint32_t>(a[0]));
  const auto& y = cx.strings->name(static_cast<std::uint32_t>(a[1]));
  o[0] = static_cast<double>(cx.strings->intern(x + y));
}

Builtins Builtins::standard() {
  Builtins b;
  b.addFunction("abs", fAbs);
  b.addFunction("absInt", fAbs);
  b.addFunction("min", fMin);
  b.addFunction("max", fMax);
  b.addFunction("minInt", fMin);
  b.addFunction("maxInt", fMax);
  b.addFunction("clamp", fClamp);
  b.addFunction("clampInt", fClamp);
  b.addFunction("sign", fSign);
  b.addFunction("sqrt", fSqrt);
  b.addFunction("exp", fExp);
  b.addFunction("ln", fLn);
  b.addFunction("floor", fFloor);
  b.addFunction("ceil", fCeil);
  b.addFunction("round", fRound);
  b.addFunction("sin", fSin);
  b.addFunction("cos", fCos);
  b.addFunction("tan", fTan);
  b.addFunction("asin", fAsin);
  b.addFunction("acos", fAcos);
  b.addFunction("atan2", fAtan2);
  b.addFunction("wrapAngle", fWrap);
  b.addFunction("vec2", fVec2);
  b.addFunction("vec3", fVec3);
  b.addFunction("norm", fNorm);
  b.addFunction("distance", fDistance);
  b.addFunction("dot", fDot);
  b.addFunction("cross", fCross);
  b.addFunction("normalize", fNormalize);
  b.addFunction("xy", fXy);
  b.addFunction("gen3Conf", fGen3Conf);
  b.addFunction("se2", fSe2);
  b.addFunction("containsText", fContainsText);
  b.addFunction("lowercase", fLowercase);
  b.addFunction("textLength", fTextLength);
  b.addSampler("uniformInt", sUniformInt);
  b.addSampler("uniformReal", sUniformReal);
  b.addSampler("bernoulli", sBernoulli);
  b.addSampler("uniformInBox", sUniformInBox);
  b.addSampler("keepOrUniformInBox", sKeepOrUniformInBox);
  b.addSampler("pointInRectInset", sPointInRectInset);
  addPoseBuiltins(b);
  return b;
}

FunctionImpl Builtins::function(const std::string& name) const {
  auto it = functions_.find(name);
  return it == functions_.end() ? nullptr : it->second;
}

SamplerImpl Builtins::sampler(const std::string& name) const {
  auto it = samplers_.find(name);
  return it == samplers_.end() ? nullptr : it->second;
}

std::vector<std::string> Builtins::functionNames() const {
  std::vector<std::string> out;
  for (const auto& [n, f] : functions_) out.push_back(n);
  return out;
}

std::vector<std::string> Builtins::samplerNames() const {
  std::vector<std::string> out;
  for (const auto& [n, s] : samplers_) out.push_back(n);
  return out;
}

}  // namespace cbtl::rt
