#include "domains/cooking/CookingWorld.h"

#include <algorithm>
#include <cmath>

namespace cbtl::domains::cooking {

CookingWorld::CookingWorld() { reinitialize(Stock{}); }

void CookingWorld::reinitialize(const Stock& stock) {
  for (std::size_t i = 0; i < kPotCount; ++i) {
    pots_[i] = PotState{};
    pots_[i].radius = kPotRadius[i];
  }
  stock_ = stock;
  mealTicks_ = 0;
  queued_.clear();
}

MoveOutcome CookingWorld::movePot(std::size_t pot, double x, double y) {
  if (pot >= kPotCount) return MoveOutcome::NoSuchPot;
  if (!std::isfinite(x) || !std::isfinite(y)) return MoveOutcome::BadPosition;
  const double r = pots_[pot].radius;
  // Same comparisons as std.geometry's circleInRect and circlesOverlap, so a position the CSP accepts is one
  // the stove accepts.
  if (x - r < 0 || x + r > kStoveSize || y - r < 0 || y + r > kStoveSize) return MoveOutcome::LeavesStove;
  for (std::size_t other = 0; other < kPotCount; ++other) {
    if (other == pot || !pots_[other].onStove) continue;
    const double dx = x - pots_[other].x, dy = y - pots_[other].y;
    if (std::sqrt(dx * dx + dy * dy) < r + pots_[other].radius) return MoveOutcome::Overlaps;
  }
  pots_[pot].onStove = true;
  pots_[pot].x = x;
  pots_[pot].y = y;
  return MoveOutcome::Moved;
}

bool CookingWorld::removeFromStove(std::size_t pot) {
  if (pot >= kPotCount) return false;
  pots_[pot].onStove = false;
  return true;
}

AddOutcome CookingWorld::queueAddition(Ingredient ingredient, std::size_t pot, double quantity) {
  if (pot >= kPotCount) return AddOutcome::NoSuchPot;
  if (!std::isfinite(quantity) || quantity <= 0) return AddOutcome::BadQuantity;
  if (pots_[pot].ingredient) return AddOutcome::PotNotEmpty;
  double available = stock_[indexOf(ingredient)];
  for (const Addition& q : queued_) {
    if (q.pot == pot) return AddOutcome::PotNotEmpty;
    if (q.ingredient == ingredient) available -= q.quantity;
  }
  if (quantity > available) return AddOutcome::NotEnoughStock;
  queued_.push_back(Addition{ingredient, pot, quantity});
  return AddOutcome::Queued;
}

std::vector<Addition> CookingWorld::tick() {
  // Heating first: an ingredient added in this tick starts at 0 and heats from the next tick on.
  for (PotState& p : pots_) {
    if (!p.ingredient) continue;
    if (p.onStove) {
      ++p.temperatureTicks;
    } else {
      p.temperatureTicks = std::max(0, p.temperatureTicks - 1);
    }
  }
  std::vector<Addition> added;
  added.swap(queued_);
  for (const Addition& a : added) {
    PotState& p = pots_[a.pot];
    p.ingredient = a.ingredient;
    p.quantity = a.quantity;
    p.temperatureTicks = 0;
    p.startTick = mealTicks_;
    double& left = stock_[indexOf(a.ingredient)];
    left = std::max(0.0, left - a.quantity);  // queueAddition checked the sum; max only absorbs rounding
  }
  ++mealTicks_;
  return added;
}

std::vector<PotContent> CookingWorld::contents() const {
  std::vector<PotContent> out;
  for (std::size_t i = 0; i < kPotCount; ++i) {
    const PotState& p = pots_[i];
    if (p.ingredient) out.push_back(PotContent{i, *p.ingredient, p.quantity, p.startTick, p.temperatureTicks});
  }
  return out;
}

}  // namespace cbtl::domains::cooking
