// A planted example for scripts/check_comment_history.py: three comments
// that name where a rule came from instead of why it holds, and code and
// comments that only look alike.
#include <cstdint>

namespace planted {

// Raised after random scene 1468088629 lost its board.          (finding 1)
constexpr double kThreshold = 0.3;

/* Measured 2026-12-03 on the quick suite.                          (finding 2)
   Seeds 1-20 of the survey: fine, too short to be a scene's seed. */
constexpr std::int64_t kStart = 1700000000LL * 1000000000LL;  // the epoch in ns: a number, not a seed

/// Holds for every face: the seed of the
/// scene draw is 2094806729 here.                                  (finding 3: the sentence goes on)
/// A 12-digit serial number of a lidar, 123456789012, is data.
constexpr double kOther = 0.1;

}  // namespace planted
