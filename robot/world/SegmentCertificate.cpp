#include "robot/world/SegmentCertificate.h"

#include "robot/world/GeomDistance.h"
#include "robot/world/MotionBound.h"
#include "robot/world/Separation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace cbtl::world {

const char* toString(SegmentStatus s) {
  switch (s) {
    case SegmentStatus::Certified:
      return "certified";
    case SegmentStatus::Collides:
      return "collides";
    case SegmentStatus::Uncertain:
      return "not certified (grazes)";
  }
  return "unknown";
}

namespace {

constexpr double kUnmeasured = std::numeric_limits<double>::quiet_NaN();

// The body a geom moves with and how far its points lie from that body's origin, or body -1 for a geom that
// stays put during the motion.
struct Mover {
  int body = -1;
  double radius = 0;
};

Mover moverOf(const Workspace& ws, int g) {
  const Scene& s = ws.scene();
  const mjModel* m = s.model();
  const int b = m->geom_bodyid[g];
  const BodyKind kind = s.bodyKind(b);
  if (kind == BodyKind::Robot || kind == BodyKind::Gripper) {
    const double* p = m->geom_pos + 3 * g;
    return {b, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) + m->geom_rbound[g]};
  }
  if (ws.heldObject() >= 0 && s.objectOfBody(b) == ws.heldObject()) {
    // Rigidly attached to the end effector while held: its offset from the end effector's origin is fixed.
    const int ee = s.endEffectorBody();
    const double* x = ws.data()->geom_xpos + 3 * g;
    const double* o = ws.data()->xpos + 3 * ee;
    const double dx = x[0] - o[0], dy = x[1] - o[1], dz = x[2] - o[2];
    return {ee, std::sqrt(dx * dx + dy * dy + dz * dz) + m->geom_rbound[g]};
  }
  return {};
}

// Each pair's motion bound over the whole segment: how much its separation can change from end to end.
// `delta[k]` is |Δq| of MotionBound joint k over the segment.
std::vector<double> pairRates(const Workspace& ws, const std::vector<CheckedPair>& pairs,
                              const std::vector<double>& delta) {
  const MotionBound& mb = ws.scene().motionBound();
  std::vector<int> moving;
  for (std::size_t k = 0; k < delta.size(); ++k)
    if (delta[k] > 0) moving.push_back(static_cast<int>(k));
  std::vector<double> rates(pairs.size(), 0.0);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Mover a = moverOf(ws, pairs[i].g1), b = moverOf(ws, pairs[i].g2);
    double rate = 0;
    for (int k : moving) {
      const bool ma = a.body >= 0 && mb.moves(k, a.body), mbv = b.body >= 0 && mb.moves(k, b.body);
      if (ma && !mbv) rate += delta[static_cast<std::size_t>(k)] * mb.rate(k, a.body, a.radius);
      if (mbv && !ma) rate += delta[static_cast<std::size_t>(k)] * mb.rate(k, b.body, b.radius);
    }
    rates[i] = rate;
  }
  return rates;
}

// The halving search. States are first measured with the cheap lower bounds only; a pair whose cheap bounds at
// a piece's two ends do not carry it over the piece is measured exactly at those ends (where a violation shows),
// and only a pair that still fails is tested at the piece's midpoint.
class Certifier {
 public:
  // `wholeSegment`, when given, may prove a pair clear over the whole segment at once (the Workspace at its start);
  // it is asked only about pairs whose cheap bounds at the two ends do not.
  Certifier(Workspace& ws, const std::vector<CheckedPair>& pairs, std::vector<double> rates,
            std::function<void(double)> setAt, std::function<bool(const CheckedPair&)> wholeSegment = {})
      : ws_(ws),
        pairs_(pairs),
        rates_(std::move(rates)),
        setAt_(std::move(setAt)),
        wholeSegment_(std::move(wholeSegment)) {}

  SegmentReport run() {
    std::vector<int> all(pairs_.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    const int start = measure(0.0, all);
    const int end = measure(1.0, all);
    if (wholeSegment_) settle(start, end, all);
    struct Node {
      int from, to;
      std::vector<int> pairs;
      int depth;
    };
    std::vector<Node> stack{{start, end, std::move(all), 0}};
    while (!stack.empty()) {
      Node node = std::move(stack.back());
      stack.pop_back();
      const double length =
          states_[static_cast<std::size_t>(node.to)].t - states_[static_cast<std::size_t>(node.from)].t;
      std::vector<int> open = failing(node.from, node.to, node.pairs, length);
      if (open.empty()) continue;
      if (!refine(node.from, open, length) || !refine(node.to, open, length)) return report_;
      open = failing(node.from, node.to, open, length);
      if (open.empty()) continue;
      const State& a = states_[static_cast<std::size_t>(node.from)];
      if (node.depth >= kMaxCertificateDepth) {
        fail(SegmentStatus::Uncertain, pairs_[static_cast<std::size_t>(open.front())], 0.0, a.t);
        return report_;
      }
      const double tm = 0.5 * (a.t + states_[static_cast<std::size_t>(node.to)].t);
      const int mid = measure(tm, open);
      stack.push_back({mid, node.to, open, node.depth + 1});
      stack.push_back({node.from, mid, std::move(open), node.depth + 1});
    }
    return report_;
  }

 private:
  struct State {
    double t;
    std::vector<double> slack;  // per pair: a lower bound on separation minus requirement (NaN: unmeasured)
    std::vector<char> exact;    // whether slack is GeomDistance's measure rather than the cheap bound
  };

  // The pairs of `subset` whose slacks at the two states do not prove them apart over a piece of `length`.
  std::vector<int> failing(int from, int to, const std::vector<int>& subset, double length) const {
    const State& a = states_[static_cast<std::size_t>(from)];
    const State& b = states_[static_cast<std::size_t>(to)];
    std::vector<int> out;
    for (int i : subset) {
      const auto u = static_cast<std::size_t>(i);
      if (!(a.slack[u] + b.slack[u] > rates_[u] * length)) out.push_back(i);
    }
    return out;
  }

  // Drops from `subset` the pairs the cheap bounds leave open and wholeSegment_ proves clear.
  void settle(int start, int end, std::vector<int>& subset) {
    const std::vector<int> open = failing(start, end, subset, 1.0);
    if (open.empty()) return;
    setAt_(0.0);
    ++report_.states;
    std::vector<char> settled(pairs_.size(), 0);
    for (int i : open) settled[static_cast<std::size_t>(i)] = wholeSegment_(pairs_[static_cast<std::size_t>(i)]);
    std::erase_if(subset, [&](int i) { return settled[static_cast<std::size_t>(i)] != 0; });
  }

  // The cheap bounds of `subset` at parameter t, as a new state.
  int measure(double t, const std::vector<int>& subset) {
    setAt_(t);
    ++report_.states;
    const mjModel* m = ws_.model();
    const mjData* d = ws_.data();
    State s{t, std::vector<double>(pairs_.size(), kUnmeasured), std::vector<char>(pairs_.size(), 0)};
    for (int i : subset) {
      const auto u = static_cast<std::size_t>(i);
      s.slack[u] = lowerBound(m, d, pairs_[u].g1, pairs_[u].g2) - pairs_[u].required;
    }
    states_.push_back(std::move(s));
    return static_cast<int>(states_.size()) - 1;
  }

  // Measures the pairs of `open` exactly at state `index` (those not measured so); false after recording a
  // violation. A pair's measure stops once it alone would carry the pair over a piece of `length`.
  bool refine(int index, const std::vector<int>& open, double length) {
    State& s = states_[static_cast<std::size_t>(index)];
    bool placed = false;
    for (int i : open) {
      const auto u = static_cast<std::size_t>(i);
      if (s.exact[u]) continue;
      if (!placed) {
        setAt_(s.t);
        ++report_.states;
        placed = true;
      }
      const CheckedPair& p = pairs_[u];
      ++report_.exactQueries;
      const double enough = p.required + std::max(rates_[u] * length, 0.0);
      const double slack = exactSeparation(ws_, p.g1, p.g2, enough, p.required < 0) - p.required;
      if (!(slack > 0)) {
        fail(SegmentStatus::Collides, p, p.required - exactSeparation(ws_, p.g1, p.g2), s.t);
        return false;
      }
      // The cheap bound stays valid; keep the larger of the two.
      s.slack[u] = std::max(s.slack[u], slack);
      s.exact[u] = 1;
    }
    return true;
  }

  void fail(SegmentStatus status, const CheckedPair& p, double depth, double t) {
    const Scene& sc = ws_.scene();
    report_.status = status;
    report_.contact = {p.kind, sc.geomName(p.g1), sc.geomName(p.g2), depth, p.required, {}};
    report_.at = t;
  }

  Workspace& ws_;
  const std::vector<CheckedPair>& pairs_;
  std::vector<double> rates_;
  std::function<void(double)> setAt_;
  std::function<bool(const CheckedPair&)> wholeSegment_;
  std::vector<State> states_;
  SegmentReport report_;
};

int jointNamed(const Scene& s, const char* name) { return mj_name2id(s.model(), mjOBJ_JOINT, name); }

}  // namespace

SegmentReport certifyArmSegment(Workspace& ws, const ArmConfig& a, const ArmConfig& b,
                                const CollisionOptions& options) {
  const Scene& s = ws.scene();
  const MotionBound& mb = s.motionBound();
  ArmConfig step{};
  std::vector<double> delta(mb.joints().size(), 0.0);
  for (int i = 0; i < kArmDof; ++i) {
    step[i] = s.armContinuous(i) ? angleDiff(b[i], a[i]) : b[i] - a[i];
    delta[static_cast<std::size_t>(mb.jointIndex(s.armJointId(i)))] = std::abs(step[i]);
  }
  const std::vector<CheckedPair>& pairs = pairsFor(ws, options);
  // The rates use the held object's offset from the gripper, which the arm's motion does not change.
  Certifier c(ws, pairs, pairRates(ws, pairs, delta), [&](double t) {
    ArmConfig q{};
    for (int i = 0; i < kArmDof; ++i) q[i] = t >= 1.0 ? b[i] : a[i] + t * step[i];
    ws.setArm(q);
  });
  return c.run();
}

SegmentReport certifyBaseSegment(Workspace& ws, const Pose2& a, const Pose2& b, const CollisionOptions& options) {
  const Scene& s = ws.scene();
  const MotionBound& mb = s.motionBound();
  const double dx = b.x - a.x, dy = b.y - a.y, dyaw = angleDiff(b.yaw, a.yaw);
  std::vector<double> delta(mb.joints().size(), 0.0);
  const char* names[3] = {"base_x", "base_y", "base_yaw"};
  const double steps[3] = {dx, dy, dyaw};
  for (int i = 0; i < 3; ++i) {
    const int k = mb.jointIndex(jointNamed(s, names[i]));
    if (k >= 0) delta[static_cast<std::size_t>(k)] = std::abs(steps[i]);
  }
  const std::vector<CheckedPair>& pairs = pairsFor(ws, options);
  auto setAt = [&](double t) {
    if (t >= 1.0) return ws.setBase(b);
    ws.setBase(Pose2{a.x + t * dx, a.y + t * dy, wrapAngle(a.yaw + t * dyaw)});
  };
  const bool slides = jointNamed(s, "base_x") >= 0 && jointNamed(s, "base_y") >= 0;
  if (dyaw != 0 || (dx == 0 && dy == 0) || !slides)
    return Certifier(ws, pairs, pairRates(ws, pairs, delta), setAt).run();
  // A pure translation (a wipe stroke, a straight drive): every robot geom and the held object shift by the same
  // vector, the slides' world axes (fixed: they precede the yaw hinge) times their steps, and turn not at all, so a
  // pair of a moving and a fixed geom can be settled over the whole segment by GeomDistance's translation bound.
  double shift[3] = {0, 0, 0};
  for (const auto& [name, step] : {std::pair{"base_x", dx}, std::pair{"base_y", dy}}) {
    const double* axis = ws.data()->xaxis + 3 * jointNamed(s, name);
    for (int k = 0; k < 3; ++k) shift[k] += step * axis[k];
  }
  const GeomDistance& exact = s.geomDistance();
  auto wholeSegment = [&](const CheckedPair& p) {
    if (moverOf(ws, p.g1).body < 0 || moverOf(ws, p.g2).body >= 0) return false;
    if (!exact.supports(p.g1) || !exact.supports(p.g2)) return false;
    return exact.translationSeparation(ws.data(), p.g1, p.g2, shift) - p.required > 0;
  };
  return Certifier(ws, pairs, pairRates(ws, pairs, delta), setAt, wholeSegment).run();
}

}  // namespace cbtl::world
