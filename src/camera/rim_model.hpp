#pragma once
// The model the rim refinement fits (private to the library): the board's
// hole rims in 3D, the rectified views they project into, the image
// gradients they are matched against, and which rim points a view can see.
// Apart from the edge search (rim_edge_search.hpp) and the Gauss-Newton fit
// (board_pose_refiner.cpp) because both work on it.

#include <l2s/board_pose_refiner.hpp>

#include <opencv2/core.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace l2s::detail {

/// Directional gradients of a crop of an 8-bit image, in gray levels per
/// pixel: one pair per channel (one for gray, three for colour).
struct Gradient {
  std::vector<cv::Mat> gx, gy;  // CV_32F, per channel
  int x0 = 0, y0 = 0;

  /// The strongest channel's |gradient . normal| at full-image coordinates
  /// (Catmull-Rom bicubic); false outside the crop. Bilinear interpolation
  /// would make the profile along a search line piecewise linear with kinks
  /// at the pixel grid, and the parabolic peak fit would lock towards them:
  /// a bias of ~0.02 px that differs between the views, i.e. ~1 mm of depth
  /// per hole at 3.5 m.
  bool along(double x, double y, const Eigen::Vector2d& normal, double& value) const {
    if (gx.empty()) return false;
    const double fx = x - x0, fy = y - y0;
    const int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
    if (ix < 1 || iy < 1 || ix + 2 >= gx[0].cols || iy + 2 >= gx[0].rows) return false;
    const auto weights = [](double t, double w[4]) {
      const double t2 = t * t, t3 = t2 * t;
      w[0] = 0.5 * (-t3 + 2 * t2 - t);
      w[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
      w[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
      w[3] = 0.5 * (t3 - t2);
    };
    double wx[4], wy[4];
    weights(fx - ix, wx);
    weights(fy - iy, wy);
    const auto interp = [&](const cv::Mat& m) {
      double sum = 0.0;
      for (int j = 0; j < 4; ++j) {
        const float* r = m.ptr<float>(iy - 1 + j) + ix - 1;
        sum += wy[j] * (wx[0] * r[0] + wx[1] * r[1] + wx[2] * r[2] + wx[3] * r[3]);
      }
      return sum;
    };
    value = 0.0;
    for (std::size_t c = 0; c < gx.size(); ++c)
      value = std::max(value, std::abs(interp(gx[c]) * normal.x() + interp(gy[c]) * normal.y()));
    return true;
  }
};

/// The gradients of `image` within `box` (clipped to the image); without
/// channels (along() false everywhere) when the box misses the image.
Gradient gradient_of(const cv::Mat& image, const cv::Rect& box);

/// One rectified camera: projection matrix P (left optical frame in) and centre.
struct View {
  Eigen::Matrix<double, 3, 4> P;
  Eigen::Vector3d center;  // [m] in the left optical frame
  int width = 0, height = 0;
  Gradient grad;

  bool project(const Eigen::Vector3d& p, Eigen::Vector2d& u, Eigen::Matrix<double, 2, 3>* J) const {
    const Eigen::Vector3d h = P * p.homogeneous();
    if (!(h.z() > 1e-6)) return false;
    u = h.head<2>() / h.z();
    if (J) *J = (P.topLeftCorner<2, 3>() - u * P.block<1, 3>(2, 0)) / h.z();
    return true;
  }
};

/// A rim point matched to an image edge in one view.
struct Sample {
  int view;
  Eigen::Vector3d X_board;   // [m] on a rim circle (or a known point: an anchor)
  Eigen::Vector2d normal;    // unit, image normal of the projected rim (an anchor: one image axis)
  Eigen::Vector2d observed;  // [px] edge position found on the search line
  double weight = 1.0;       // an anchor's weight relative to one rim sample
  bool rim = true;           // false: an anchor (not in the edge rms)
  bool outline = false;      // on the board's outer edge, not a hole's rim
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();  // an outline sample: away from the board, board frame
};

/// The hole rims in the board frame: each hole's front (z = 0) and back
/// (z = -thickness) circle, sampled evenly, with the tangent at each sample;
/// optionally (with_outline) the board's outer edges too, front and back.
struct Rims {
  std::vector<Eigen::Vector3d> points;    // [m] board frame, [hole][rim][theta], then the outline's
  std::vector<Eigen::Vector3d> tangents;  // unit, board frame
  std::vector<Eigen::Vector2d> material;  // unit, board plane: from the point into the board's material
  std::vector<int> hole;                  // the hole of each point; kOutline for the board's outer edges
  std::array<Eigen::Vector2d, 4> centers;  // [m] hole centres, board frame
  double radius = 0.0;     // [m]
  double thickness = 0.0;  // [m]

  static constexpr int kOutline = -1;
};

/// The rims of `target`'s holes, `samples_per_rim` points on each circle.
Rims rims_of(const Target& target, int samples_per_rim);

/// `rims` and the board's four outer edges, front (z = 0) and back, about
/// `samples` points per face spread evenly along the perimeter, none within
/// `corner_gap` [m] of a corner (where two edges meet, and real boards are
/// often rounded).
Rims with_outline(Rims rims, const Target& target, int samples, double corner_gap);

/// True when rim or outline point k cannot be seen from `eye` (board frame):
/// a hole's wall hides it, or, on the outline's back edge, the board itself.
bool hidden_from(const Rims& rims, const Eigen::Vector3d& eye, std::size_t k);

/// The left view (and the right one, with use_right_image), each with the
/// gradient of the board's neighbourhood only: the whole image's would cost
/// more than the fit. Empty when the board is behind a camera.
std::vector<View> views_of(const StereoCamera& camera, const Image& left, const Image& right,
                           const cv::Mat& pixels_left, const cv::Mat& pixels_right, const Rims& rims,
                           const Eigen::Isometry3d& T_camera_board, const BoardPoseRefiner::Params& params);


/// Where a rim point projects in a view and the image normal of its rim there.
struct RimPixel {
  Eigen::Vector2d u;       // [px]
  Eigen::Vector2d normal;  // unit
};

}  // namespace l2s::detail
