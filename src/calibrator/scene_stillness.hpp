#pragma once
// Whether a ring-free lidar's scene stood still over the sweeps of a window
// (private). A non-repetitive scan looks in other directions in every sweep,
// so sweeps are compared by direction: each return falls in a cell of
// azimuth and elevation, and the window keeps the nearest and the farthest
// range seen in each cell. A return of a new sweep beyond the span of its
// cell and the neighbouring ones (by more than the range noise) sees
// something that was not there, or no longer sees it: the board moved into
// or out of that direction. Cells at a depth edge span both surfaces and
// accept either, so the mixed returns at the board's outline and rims do
// not count as motion.

#include <l2s/types.hpp>

#include <cstdint>
#include <unordered_map>

namespace l2s::detail {

class SceneStillness {
 public:
  struct Comparison {
    int compared = 0;  ///< returns of the sweep in cells the window has seen
    int changed = 0;   ///< of those, beyond the cell's span
    bool moved = false;
  };

  /// The sweep against the window taken in so far (nothing moved while it is empty).
  Comparison compare(const LidarCloud& sweep) const;
  /// Takes the sweep's returns into the window.
  void add(const LidarCloud& sweep);
  void clear() { cells_.clear(); }
  bool empty() const { return cells_.empty(); }

 private:
  struct Span {
    float nearest;
    float farthest;
  };
  std::unordered_map<std::int64_t, Span> cells_;
};

}  // namespace l2s::detail
