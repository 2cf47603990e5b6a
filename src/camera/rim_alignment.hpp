#pragma once
// The search-and-fit rounds of the board pose refinement (private to the
// library): the edge search (rim_edge_search.hpp) and a robust Gauss-Newton
// fit of the pose alternate until the pose settles. Apart from the driver
// (board_pose_refiner.cpp), which runs them with other edge rules, in gray
// and in colour, and once more with the board's outline.

#include "camera/rim_edge_search.hpp"
#include "camera/rim_model.hpp"

#include <l2s/board_pose_refiner.hpp>

#include <Eigen/Geometry>
#include <limits>
#include <vector>

namespace l2s::detail {

/// What the outline's edges are allowed to differ by from the board's
/// nominal outline (Alignment::free_outline_nuisance): a common disparity
/// offset in the right view, and how far its sides and its top and bottom
/// edges lie outside where target.yaml puts them. Either shows where a
/// board edge against its background is found with another bias than a
/// rim, or a board cut a little larger or smaller than its nominal size, and
/// either would otherwise shift the board's range.
struct OutlineNuisance {
  double disparity_px = 0.0;                             // [px] added to an outline edge's x in the right view
  Eigen::Vector2d dilation = Eigen::Vector2d::Zero();   // [m] sides (x) and top and bottom (y) this much farther out
};

/// The search-and-fit rounds from an initial pose. The search range halves
/// each round down to the final one, which then locks the sample selection
/// (EdgeSearch).
class Alignment {
 public:
  /// `anchors`: known points fitted with the rims in every round (marker corners of a mono camera).
  Alignment(const BoardPoseRefiner::Params& params, const Rims& rims, const std::vector<View>& views,
            const std::vector<Sample>& anchors)
      : params_(params), rims_(rims), views_(views), anchors_(anchors), edges_(params, rims, views) {}

  /// The last round's samples (and the anchors).
  const std::vector<Sample>& samples() const { return samples_; }
  /// The outline's nuisance fitted with the pose (free_outline_nuisance).
  const OutlineNuisance& outline_nuisance() const { return nuisance_; }
  /// Fit the outline's edges with their own disparity offset and dilation
  /// (OutlineNuisance): they then hold the board's tilt, not its range.
  void free_outline_nuisance() { free_nuisance_ = true; }

  /// Fills `result` (reason empty: converged) with the pose the rounds end at.
  void run(const Eigen::Isometry3d& T_camera_board, BoardPoseRefiner::Result& result);

 private:
  /// One search and fit; false when the round fails (result.reason says why).
  bool run_round(int round, Eigen::Isometry3d& T, BoardPoseRefiner::Result& result);

  const BoardPoseRefiner::Params& params_;
  const Rims& rims_;
  const std::vector<View>& views_;
  const std::vector<Sample>& anchors_;
  EdgeSearch edges_;
  std::vector<Sample> samples_;  // the last round's edges (and the anchors)
  bool settled_ = false;
  bool lock_selection_ = false;  // the next round keeps this round's sample selection
  double previous_step_px_ = std::numeric_limits<double>::infinity();
  int searched_at_selection_ = 0;  // samples searched in the round that chose the selection
  OutlineNuisance nuisance_;
  bool free_nuisance_ = false;
};

/// How well samples fit a pose: the rms normal distance and the share of the
/// samples that count (fit_of).
struct SampleFit {
  double rms_px = std::numeric_limits<double>::quiet_NaN();  // NaN: no samples
  double inlier_share = 0.0;
  int inliers = 0;
};

/// The fit at pose T of the rim samples (outline false) or of the outline's
/// inliers (true, with their nuisance; outline samples farther than 1 px
/// from their edge do not count).
SampleFit fit_of(const std::vector<Sample>& samples, const std::vector<View>& views, const Eigen::Isometry3d& T,
                 const OutlineNuisance& nuisance, bool outline);

}  // namespace l2s::detail
