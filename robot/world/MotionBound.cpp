#include "robot/world/MotionBound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cbtl::world {

namespace {

double norm3(const mjtNum* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// How far joint j can move its body's origin relative to the frame it is applied in: twice its anchor offset for a
// hinge (the origin circles the anchor), its largest travel from the reference position for a slide (infinite
// when the slide is unlimited).
double originTravel(const mjModel* m, int j) {
  if (m->jnt_type[j] == mjJNT_HINGE) return 2 * norm3(m->jnt_pos + 3 * j);
  if (m->jnt_type[j] == mjJNT_SLIDE) {
    if (!m->jnt_limited[j]) return std::numeric_limits<double>::infinity();
    const double ref = m->qpos0[m->jnt_qposadr[j]];
    return std::max(std::abs(m->jnt_range[2 * j] - ref), std::abs(m->jnt_range[2 * j + 1] - ref));
  }
  return std::numeric_limits<double>::infinity();  // ball and free joints: not robot joints here
}

}  // namespace

MotionBound::MotionBound(const mjModel* m, const std::vector<bool>& robotBody) {
  nbody_ = static_cast<std::size_t>(m->nbody);
  jointIndex_.assign(static_cast<std::size_t>(m->njnt), -1);
  for (int j = 0; j < m->njnt; ++j) {
    const int type = m->jnt_type[j];
    if (!robotBody[static_cast<std::size_t>(m->jnt_bodyid[j])]) continue;
    if (type != mjJNT_HINGE && type != mjJNT_SLIDE) continue;
    jointIndex_[static_cast<std::size_t>(j)] = static_cast<int>(joints_.size());
    joints_.push_back(j);
    slide_.push_back(type == mjJNT_SLIDE);
  }
  reach_.assign(joints_.size() * nbody_, -1.0);
  for (std::size_t k = 0; k < joints_.size(); ++k) {
    const int j = joints_[k];
    const int jb = m->jnt_bodyid[j];
    // The joint's own body: its anchor offset, plus what the joints applied after it in the same body add.
    double own = norm3(m->jnt_pos + 3 * j);
    for (int o = j + 1; o < m->body_jntadr[jb] + m->body_jntnum[jb]; ++o) own += originTravel(m, o);
    reach_[index(static_cast<int>(k), jb)] = own;
    // Bodies are numbered parents first, so one pass down the ids reaches the whole subtree.
    for (int b = jb + 1; b < m->nbody; ++b) {
      const double parent = reach_[index(static_cast<int>(k), m->body_parentid[b])];
      if (parent < 0) continue;
      double r = parent + norm3(m->body_pos + 3 * b);
      for (int o = m->body_jntadr[b]; o < m->body_jntadr[b] + m->body_jntnum[b]; ++o) r += originTravel(m, o);
      reach_[index(static_cast<int>(k), b)] = r;
    }
  }
}

int MotionBound::jointIndex(int joint) const {
  if (joint < 0 || static_cast<std::size_t>(joint) >= jointIndex_.size()) return -1;
  return jointIndex_[static_cast<std::size_t>(joint)];
}

double MotionBound::rate(int k, int body, double r) const {
  const double reach = reach_[index(k, body)];
  if (reach < 0) return 0.0;
  return slide_[static_cast<std::size_t>(k)] ? 1.0 : reach + r;
}

}  // namespace cbtl::world
