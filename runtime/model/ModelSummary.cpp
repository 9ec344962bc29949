#include "runtime/model/ModelSummary.h"

#include <fmt/format.h>

#include <variant>

namespace cbtl::model {
namespace {

std::string answers(std::size_t n) { return fmt::format("{} answer{}", n, n == 1 ? "" : "s"); }

std::string describeInterval(const IntervalModel& m) {
  if (m.data().empty()) return fmt::format("unknown (no data): the declared range {:g} to {:g}", m.lo(), m.hi());
  std::size_t refused = 0;
  for (const auto& [x, holds] : m.data()) refused += holds ? 0 : 1;
  if (!m.hasPositive()) return fmt::format("nothing liked yet, {} refused; {}", refused, answers(m.data().size()));
  return fmt::format(
      "liked from {:.4g} to {:.4g} (the lower bound between {:.4g} and {:.4g}, the upper between "
      "{:.4g} and {:.4g}); {}",
      m.x2(), m.x3(), m.x1(), m.x2(), m.x3(), m.x4(), answers(m.data().size()));
}

std::string describeThreshold(const ThresholdModel& m) {
  const char* side = m.direction() == ThresholdModel::Direction::Above ? "holds at or above" : "holds at or below";
  if (m.data().empty())
    return fmt::format("unknown (no data): {} a threshold somewhere in {:g} to {:g}", side, m.lo(), m.hi());
  if (m.posteriorHi() <= m.posteriorLo())
    return fmt::format("contradictory answers: no threshold fits them ({})", answers(m.data().size()));
  return fmt::format("{} a threshold between {:.4g} and {:.4g}; {}", side, m.posteriorLo(), m.posteriorHi(),
                     answers(m.data().size()));
}

std::string describeTable(const TableModel& m) {
  if (m.entries().empty()) return "unknown (no data)";
  std::string liked, refused;
  for (const auto& [key, holds] : m.entries()) {
    std::string& list = holds ? liked : refused;
    list += (list.empty() ? "" : ", ") + key;
  }
  return fmt::format("liked: {}; refused: {}; {}", liked.empty() ? "none" : liked, refused.empty() ? "none" : refused,
                     answers(m.entries().size()));
}

std::string describeText(const TextFactor& m) {
  if (m.historySize() == 0) return "unknown (no data)";
  return fmt::format("{} ({})", m.model().thetaText(), answers(m.historySize()));
}

}  // namespace

std::string describeFactor(const Factor& factor) {
  return std::visit(
      [](const auto& m) -> std::string {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, IntervalModel>) return describeInterval(m);
        if constexpr (std::is_same_v<M, ThresholdModel>) return describeThreshold(m);
        if constexpr (std::is_same_v<M, TableModel>) return describeTable(m);
        if constexpr (std::is_same_v<M, TextFactor>) return describeText(m);
        return "?";
      },
      factor.model());
}

std::string describeModel(const UserModel& model) {
  std::string text =
      fmt::format("what the robot believes about this person ({} in all):\n", answers(model.dataCount()));
  for (std::size_t g = 0; g < model.size(); ++g) {
    const GeneratorState& state = model.generator(g);
    text += fmt::format("  {}\n", state.spec().name);
    if (state.keys().empty()) {
      for (const Factor& f : state.factors("")) text += fmt::format("    {}: {}\n", f.label(), describeFactor(f));
      continue;
    }
    for (const auto& [key, factors] : state.keys()) {
      for (const Factor& f : factors)
        text += fmt::format("    {}{}: {}\n", key.empty() ? "" : "[" + key + "] ", f.label(), describeFactor(f));
    }
  }
  return text;
}

}  // namespace cbtl::model
