// FeedingActions.h — Feeding's own actions on the robot world (feeding.cbtl), for both the simulator that carries
// plans out and the runtime's world model that dry-runs them (robot/actions/RobotActions.h DomainActions):
//
//   movePlate(xy), moveDrink(xy)  the caregiver slides the plate or the drink (TableSlide.h).
//   grasp("drink")                the drink is taken by its handle: a collision-free IK solution for the tool
//                                 kDrinkApproach behind the grasp (tool z along world +y; of a few IK draws the
//                                 first the straight joint segment reaches free), the arm moved there, the
//                                 open fingers slid along the handle's sides in a straight line to the grasp, the
//                                 gripper closed on the handle (world/GraspClosure.h: a grasp on air fails), and the
//                                 drink lifted kDrinkLift (a certified segment that may start with the drink resting
//                                 on the table); feeding.cbtl then carries it to its post-grasp pose and sets it down.
//   release() holding the utensil the utensil goes back on its mount: the tool must be within kMountTolerance
//                                 of the mount's grasp pose; the utensil is set to its mount pose (the scene's).
//   acquireFood()                 the held utensil must be over the plate (its fork tip, site utensil_tip,
//                                 within kFoodReach of the plate's centre).
//   dipInto(sauce), waitForReady(signal)  change nothing in the world (the simulator checks the sauce is on the
//                                 table and records the signal).
// Every other call is the standard executor's. Pure and both modes as RobotActions.h says; failures leave the
// world as it was.
#pragma once

#include "robot/actions/RobotActions.h"

#include <map>
#include <memory>
#include <string>

namespace cbtl::domains::feeding {

// The tool frame stops this far short of the handle's centre (world -y): the finger pads (0.02 m behind to 0.05 m
// past the tool frame) then cover the handle's first 3 cm, its whole height, and the palm stays 4.5 cm clear.
inline constexpr double kDrinkGraspStandoff = 0.05;
inline constexpr double kDrinkApproach = 0.06;  // metres further back where the straight approach starts
inline constexpr double kUtensilGraspDepth =
    0.05955;  // metres from the tool frame to the utensil's grasp frame (finger_tip)
// Metres the tool rises after closing on the handle: 1.5 cm, so that the drink it carries off keeps feeding.cbtl's 1 cm
// from the table with 5 mm to spare (lifted 1 cm, every move after the lift started without slack, and a slice of
// two seeds had a training request for the drink the solver could not plan within its budget).
inline constexpr double kDrinkLift = 0.015;
inline constexpr double kMountTolerance = 0.03;  // metres from the mount pose where a release re-mounts
inline constexpr double kFoodReach = 0.10;       // metres from the plate centre where food can be picked up

// The tool pose grasp("drink") stops at for the drink standing at `drink` (before its lift), and the drink's pose in
// the tool frame while held: what a drink held at any configuration looks like.
world::Pose3 drinkHandlePose(const world::Pose3& drink);
world::Pose3 drinkInTool(const world::Pose3& drink);

class FeedingActions final : public actions::DomainActions {
 public:
  // `utensilMount`: the utensil's pose on its mount (the scene's initial pose).
  explicit FeedingActions(world::Pose3 utensilMount) : mount_(std::move(utensilMount)) {}
  // Reads the mount pose from the scene.
  static std::shared_ptr<const FeedingActions> forScene(const world::Scene& scene);

  std::optional<actions::RobotActionResult> execute(world::World& w, const sim::ActionCall& call,
                                                    actions::ExecutionMode mode) const override;
  bool handles(std::string_view name) const override;

 private:
  actions::RobotActionResult graspDrink(world::World& w, actions::ExecutionMode mode) const;
  actions::RobotActionResult releaseUtensil(world::World& w) const;
  actions::RobotActionResult acquireFood(world::World& w) const;

  world::Pose3 mount_;
};

}  // namespace cbtl::domains::feeding
