// HomeSurfaces.h — the seven surfaces of the home scene as the Cleaning and Books .cbtl files name them
// (`enum Surface`), with their scene geoms (the files' `surfaceGeom` table), and the hand frame of the user.
#pragma once

#include "robot/world/WorldOperations.h"

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cbtl::domains::home {

struct HomeSurface {
  std::string_view member;  // enum member of `Surface`
  std::string_view geom;    // box geom of the top face in home.xml
};

inline constexpr std::array<HomeSurface, 7> kHomeSurfaces{{
    {"mainTable", "table_top"},
    {"shelfBottom", "shelf_layer_0"},
    {"shelfMiddle", "shelf_layer_1"},
    {"shelfTop", "shelf_layer_2"},
    {"sideTable0", "side_table_0_top"},
    {"sideTable1", "side_table_1_top"},
    {"sideTable2", "side_table_2_top"},
}};

// The member for a geom / the geom for a member; nullopt when it is none of the seven.
std::optional<std::string> surfaceMemberOfGeom(std::string_view geom);
std::optional<std::string> surfaceGeomOfMember(std::string_view member);
// The seven geoms in declaration order.
std::vector<std::string> homeSurfaceGeoms();

// The user's hand frame for the .cbtl observation `handPose`: at site `user_hand`, oriented so that its
// z axis points at site `handover_center` (the reference's ROM sphere centre, 0.2 m from the hand along the
// hand's z). home.xml gives user_hand no orientation, so the frame is rebuilt from the two sites: with it,
// books.cbtl's romCentre() = hand ∘ (0, 0, 0.2) lands on handover_center (within the sites' rounding).
// nullopt when the scene lacks either site.
std::optional<world::Pose3> userHandFrame(const world::Workspace& ws);

}  // namespace cbtl::domains::home
