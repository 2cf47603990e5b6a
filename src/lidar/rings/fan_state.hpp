#pragma once
// The vocabulary the steps of the fan fit share (laser_fan.hpp): a line with
// the returns it was fitted to, the prior on a laser's offset, the ridge fit
// under that prior, and what the lines say about one return.

#include "lidar/rings/laser_fan.hpp"

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace l2s::io::fan {

/// A line with the sums it was fitted to.
struct Fitted {
  Line line;
  LineSums sums;
  std::vector<std::size_t> members;  ///< the returns in `sums` (while the fan grows)
};

std::vector<Line> plain(const std::vector<Fitted>& lines);
void sort_by_intercept(std::vector<Fitted>& lines);
/// Residual sum of squares of `sums` about `line`, v units squared.
double rss(const LineSums& sums, const Line& line);
/// Median residual scale of the lines, in radians: the sensor's noise level.
double typical_noise(const std::vector<Fitted>& lines, const FanParams& params);

/// What a laser's offset h may be before its own returns pin it down: one or
/// two hypotheses (mean, sigma) [m].
struct Hypotheses {
  std::array<std::pair<double, double>, 2> options;
  int count = 1;
};

/// The offset h expected for a laser at intercept t. Offsets change smoothly
/// across a fan except between blocks of lasers, so the nearest established
/// lines below and above t say most: their interpolation, as sure as they
/// agree. Where they disagree by more than kJump, t sits between two blocks
/// and the laser takes the one or the other offset (two hypotheses; its
/// returns decide). Without established neighbours on both sides (a laser
/// beyond those seen so far may belong to another block) the profile speaks,
/// in the same way.
class OffsetPrior {
 public:
  OffsetPrior(const std::vector<Fitted>& lines, const OffsetProfile& profile,
              const FanParams& params);
  /// The laser's own line is not its own neighbour: lines closer than half
  /// the minimum gap are skipped.
  Hypotheses at(double t) const;

 private:
  std::vector<double> t_, h_;  // established lines, ascending t
  const OffsetProfile& profile_;
  const FanParams& params_;
};

/// Ridge fit under each hypothesis of the prior; the one that explains the
/// returns and its prior best wins (ties: the first, the lower block).
Line fit(const LineSums& sums, const OffsetPrior& prior, const OffsetProfile& profile,
         const FanParams& params);

/// What a return's lines say about it: exactly one line explains it within
/// `gate` sigmas of its prediction (or one far better than any other: accept),
/// none does (outlier: perhaps a laser not seen yet), or several do
/// (uncertain: a line whose offset is still open may reach it; decide later).
enum class Verdict { Accept, Outlier, Uncertain };
struct Decision {
  Verdict verdict = Verdict::Outlier;
  int line = -1;
};
Decision classify(const std::vector<Fitted>& lines, const Match& nearest, const Point& p,
                  const FanParams& params);

}  // namespace l2s::io::fan
