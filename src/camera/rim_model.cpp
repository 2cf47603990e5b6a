// The rim model of the board pose refinement: the rim circles of a target,
// the views of a stereo pair with the gradients around the board, and the
// hole walls' occlusion of the rims (see rim_model.hpp).

#include "camera/rim_model.hpp"

#include <opencv2/imgproc.hpp>

#include <optional>

namespace l2s::detail {

Gradient gradient_of(const cv::Mat& image, const cv::Rect& box) {
  Gradient grad;
  const cv::Rect crop = box & cv::Rect(0, 0, image.cols, image.rows);
  grad.x0 = crop.x;
  grad.y0 = crop.y;
  if (crop.area() <= 0) return grad;
  std::vector<cv::Mat> channels;
  cv::split(image(crop), channels);
  for (const cv::Mat& channel : channels) {
    // 3x3 Sobel / 8 is the central difference smoothed across: gray levels / px.
    grad.gx.emplace_back();
    grad.gy.emplace_back();
    cv::Sobel(channel, grad.gx.back(), CV_32F, 1, 0, 3, 1.0 / 8.0);
    cv::Sobel(channel, grad.gy.back(), CV_32F, 0, 1, 3, 1.0 / 8.0);
  }
  return grad;
}

Rims rims_of(const Target& target, int samples_per_rim) {
  Rims rims;
  rims.radius = target.hole_radius;
  rims.thickness = target.board_thickness;
  rims.centers = target.hole_centers();
  const int n = samples_per_rim;
  for (int h = 0; h < 4; ++h)
    for (const double z : {0.0, -rims.thickness})
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * M_PI * (k + 0.5) / n;
        rims.points.emplace_back(rims.centers[h].x() + rims.radius * std::cos(a),
                                 rims.centers[h].y() + rims.radius * std::sin(a), z);
        rims.tangents.emplace_back(-std::sin(a), std::cos(a), 0.0);
        rims.material.emplace_back(std::cos(a), std::sin(a));  // the face lies outside a hole's rim
        rims.hole.push_back(h);
      }
  return rims;
}

namespace {

/// The box around the rims' projection at pose T, padded by `pad` [px];
/// empty when no rim point projects (the board is behind the camera).
std::optional<cv::Rect> board_box(const View& view, const Rims& rims, const Eigen::Isometry3d& T, double pad) {
  double x_min = 1e18, y_min = 1e18, x_max = -1e18, y_max = -1e18;
  for (const auto& X : rims.points) {
    Eigen::Vector2d u;
    if (!view.project(T * X, u, nullptr)) continue;
    x_min = std::min(x_min, u.x()); x_max = std::max(x_max, u.x());
    y_min = std::min(y_min, u.y()); y_max = std::max(y_max, u.y());
  }
  if (x_min > x_max) return std::nullopt;
  return cv::Rect(cv::Point(static_cast<int>(x_min - pad), static_cast<int>(y_min - pad)),
                  cv::Point(static_cast<int>(x_max + pad), static_cast<int>(y_max + pad)));
}

}  // namespace

std::vector<View> views_of(const StereoCamera& camera, const Image& left, const Image& right,
                           const cv::Mat& pixels_left, const cv::Mat& pixels_right, const Rims& rims,
                           const Eigen::Isometry3d& T_camera_board, const BoardPoseRefiner::Params& params) {
  std::vector<View> views;
  const double baseline = camera.baseline();
  views.push_back({camera.left.projection_matrix, Eigen::Vector3d::Zero(), left.width, left.height, {}});
  if (params.use_right_image)
    views.push_back({camera.right.projection_matrix, Eigen::Vector3d(baseline, 0, 0), right.width,
                     right.height, {}});
  for (std::size_t v = 0; v < views.size(); ++v) {
    const double pad = 4.0 * params.search_range_px + 20.0;  // room for the pose to move
    const std::optional<cv::Rect> box = board_box(views[v], rims, T_camera_board, pad);
    if (!box) return {};
    views[v].grad = gradient_of(v == 0 ? pixels_left : pixels_right, *box);
  }
  return views;
}

Rims with_outline(Rims rims, const Target& target, int samples, double corner_gap) {
  const double w = 0.5 * target.board_width, h = 0.5 * target.board_height;
  const double spacing = 4.0 * (w + h) / std::max(samples, 4);
  // Each edge from corner to corner: start, direction, outward normal, length.
  struct Edge {
    Eigen::Vector2d start, direction, outward;
    double length;
  };
  const Edge edges[] = {{{-w, h}, {1, 0}, {0, 1}, 2 * w},
                        {{w, h}, {0, -1}, {1, 0}, 2 * h},
                        {{w, -h}, {-1, 0}, {0, -1}, 2 * w},
                        {{-w, -h}, {0, 1}, {-1, 0}, 2 * h}};
  for (const double z : {0.0, -rims.thickness})
    for (const Edge& edge : edges) {
      const double usable = edge.length - 2.0 * corner_gap;
      const int n = static_cast<int>(std::floor(usable / spacing));
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector2d p = edge.start + (corner_gap + (k + 0.5) * usable / n) * edge.direction;
        rims.points.emplace_back(p.x(), p.y(), z);
        rims.tangents.emplace_back(edge.direction.x(), edge.direction.y(), 0.0);
        rims.material.push_back(-edge.outward);
        rims.hole.push_back(Rims::kOutline);
      }
    }
  return rims;
}

bool hidden_from(const Rims& rims, const Eigen::Vector3d& eye, std::size_t k) {
  const Eigen::Vector3d& X = rims.points[k];
  const double other_z = X.z() == 0.0 ? -rims.thickness : 0.0;
  const double s = (other_z - eye.z()) / (X.z() - eye.z());
  const Eigen::Vector2d Q = (eye + s * (X - eye)).head<2>();  // the line of sight on the other face's plane
  if (rims.hole[k] != Rims::kOutline) return (Q - rims.centers[rims.hole[k]]).norm() > rims.radius;
  // As with a hole: an edge counts where the board borders what lies behind
  // it. While a side face is in view (the line of sight through its front
  // edge enters the board's side), the front edge borders that face and the
  // back edge is the silhouette; otherwise the back edge is hidden.
  const Eigen::Vector2d outward = -rims.material[k];
  return outward.dot(Q) < outward.dot(X.head<2>());
}

}  // namespace l2s::detail
