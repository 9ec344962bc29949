// SimulatorBase.h — the scaffolding every in-process simulator repeats: the state a training world shares with its
// evaluation twins (the simulated user, the scene, ...), the experiment options, the world's RNG, which role this
// world plays, the evaluation twin itself, and the step results every domain builds.
//
// A domain writes
//   class MySimulator final : public sim::SimulatorBase<MySimulator, MyShared> { ... };
// with one constructor that the base uses to make twins,
//   MySimulator(std::shared_ptr<MyShared> shared, const sim::SimulatorOptions& options, sim::WorldRole role,
//               std::uint64_t seed);
// (private, with `friend class sim::SimulatorBase<MySimulator, MyShared>;`), which builds the world and calls
// reset(seed). makeEvaluationTwin() then constructs a twin from the same shared state with role Evaluation and seed
// 0, as DomainSimulator.h requires: the same user, its own world and RNG.
//
// `Layer` is the class the base derives from: DomainSimulator itself, or a scaffold that implements part of it for a
// family of domains (robot/actions/RobotSimulator.h for the robot domains); the base's constructor passes its extra
// arguments on to Layer's.
//
// Sharing: a twin holds the same std::shared_ptr<Shared>. A domain whose training world changes the shared state
// (Cooking shifts its user's preferences) declares Shared non-const and changes it only in the Training role; the
// twin sees the change, which is the point (an evaluation judges the user as they are now).
#pragma once

#include "runtime/core/Rng.h"
#include "runtime/sim/DomainSimulator.h"

#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

namespace cbtl::sim {

// Which world a simulator is: the one the robot learns in, or an evaluation twin of it.
enum class WorldRole { Training, Evaluation };

// A step that did not happen: the call is not one of the domain's actions or does not fit its declaration (no step
// passes, the world is unchanged). `message` says why.
inline StepResult unknownActionStep(std::string message) {
  StepResult r;
  r.status = ActionStatus::UnknownAction;
  r.message = std::move(message);
  return r;
}

// A step that passed without an action.
inline StepResult idleStep(std::string message) {
  StepResult r;
  r.consumedStep = true;
  r.message = std::move(message);
  return r;
}

template <class Derived, class Shared, class Layer = DomainSimulator>
class SimulatorBase : public Layer {
  static_assert(std::is_base_of_v<DomainSimulator, Layer>, "Layer must be a DomainSimulator");

 public:
  std::unique_ptr<DomainSimulator> makeEvaluationTwin() const override {
    return std::unique_ptr<DomainSimulator>(new Derived(shared_, options_, WorldRole::Evaluation, 0));
  }

  const SimulatorOptions& options() const { return options_; }
  WorldRole role() const { return role_; }

 protected:
  template <class... LayerArgs>
  SimulatorBase(std::shared_ptr<Shared> shared, const SimulatorOptions& options, WorldRole role, LayerArgs&&... layer)
      : Layer(std::forward<LayerArgs>(layer)...), shared_(std::move(shared)), options_(options), role_(role) {}

  const Shared& shared() const { return *shared_; }
  // The shared state itself, for a Training world that changes it (see the header).
  const std::shared_ptr<Shared>& sharedPointer() const { return shared_; }
  bool isEvaluationTwin() const { return role_ == WorldRole::Evaluation; }

  rt::Rng rng_;  // this world's draws; a domain reseeds it in reset(seed)

 private:
  std::shared_ptr<Shared> shared_;
  SimulatorOptions options_;
  WorldRole role_;
};

}  // namespace cbtl::sim
