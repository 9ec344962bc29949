// OptionChecks.h — CLI11 validators for the numeric options of `cbtl` commands.
//
// Each validator checks the option's text before CLI11 converts it, so a bad value is a CLI11 ValidationError:
// main() prints "<option>: <reason>" and exits 2 (usage). They parse the text the way CLI11 converts it
// (strtoll/strtoull with base 0, strtod), and:
//   integerIn(lo, hi)  — a signed integer in [lo, hi];
//   unsignedIn(lo, hi) — an unsigned integer in [lo, hi], with no minus sign (CLI11 itself would wrap "-1" to
//                        2^64 - 1 for a std::uint64_t option);
//   realIn(lo, hi)     — a finite real in [lo, hi] (NaN and infinities are refused; CLI::Range lets NaN through).
// Text that is not a number at all is refused too, with the option's name in the message.
#pragma once

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

namespace cbtl::cli {

inline constexpr std::int64_t kNoMax = std::numeric_limits<std::int64_t>::max();

namespace detail {

// The bound as shown in --help: "..." for no upper limit.
inline std::string boundText(std::int64_t v) { return v == kNoMax ? "..." : std::to_string(v); }

// True when `text` is all consumed by strto*, i.e. a number CLI11 would also accept.
inline bool consumedAll(const std::string& text, const char* end) {
  return !text.empty() && end == text.c_str() + text.size();
}

}  // namespace detail

inline CLI::Validator integerIn(std::int64_t lo, std::int64_t hi = kNoMax) {
  const std::string range = fmt::format("[{}, {}]", lo, detail::boundText(hi));
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const long long v = std::strtoll(text.c_str(), &end, 0);
        if (!detail::consumedAll(text, end)) return fmt::format("'{}' is not an integer", text);
        if (errno == ERANGE || v < lo || v > hi) return fmt::format("{} is outside {}", text, range);
        return {};
      },
      "INT in " + range, "integerIn");
}

inline CLI::Validator unsignedIn(std::uint64_t lo, std::uint64_t hi = std::numeric_limits<std::uint64_t>::max()) {
  const std::string range = fmt::format(
      "[{}, {}]", lo, hi == std::numeric_limits<std::uint64_t>::max() ? std::string("...") : std::to_string(hi));
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        if (text.find('-') != std::string::npos)
          return fmt::format("{} is negative; the value must be in {}", text, range);
        errno = 0;
        char* end = nullptr;
        const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
        if (!detail::consumedAll(text, end)) return fmt::format("'{}' is not a non-negative integer", text);
        if (errno == ERANGE || v < lo || v > hi) return fmt::format("{} is outside {}", text, range);
        return {};
      },
      "UINT in " + range, "unsignedIn");
}

inline CLI::Validator realIn(double lo, double hi) {
  auto show = [](double v) { return std::isinf(v) ? std::string(v < 0 ? "-inf" : "inf") : fmt::format("{}", v); };
  const std::string range = fmt::format("[{}, {}]", show(lo), show(hi));
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (!detail::consumedAll(text, end)) return fmt::format("'{}' is not a number", text);
        if (!std::isfinite(v)) return fmt::format("{} is not a finite number", text);
        if (v < lo || v > hi) return fmt::format("{} is outside {}", text, range);
        return {};
      },
      "REAL in " + range, "realIn");
}

}  // namespace cbtl::cli
