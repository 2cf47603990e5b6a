#pragma once
// Stereo matching: a rectified pair to a disparity map and a stereo cloud
// (paper Sec. III-A, Semi-Global Matching after Hirschmuller 2008).

#include <l2s/camera.hpp>
#include <l2s/export.hpp>
#include <l2s/geometry.hpp>
#include <l2s/types.hpp>

#include <string>
#include <vector>

namespace l2s {

/// A rectangle of pixels; a zero width or height means "the whole image".
struct PixelRect {
  int x = 0;       ///< [px] first column
  int y = 0;       ///< [px] first row
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  bool empty() const { return width <= 0 || height <= 0; }
};

/// Disparity of the left image, kept for diagnostics. Cell (i, j) covers the
/// left pixel (x0 + (i + 0.5) / scale - 0.5, y0 + (j + 0.5) / row_scale - 0.5).
struct DisparityMap {
  int width = 0;        ///< [cells]
  int height = 0;       ///< [cells]
  int x0 = 0;           ///< [px] left-image column of the first cell
  int y0 = 0;           ///< [px] left-image row of the first cell
  double scale = 1.0;   ///< cells per left-image column (1 = full resolution)
  double row_scale = 1.0;  ///< cells per left-image row (scale * row_downscale)
  std::vector<float> values;  ///< [px] full-resolution disparity, row-major; NaN = no match

  float at(int i, int j) const { return values[static_cast<std::size_t>(j) * width + i]; }
  bool empty() const { return values.empty(); }
};

/// Semi-Global Matching (cv::StereoSGBM) on a rectified pair, then
/// triangulation Z = fx * B / d into the left optical frame. The disparity
/// search follows the rig: it spans exactly the depths min_depth..max_depth
/// for the fx * B of the cameras given to match(), so the working range means
/// the same on every rig. Matches at the edge of that window (the true match
/// lies outside it: SGBM clamps), or failing SGBM's left-right or uniqueness
/// checks, give no point.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT StereoMatcher {
 public:
  /// Cost aggregation paths of SGBM: 5 (single pass), 8 (two passes, slow),
  /// 8 in three passes (fast, parallel), 4 paths (HH4).
  enum class Mode { Sgbm5, Hh8, Sgbm3Way, Hh4 };

  struct Params {
    int block_size = 5;        ///< [px] odd matching window, 1..11
    int p1 = 0;                ///< smoothness penalty for +-1 px disparity steps; 0 = 8 * block_size^2
    int p2 = 0;                ///< penalty for larger disparity steps, > p1; 0 = 32 * block_size^2
    int disp12_max_diff = 1;   ///< [px] left-right consistency tolerance; < 0 disables
    int pre_filter_cap = 63;   ///< clamp of the x-derivative prefilter, 1..63
    int uniqueness_ratio = 10; ///< [%] best cost must beat the second best by this margin, 0..100
    int speckle_window_size = 100;  ///< [px] largest speckle region removed; 0 disables
    int speckle_range = 2;     ///< [px] disparity variation inside a connected region, >= 0
    Mode mode = Mode::Sgbm3Way;  ///< aggregation variant; Sgbm3Way is the fastest
    double downscale = 1.0;    ///< processing scale of columns and rows, (0, 1]; 0.5 matches at half resolution (~6x faster), but SGBM's sub-pixel disparity locks to whole (coarser) pixels: a slanted board becomes terraces of ~2 cm at 3.5 m
    double row_downscale = 1.0;  ///< further scale of the rows only, (0, 1]; rows carry no disparity, so 0.5 halves the cost while depth keeps the column resolution
    PixelRect roi;             ///< [px] part of the left image to match; empty = all
    double min_depth = 1.0;    ///< [m] nearest depth searched: the largest disparity is fx * B / min_depth, > 0
    double max_depth = 10.0;   ///< [m] farthest depth searched: the smallest disparity is fx * B / max_depth, > min_depth
    double guard_px = 8.0;     ///< [px] the search reaches this far (full resolution) beyond the window on each side and drops what it finds there: a surface just outside the working range matches there instead of aliasing into the window, >= 0
    int stride = 1;            ///< [cells] keep every stride-th cell in x and y of the cloud, >= 1
    double disparity_sigma = 0.25;  ///< [px] SGBM's disparity noise at the matched resolution (sets Result::depth_noise), > 0

    /// Throws ParamError naming the first invalid field.
    void validate() const;
  };

  struct Result {
    bool found = false;        ///< a cloud with at least one point was produced
    std::string reason;        ///< why not, when !found
    DisparityMap disparity;    ///< the raw disparity, for diagnostics
    StereoCloud cloud;         ///< [m] left optical frame, each point with its left pixel
    double min_disparity = 0.0;  ///< [px] full-resolution window searched (from max_depth) ...
    double max_disparity = 0.0;  ///< [px] ... to (from min_depth)
    std::size_t window_edge = 0;  ///< matches dropped outside the window (guard band or clamped at the search's edge)
    double depth_noise = 0.0;    ///< [1/m] depth sigma of a point at depth z is depth_noise * z^2 (disparity_sigma / (downscale * fx * B))
    double match_ms = 0.0;     ///< [ms] time spent inside SGBM
    double total_ms = 0.0;     ///< [ms] whole call
  };

  // `Stage(Params = {})` does not compile with GCC while Params has default
  // member initializers (they are parsed only once the outer class is complete).
  StereoMatcher() : StereoMatcher(Params{}) {}
  /// Throws ParamError naming the field when `params` is invalid.
  explicit StereoMatcher(Params params);
  const Params& params() const { return params_; }

  /// Matches a rectified pair (8-bit gray or BGR, same size as the cameras).
  /// Throws InputError naming the image when one is unusable (empty,
  /// not 1 or 3 channels) or its size differs from the other's or its camera's.
  Result match(const Image& left, const Image& right, const StereoCamera& camera) const;

 private:
  Params params_;
};

}  // namespace l2s
