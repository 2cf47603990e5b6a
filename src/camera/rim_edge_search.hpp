#pragma once
// The search half of a rim refinement round (private to the library): which
// rim samples count in each view and where each finds its image edge. Apart
// from the Gauss-Newton fit (board_pose_refiner.cpp): the fit sees only the
// samples it returns, and the check for edges on the board's face
// (face_edge_fraction) runs the search alone.

#include "camera/rim_model.hpp"

#include <l2s/board_pose_refiner.hpp>

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace l2s::detail {

/// The search half of a round: which (view, rim point) samples are used, and
/// where each finds its edge along the rim's normal.
///
/// Visibility and the separation test are decided afresh while the search
/// range shrinks, then frozen (`locked`): samples toggling at those
/// thresholds would otherwise keep the pose jittering by a few 1e-5 and never
/// let the rounds settle. Once frozen, a sample that loses its edge (too
/// weak, window clipped) is dropped for good, so the set only shrinks and
/// cannot toggle either.
class EdgeSearch {
 public:
  EdgeSearch(const BoardPoseRefiner::Params& params, const Rims& rims, const std::vector<View>& views)
      : params_(params), rims_(rims), views_(views), chosen_(views.size() * rims.points.size(), 0) {}

  /// Fills `samples` with the edges found at pose T within +-range [px];
  /// returns how many samples were searched (search line inside the image),
  /// edge or not.
  int search(const Eigen::Isometry3d& T, double range, bool locked, std::vector<Sample>& samples);

 private:
  enum class Outcome { NotSearched, NoEdge, Edge };

  /// The edge of rim point k in `view` at pose T: its projection, the
  /// search window along the normal, the gradient profile and its peak.
  Outcome find_edge(const View& view, const Eigen::Isometry3d& T, std::size_t k, bool locked, RimPixel& at,
                    double& along);

  /// +1 when the board's material (the face beside a front rim, the hole's
  /// wall beside a back rim) lies along +normal from rim point k's
  /// projection, -1 when along -normal, 0 when it cannot be told.
  int board_side_of(const View& view, const Eigen::Isometry3d& T, std::size_t k, const RimPixel& at) const;

  /// Projection and rim normal of rim point k; false when it falls outside
  /// the image (less the margin and the search range) or the rim is seen
  /// edge-on.
  bool project_rim(const View& view, const Eigen::Isometry3d& T, std::size_t k, RimPixel& at) const;

  /// A back-rim silhouette has the hole wall beside it, bounded by the front
  /// rim's edge (face | wall | back rim | background). When that band is
  /// narrow both edges merge into one gradient peak whose position is
  /// biased, differently in each view: such samples are dropped (until the
  /// selection is locked). The face-to-wall edge is often the stronger one (a
  /// wall in shadow is as dark as what is seen through the hole), so the
  /// search must not reach it: the window [lo, hi] stops half a pixel short
  /// of half-way to the front rim on that side, whatever the step (the Sobel
  /// response of that edge is ~1.5 px wide; a window ending on its flank
  /// finds a biased peak).
  bool clip_back_rim_window(const View& view, const Eigen::Isometry3d& T, const Eigen::Vector3d& X,
                            const RimPixel& at, bool locked, int& lo, int& hi) const;

  /// |directional gradient| along the normal at profile indices lo..hi;
  /// false when the window leaves the gradient's crop.
  bool sample_profile(const View& view, const RimPixel& at, int lo, int hi);

  /// The rim's peak in the profile, refined by a parabola, as a distance
  /// along the normal [px]; false when it is too weak or the profile still
  /// rises at a clipped end (the peak is the front rim's, beyond).
  ///
  /// With `board_side` (+1 / -1: the board's material lies towards higher /
  /// lower indices) it is the first peak met coming from the board's side,
  /// not the strongest: the board's face beside a rim is smooth, what is
  /// seen through the hole need not be. Bricks or tiles behind a hole put
  /// edges a pixel or two inside the rim that are stronger than a
  /// low-contrast rim, and the strongest peak then follows them: on a gray
  /// board before bricks a refinement started at the true pose can follow
  /// the joints centimetres and degrees away, where the first peak from the
  /// board's side stays on the rim. A peak is a sample that is the
  /// largest within +-1 px and reaches min_edge_strength and kFirstEdgeShare
  /// of the strongest.
  bool peak(int lo, int hi, int board_side, double& along) const;

  /// The first inner index from `start`, walking by `step` (+-1), that
  /// reaches `threshold` and is the largest within +-1 px; the strongest
  /// sample does, so one is always found.
  int first_peak_from(int start, int step, int lo, int hi, double threshold) const;

  const BoardPoseRefiner::Params& params_;
  const Rims& rims_;
  const std::vector<View>& views_;
  std::vector<char> chosen_;     // [view][rim point]: used in the last round
  std::vector<double> profile_;  // gradient along the current search line
  int steps_ = 0;                // search steps on each side of the rim
  double margin_ = 0.0;          // [px] from the image border, search range included
};

}  // namespace l2s::detail
