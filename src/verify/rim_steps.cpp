#include "verify/rim_steps.hpp"

#include "camera/cv_image.hpp"
#include "camera/noise_level.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

/// Counts of judged and stepped arcs.
struct ArcCount {
  int arcs = 0, stepped = 0;
  double share() const {
    return arcs > 0 ? static_cast<double>(stepped) / arcs : std::numeric_limits<double>::quiet_NaN();
  }
};

/// One view: its image, camera and noise.
struct StepView {
  const cv::Mat& image;
  const CameraInfo& camera;
  double noise;  // [gray levels] sigma per pixel
};

/// Walks circles on the board plane in one view and judges each arc's step.
class ArcJudge {
 public:
  ArcJudge(const StepView& view, const Eigen::Isometry3d& T_camera_board, const RimStepParams& params)
      : view_(view), T_(T_camera_board), params_(params) {}

  /// The circle of `radius` around `centre` (board frame); `counts(q)` says
  /// whether the board-frame place q takes part (the face circles: on the
  /// board, off the holes).
  template <class Counts>
  void circle(const Eigen::Vector2d& centre, double radius, Counts counts, ArcCount& out) const {
    const int per_arc = params_.samples_per_arc, arcs = params_.arcs_per_circle;
    for (int a = 0; a < arcs; ++a) {
      double sum = 0.0, length = 0.0;
      int n = 0;
      Eigen::Vector2d previous = Eigen::Vector2d::Zero();
      for (int s = 0; s < per_arc; ++s) {
        const double theta = 2.0 * M_PI * (a * per_arc + s + 0.5) / (arcs * per_arc);
        const Eigen::Vector2d radial(std::cos(theta), std::sin(theta));
        const Eigen::Vector2d q = centre + radius * radial;
        double step = 0.0;
        Eigen::Vector2d u;
        if (!counts(q) || !step_at(q, radial, u, step)) continue;
        if (n > 0) length += (u - previous).norm();
        previous = u;
        sum += step;
        ++n;
      }
      if (2 * n < per_arc) continue;  // mostly outside the image or off the face
      // Samples closer than pixels_per_sample share their noise.
      const double independent = std::clamp(length / params_.pixels_per_sample + 1.0, 1.0, static_cast<double>(n));
      const double sigma = view_.noise / std::sqrt(independent);
      ++out.arcs;
      if (std::abs(sum / n) > params_.noise_factor * sigma) ++out.stepped;
    }
  }

 private:
  /// The mean brightness beyond the circle at q (along `radial`, board
  /// frame) less that inside it, near_px..far_px from it in the image.
  bool step_at(const Eigen::Vector2d& q, const Eigen::Vector2d& radial, Eigen::Vector2d& u, double& step) const {
    const Eigen::Vector3d p = T_ * Eigen::Vector3d(q.x(), q.y(), 0.0);
    const Eigen::Vector3d beyond = T_ * Eigen::Vector3d(q.x() + 1e-3 * radial.x(), q.y() + 1e-3 * radial.y(), 0.0);
    if (!(p.z() > 0.0 && beyond.z() > 0.0)) return false;
    u = view_.camera.project(p);
    const Eigen::Vector2d along = view_.camera.project(beyond) - u;
    if (!u.allFinite() || !(along.norm() > 1e-9)) return false;
    const Eigen::Vector2d n = along.normalized();
    const double reach = params_.far_px + 1.0;
    if (u.x() < reach || u.y() < reach || u.x() > view_.image.cols - 1 - reach || u.y() > view_.image.rows - 1 - reach)
      return false;
    step = 0.0;
    for (const double d : {params_.near_px, params_.far_px}) {
      const Eigen::Vector2d out = u + d * n, in = u - d * n;
      step += gray_at(view_.image, out.x(), out.y()) - gray_at(view_.image, in.x(), in.y());
    }
    step *= 0.5;
    return true;
  }

  const StepView& view_;
  const Eigen::Isometry3d& T_;
  const RimStepParams& params_;
};

}  // namespace

RimSteps rim_steps(const cv::Mat& left, const cv::Mat& right, const StereoCamera& cameras, const Target& target,
                   const Eigen::Isometry3d& T_camera_board, const RimStepParams& params) {
  const auto holes = target.hole_centers();
  const double face = params.face_radius * target.hole_radius;
  // A face circle's place must lie on the board, its whole step band too,
  // and off every hole (neighbouring holes of a dense pattern).
  const auto on_face = [&](const Eigen::Vector2d& q) {
    const double band = face - target.hole_radius;
    if (std::abs(q.x()) > 0.5 * target.board_width - band || std::abs(q.y()) > 0.5 * target.board_height - band)
      return false;
    for (const Eigen::Vector2d& c : holes)
      if ((q - c).norm() < 0.999 * face) return false;
    return true;
  };
  const auto anywhere = [](const Eigen::Vector2d&) { return true; };
  ArcCount rims, faces;
  const StepView views[2] = {{left, cameras.left, image_noise_sigma(left)},
                             {right, cameras.right, image_noise_sigma(right)}};
  for (const StepView& view : views) {
    const ArcJudge judge(view, T_camera_board, params);
    for (const Eigen::Vector2d& c : holes) {
      judge.circle(c, target.hole_radius, anywhere, rims);
      judge.circle(c, face, on_face, faces);
    }
  }
  return {rims.share(), faces.share()};
}

}  // namespace l2s::detail
