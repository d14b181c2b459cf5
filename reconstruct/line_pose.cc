#include "reconstruct/line_pose.h"

#include <Eigen/Dense>
#include <cmath>

namespace brdfrig::reconstruct {
namespace {

using Params = Eigen::Matrix<double, 6, 1>;  // Rodrigues vector, translation

Eigen::Vector2d Project(const Params& x, const cv::Matx33d& k, const geometry::Vec3& world) {
  const Eigen::Vector3d r = x.head<3>();
  const double angle = r.norm();
  const Eigen::Matrix3d rotation = angle > 0
                                       ? Eigen::AngleAxisd(angle, r / angle).toRotationMatrix()
                                       : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d c = rotation * world + x.tail<3>();
  return {k(0, 0) * c.x() / c.z() + k(0, 2), k(1, 1) * c.y() / c.z() + k(1, 2)};
}

// The image points the fit holds to the posed world lines: per line, the points of the found
// line nearest to where the start pose puts the segment's ends.
struct Anchor {
  std::size_t line;
  Eigen::Vector2d point;
};

Eigen::VectorXd Residuals(const Params& x, const std::vector<PlaneLine>& lines,
                          const std::vector<Anchor>& anchors, const cv::Matx33d& k) {
  Eigen::VectorXd r(anchors.size());
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const PlaneLine& l = lines[anchors[i].line];
    const Eigen::Vector2d pa = Project(x, k, l.a), pb = Project(x, k, l.b);
    const Eigen::Vector2d d = (pb - pa).normalized();
    const Eigen::Vector2d v = anchors[i].point - pa;
    r(static_cast<Eigen::Index>(i)) = v.x() * d.y() - v.y() * d.x();
  }
  return r;
}

}  // namespace

geometry::CameraPose ToCameraPose(const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
  const Eigen::Vector3d r(rvec[0], rvec[1], rvec[2]);
  const double angle = r.norm();
  geometry::CameraPose pose;
  pose.camera_from_world.linear() = angle > 0
                                        ? Eigen::AngleAxisd(angle, r / angle).toRotationMatrix()
                                        : Eigen::Matrix3d::Identity();
  pose.camera_from_world.translation() = Eigen::Vector3d(tvec[0], tvec[1], tvec[2]);
  return pose;
}

bool PoseFromPlaneLines(const std::vector<PlaneLine>& lines, const cv::Matx33d& k,
                        const geometry::CameraPose& start, LinePose* pose) {
  int horizontal = 0, vertical = 0;  // world direction: y = const or x = const
  for (const PlaneLine& l : lines) {
    (std::abs(l.b.y() - l.a.y()) < std::abs(l.b.x() - l.a.x()) ? horizontal : vertical) += 1;
  }
  if (lines.size() < 4 || horizontal == 0 || vertical == 0) return false;
  Params x;
  const Eigen::AngleAxisd start_rotation(start.camera_from_world.linear());
  x.head<3>() = start_rotation.angle() * start_rotation.axis();
  x.tail<3>() = start.camera_from_world.translation();
  std::vector<Anchor> anchors;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const cv::Vec4d& m = lines[i].image;
    const Eigen::Vector2d direction(m[0], m[1]), through(m[2], m[3]);
    for (const geometry::Vec3& end : {lines[i].a, lines[i].b}) {
      const Eigen::Vector2d p = Project(x, k, end);
      anchors.push_back({i, through + direction.dot(p - through) * direction});
    }
  }
  // Levenberg–Marquardt with a forward-difference Jacobian: six unknowns, a few dozen residuals.
  double lambda = 1e-3;
  Eigen::VectorXd r = Residuals(x, lines, anchors, k);
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::MatrixXd jacobian(r.size(), 6);
    for (int j = 0; j < 6; ++j) {
      Params step = x;
      const double h = j < 3 ? 1e-7 : 1e-7 * std::max(1.0, x.tail<3>().norm());
      step(j) += h;
      jacobian.col(j) = (Residuals(step, lines, anchors, k) - r) / h;
    }
    const Eigen::Matrix<double, 6, 6> normal = jacobian.transpose() * jacobian;
    const Params gradient = jacobian.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Eigen::Matrix<double, 6, 6> damped = normal;
      damped.diagonal() *= 1 + lambda;
      const Params delta = damped.ldlt().solve(-gradient);
      const Params next = x + delta;
      const Eigen::VectorXd next_r = Residuals(next, lines, anchors, k);
      if (next_r.allFinite() && next_r.squaredNorm() < r.squaredNorm()) {
        const double gain = r.squaredNorm() - next_r.squaredNorm();
        x = next;
        r = next_r;
        lambda = std::max(lambda / 10, 1e-9);
        improved = true;
        if (gain < 1e-12 * std::max(1.0, r.squaredNorm())) iteration = 50;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  if (!r.allFinite() || x(5) <= 0) return false;
  pose->rvec = {x(0), x(1), x(2)};
  pose->tvec = {x(3), x(4), x(5)};
  pose->rms_px = std::sqrt(r.squaredNorm() / static_cast<double>(r.size()));
  return true;
}

}  // namespace brdfrig::reconstruct
