#include "robot/world/SubtreeKinematics.h"

#include <algorithm>

namespace cbtl::world {

KinematicSubtree::KinematicSubtree(const mjModel* m, int root) {
  if (root <= 0 || root >= m->nbody) return;
  std::vector<char> inside(static_cast<size_t>(m->nbody), 0);
  // MuJoCo numbers bodies depth first, so a body's subtree is a run of later ids whose parents are inside it.
  for (int b = root; b < m->nbody; ++b) {
    if (b != root && !inside[static_cast<size_t>(m->body_parentid[b])]) continue;
    inside[static_cast<size_t>(b)] = 1;
    bodies_.push_back(b);
  }
  for (int g = 0; g < m->ngeom; ++g)
    if (inside[static_cast<size_t>(m->geom_bodyid[g])]) geoms_.push_back(g);
  for (int s = 0; s < m->nsite; ++s)
    if (inside[static_cast<size_t>(m->site_bodyid[s])]) sites_.push_back(s);
  supported_ = std::none_of(bodies_.begin(), bodies_.end(), [m](int b) { return m->body_mocapid[b] >= 0; });
}

namespace {

// The world pose of a frame given in body `b`'s frame at (pos, quat).
void placeInBody(const mjData* d, int b, const mjtNum* pos, const mjtNum* quat, mjtNum* xpos, mjtNum* xmat) {
  mju_rotVecMat(xpos, pos, d->xmat + 9 * b);
  mju_addTo3(xpos, d->xpos + 3 * b);
  mjtNum q[4];
  mju_mulQuat(q, d->xquat + 4 * b, quat);
  mju_quat2Mat(xmat, q);
}

void updateBody(const mjModel* m, mjData* d, int b) {
  const int parent = m->body_parentid[b];
  mjtNum xpos[3], xquat[4];
  mju_rotVecMat(xpos, m->body_pos + 3 * b, d->xmat + 9 * parent);
  mju_addTo3(xpos, d->xpos + 3 * parent);
  mju_mulQuat(xquat, d->xquat + 4 * parent, m->body_quat + 4 * b);

  for (int j = m->body_jntadr[b]; j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
    const int adr = m->jnt_qposadr[j];
    const mjtNum* qpos = d->qpos + adr;
    if (m->jnt_type[j] == mjJNT_FREE) {
      mju_copy3(xpos, qpos);
      mju_copy4(xquat, qpos + 3);
      mju_normalize4(xquat);
      mju_copy3(d->xanchor + 3 * j, xpos);
      mju_copy3(d->xaxis + 3 * j, m->jnt_axis + 3 * j);
      continue;
    }
    // The joint's anchor and axis in the world, in the frame before this joint moves.
    mjtNum offset[3];
    mju_rotVecQuat(offset, m->jnt_pos + 3 * j, xquat);
    mju_add3(d->xanchor + 3 * j, xpos, offset);
    mju_rotVecQuat(d->xaxis + 3 * j, m->jnt_axis + 3 * j, xquat);
    if (m->jnt_type[j] == mjJNT_SLIDE) {
      mju_addToScl3(xpos, d->xaxis + 3 * j, qpos[0] - m->qpos0[adr]);
      continue;
    }
    mjtNum local[4];
    if (m->jnt_type[j] == mjJNT_BALL) {
      mju_copy4(local, qpos);
      mju_normalize4(local);
    } else {
      mju_axisAngle2Quat(local, m->jnt_axis + 3 * j, qpos[0] - m->qpos0[adr]);
    }
    mjtNum rotated[4];
    mju_mulQuat(rotated, xquat, local);
    mju_copy4(xquat, rotated);
    // The rotation is about the anchor, not the body origin: move the origin so the anchor stays put.
    mju_rotVecQuat(offset, m->jnt_pos + 3 * j, xquat);
    mju_sub3(xpos, d->xanchor + 3 * j, offset);
  }
  mju_normalize4(xquat);
  mju_copy3(d->xpos + 3 * b, xpos);
  mju_copy4(d->xquat + 4 * b, xquat);
  mju_quat2Mat(d->xmat + 9 * b, xquat);
  placeInBody(d, b, m->body_ipos + 3 * b, m->body_iquat + 4 * b, d->xipos + 3 * b, d->ximat + 9 * b);
}

}  // namespace

void KinematicSubtree::update(const mjModel* m, mjData* d) const {
  for (int b : bodies_) updateBody(m, d, b);
  for (int g : geoms_)
    placeInBody(d, m->geom_bodyid[g], m->geom_pos + 3 * g, m->geom_quat + 4 * g, d->geom_xpos + 3 * g,
                d->geom_xmat + 9 * g);
  for (int s : sites_)
    placeInBody(d, m->site_bodyid[s], m->site_pos + 3 * s, m->site_quat + 4 * s, d->site_xpos + 3 * s,
                d->site_xmat + 9 * s);
}

}  // namespace cbtl::world
