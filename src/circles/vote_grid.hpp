#pragma once
// A 2D vote accumulator in the board plane (private): the circle and the
// hole-pattern Hough transforms both splat votes on it and read its peaks.

#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

namespace l2s::detail {

class VoteGrid {
 public:
  /// Covers `box` widened by `margin` [m] on every side, in cells of `cell`
  /// [m]. The cell grows when the box is wide (a candidate plane may be a
  /// whole wall): the grid never holds more than `max_cells`, whatever the input.
  VoteGrid(const Eigen::AlignedBox2d& box, double margin, double cell, double max_cells = 4.0e6);

  double cell() const { return cell_; }
  void clear();
  /// Bilinear splat, so a peak's position keeps sub-cell precision.
  void vote(const Eigen::Vector2d& c, float weight = 1.0f);
  /// 3x3 box sum: a rim's votes spread over neighbouring cells with noise.
  void smooth();
  /// The `max_peaks` strongest local maxima (strict over the 8 neighbours),
  /// strongest first; equal ones in scan order. A smoothed grid of scattered
  /// votes has thousands of small maxima; sorting them all cost the pattern
  /// search (100 angles) more than its votes.
  std::vector<std::pair<float, Eigen::Vector2d>> peaks(std::size_t max_peaks = SIZE_MAX) const;

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  float& at(int x, int y) { return votes_[index(x, y)]; }
  float at(int x, int y) const { return votes_[index(x, y)]; }

  double cell_ = 0.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  int width_ = 0, height_ = 0;
  std::vector<float> votes_;
  std::vector<float> scratch_;
};

}  // namespace l2s::detail
