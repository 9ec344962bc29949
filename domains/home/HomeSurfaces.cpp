#include "domains/home/HomeSurfaces.h"

namespace cbtl::domains::home {

std::optional<std::string> surfaceMemberOfGeom(std::string_view geom) {
  for (const HomeSurface& s : kHomeSurfaces)
    if (s.geom == geom) return std::string(s.member);
  return std::nullopt;
}

std::optional<std::string> surfaceGeomOfMember(std::string_view member) {
  for (const HomeSurface& s : kHomeSurfaces)
    if (s.member == member) return std::string(s.geom);
  return std::nullopt;
}

std::vector<std::string> homeSurfaceGeoms() {
  std::vector<std::string> out;
  for (const HomeSurface& s : kHomeSurfaces) out.emplace_back(s.geom);
  return out;
}

std::optional<world::Pose3> userHandFrame(const world::Workspace& ws) {
  const auto hand = ws.sitePose("user_hand");
  const auto centre = ws.sitePose("handover_center");
  if (!hand || !centre) return std::nullopt;
  const Eigen::Vector3d z = centre->position - hand->position;
  if (z.norm() < 1e-9) return world::Pose3{hand->position, Eigen::Quaterniond::Identity()};
  // The smallest rotation taking the world z axis onto the hand's z.
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), z.normalized());
  return world::Pose3{hand->position, q};
}

}  // namespace cbtl::domains::home
