#pragma once
// Camera-side discontinuity filter: keep the board-plane stereo points that lie
// on intensity edges, then drop the board's outer border lines
// (paper Sec. III-B, Sobel threshold tau_sobel; Sec. III-C, line removal).

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <cstdint>
#include <string>

namespace l2s {

/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT EdgeFilter {
 public:
  /// How the 3x3 Sobel responses gx, gy (cv::Sobel on the 8-bit gray image or, with
  /// Params::colour, on the strongest channel,
  /// each in [-1020, 1020]) become one 8-bit-like magnitude in [0, 255].
  enum class Magnitude {
    Hypot,     ///< min(255, sqrt(gx^2 + gy^2)): a step of 32 gray levels reaches 128
    HalfL1,    ///< 0.5 * sat(|gx|) + 0.5 * sat(|gy|), sat = clamp to 255 (the usual OpenCV recipe)
  };

  struct Params {
    double sobel_threshold = 128.0;  ///< tau_sobel: keep pixels whose magnitude >= this, 0..255
    double adaptive_quantile = 0.98;  ///< the board region's strong edges: this quantile of its magnitudes (rims and outline are a few % of it); 0 = fixed tau_sobel, 0..1
    double adaptive_fraction = 0.5;  ///< on a low-contrast board the threshold drops to this fraction of those strong edges, (0, 1]
    double min_sobel_threshold = 16.0;  ///< ... but never below this, 0..255
    double noise_factor = 4.0;       ///< ... nor below this many sigmas of the Sobel response to the image's own noise, >= 0
    int region_dilation_px = 3;      ///< [px] the board region is its points' pixels widened by this (stereo leaves the rims themselves unmatched), 0..50
    Magnitude magnitude = Magnitude::Hypot;  ///< scaling of the Sobel magnitude (see enum)
    /// Colour images: each pixel's gradient from its strongest channel (rims
    /// that differ from the face in hue more than in brightness); gray ones
    /// ignore it. The camera branch turns it on for a second try when the
    /// gray edges give no hole pattern.
    bool colour = false;
    bool remove_border_lines = true;  ///< drop the outer border of the board (Sec. III-C)
    double line_distance = 0.02;     ///< [m] RANSAC inlier distance to a border line (SGM scatters borders by ~1 cm), > 0
    int line_iterations = 200;       ///< RANSAC samples per line, >= 1
    int max_border_lines = 4;        ///< at most this many border lines are removed, 0..8
    int min_line_points = 15;        ///< fewer inliers than this end the line search, >= 2
    double max_line_tilt_deg = 20.0; ///< [deg] border lines deviate at most this from the board's horizontal/vertical, 0..45
    double min_border_fraction = 0.4;  ///< a border's contiguous run spans >= this fraction of its board side, (0, 1]
    double max_gap = 0.1;            ///< [m] largest gap inside a contiguous run of line points; below the gap between two hole tangents, > 0
    std::uint64_t seed = 1;          ///< RANSAC seed

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  struct Result {
    bool found = false;        ///< some edge points survived
    std::string reason;        ///< why not, when !found
    StereoCloud edges;         ///< [m] camera frame: edge points (on the plane) minus border lines, with pixels
    std::vector<Eigen::Vector3d> gradients;  ///< one per edge point: unit in-plane direction of the image gradient (camera frame)
    std::size_t input_points = 0;   ///< board-plane points given
    std::size_t edge_points = 0;    ///< image edge pixels in the board's region, cast onto the plane
    double sobel_threshold = 0.0;   ///< the threshold used (tau_sobel or the adaptive one)
    std::size_t border_points = 0;  ///< of those, removed as board border
    int border_lines = 0;           ///< border lines found and removed
  };

  // `Stage(Params = {})` does not compile with GCC while Params has default
  // member initializers (they are parsed only once the outer class is complete).
  EdgeFilter() : EdgeFilter(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit EdgeFilter(Params params);
  const Params& params() const { return params_; }

  /// `left`: the rectified left image (gray or BGR) the cloud's pixels refer
  /// to; `camera`: its camera (edge pixels are cast onto the plane through
  /// it); `board_cloud`: stereo points of the board plane; `plane_camera`:
  /// that plane; `target`: the board, for the border lengths. Throws
  /// InputError naming the image when it is unusable or not the camera's
  /// size, ParamError for an invalid target or a cloud whose pixels and
  /// points differ in count.
  Result filter(const Image& left, const CameraInfo& camera, const StereoCloud& board_cloud,
                const Plane& plane_camera, const Target& target) const;

 private:
  Params params_;
};

}  // namespace l2s
