// PoseBuiltins.cpp — the SE(2) / SE(3) functions and samplers of std.geometry.
//
// Values arrive in the Values.h layout: SE2 = x, y, yaw; SE3 = x, y, z, qx, qy, qz, qw. Quaternions read
// from a program are normalized before use (a user may write a non-unit one in poseQuat), and every SE3
// result carries a unit quaternion with qw >= 0, so equal rotations compare equal component-wise.
#include "runtime/core/PoseBuiltins.h"

#include <Eigen/Geometry>

#include <cmath>

namespace cbtl::rt {

namespace {

using Args = std::span<const double>;
using Widths = std::span<const std::uint16_t>;
using Out = std::span<double>;

struct Pose {
  Eigen::Vector3d p;
  Eigen::Quaterniond q;
};

Pose readPose(const double* a) {
  Eigen::Quaterniond q(a[6], a[3], a[4], a[5]);
  if (q.norm() < 1e-12) q = Eigen::Quaterniond::Identity();
  q.normalize();
  return {Eigen::Vector3d(a[0], a[1], a[2]), q};
}

void writePose(const Pose& x, double* o) {
  Eigen::Quaterniond q = x.q.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  o[0] = x.p.x();
  o[1] = x.p.y();
  o[2] = x.p.z();
  o[3] = q.x();
  o[4] = q.y();
  o[5] = q.z();
  o[6] = q.w();
}

Pose compose(const Pose& a, const Pose& b) { return {a.p + a.q * b.p, a.q * b.q}; }
Pose inverse(const Pose& a) {
  const Eigen::Quaterniond qi = a.q.conjugate();
  return {-(qi * a.p), qi};
}

Eigen::Quaterniond fromRpy(double roll, double pitch, double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

// Tool z pointing down (a half turn about x), then `yaw` about world z.
Eigen::Quaterniond toolDown(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX());
}

double wrap(double a) { return std::remainder(a, 2 * M_PI); }

void fCompose2(const CallContext&, Args a, Widths, Out o) {
  const double c = std::cos(a[2]), s = std::sin(a[2]);
  o[0] = a[0] + c * a[3] - s * a[4];
  o[1] = a[1] + s * a[3] + c * a[4];
  o[2] = wrap(a[2] + a[5]);
}
void fRelative2(const CallContext&, Args a, Widths, Out o) {
  const double c = std::cos(a[2]), s = std::sin(a[2]);
  const double dx = a[3] - a[0], dy = a[4] - a[1];
  o[0] = c * dx + s * dy;
  o[1] = -s * dx + c * dy;
  o[2] = wrap(a[5] - a[2]);
}
void fSe2Distance(const CallContext&, Args a, Widths, Out o) {
  o[0] = std::hypot(a[0] - a[3], a[1] - a[4]) + std::fabs(wrap(a[5] - a[2]));
}
void fSe2AtHeight(const CallContext&, Args a, Widths, Out o) {
  writePose({Eigen::Vector3d(a[0], a[1], a[3]), fromRpy(0, 0, a[2])}, o.data());
}
void fPoseRpy(const CallContext&, Args a, Widths, Out o) {
  writePose({Eigen::Vector3d(a[0], a[1], a[2]), fromRpy(a[3], a[4], a[5])}, o.data());
}
void fPoseQuat(const CallContext&, Args a, Widths, Out o) { writePose(readPose(a.data()), o.data()); }
void fCompose(const CallContext&, Args a, Widths, Out o) {
  writePose(compose(readPose(a.data()), readPose(a.data() + 7)), o.data());
}
void fInverse(const CallContext&, Args a, Widths, Out o) { writePose(inverse(readPose(a.data())), o.data()); }
void fRelativePose(const CallContext&, Args a, Widths, Out o) {
  writePose(compose(inverse(readPose(a.data())), readPose(a.data() + 7)), o.data());
}
void fTransformPoint(const CallContext&, Args a, Widths, Out o) {
  const Pose f = readPose(a.data());
  const Eigen::Vector3d r = f.p + f.q * Eigen::Vector3d(a[7], a[8], a[9]);
  o[0] = r.x();
  o[1] = r.y();
  o[2] = r.z();
}
void fPoseAbove(const CallContext&, Args a, Widths, Out o) {
  Pose p = readPose(a.data());
  p.p.z() += a[7];
  writePose(p, o.data());
}
void fToolDownAbove(const CallContext&, Args a, Widths, Out o) {
  writePose({Eigen::Vector3d(a[0], a[1], a[2] + a[3]), toolDown(a[4])}, o.data());
}
void fRetarget(const CallContext&, Args a, Widths, Out o) {
  const Pose nominal = readPose(a.data()), nominalObject = readPose(a.data() + 7), actual = readPose(a.data() + 14);
  writePose(compose(actual, compose(inverse(nominalObject), nominal)), o.data());
}
void fAngleBetween(const CallContext&, Args a, Widths, Out o) {
  o[0] = readPose(a.data()).q.angularDistance(readPose(a.data() + 7).q);
}

bool sPointInShell(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  const double rMin = a[3], rMax = a[4];
  if (!(0 <= rMin && rMin <= rMax)) return false;
  const double r = rng.uniform(rMin, rMax);
  // Uniform direction: z uniform in [-1, 1] and an azimuth uniform in [0, 2 pi) (Archimedes).
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2 * M_PI);
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  o[0] = a[0] + r * s * std::cos(phi);
  o[1] = a[1] + r * s * std::sin(phi);
  o[2] = a[2] + r * z;
  return true;
}
bool sSe2Near(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  const double h = a[3];
  if (!(h >= 0)) return false;
  o[0] = h > 0 ? rng.uniform(a[0] - h, a[0] + h) : a[0];
  o[1] = h > 0 ? rng.uniform(a[1] - h, a[1] + h) : a[1];
  o[2] = a[2];
  return true;
}
bool sToolDownAbove(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  const double spread = a[4];
  if (!(spread >= 0)) return false;
  const double yaw = spread > 0 ? rng.uniform(-spread, spread) : 0.0;
  writePose({Eigen::Vector3d(a[0], a[1], a[2] + a[3]), toolDown(yaw)}, o.data());
  return true;
}
// As sToolDownAbove, for the point a[5..7] of the tool's frame (a utensil's tip) rather than the frame's origin.
bool sToolDownWithPointAbove(const CallContext&, Args a, Widths, Rng& rng, Out o) {
  const double spread = a[4];
  if (!(spread >= 0)) return false;
  const double yaw = spread > 0 ? rng.uniform(-spread, spread) : 0.0;
  const Eigen::Quaterniond q = toolDown(yaw);
  const Eigen::Vector3d target(a[0], a[1], a[2] + a[3]);
  writePose({target - q * Eigen::Vector3d(a[5], a[6], a[7]), q}, o.data());
  return true;
}

}  // namespace

void addPoseBuiltins(Builtins& b) {
  b.addFunction("compose2", fCompose2);
  b.addFunction("relative2", fRelative2);
  b.addFunction("se2Distance", fSe2Distance);
  b.addFunction("se2AtHeight", fSe2AtHeight);
  b.addFunction("poseRpy", fPoseRpy);
  b.addFunction("poseQuat", fPoseQuat);
  b.addFunction("compose", fCompose);
  b.addFunction("inverse", fInverse);
  b.addFunction("relativePose", fRelativePose);
  b.addFunction("transformPoint", fTransformPoint);
  b.addFunction("poseAbove", fPoseAbove);
  b.addFunction("toolDownAbove", fToolDownAbove);
  b.addFunction("retarget", fRetarget);
  b.addFunction("angleBetween", fAngleBetween);
  b.addSampler("pointInShell", sPointInShell);
  b.addSampler("se2Near", sSe2Near);
  b.addSampler("toolDownAboveSampler", sToolDownAbove);
  b.addSampler("toolDownWithPointAbove", sToolDownWithPointAbove);
}

}  // namespace cbtl::rt
