#pragma once
// The ArUco markers of target.yaml printed on the board's front face: which
// marker cell (black or white) a point of the front face lies in. The bit
// patterns come from OpenCV's dictionary, so what the simulator prints is
// what cv::aruco detects.

#include <l2s/target.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace l2s::sim::detail {

class MarkerTexture {
 public:
  /// No markers when the target has none. Throws ParamError for an unknown dictionary.
  explicit MarkerTexture(const Target& target);

  /// At board-frame point `xy` [m] of the front face: -1 off every marker,
  /// 0 on a white cell or the white margin one cell wide around the marker,
  /// 1 on a black cell (the border included).
  int cell(const Eigen::Vector2d& xy) const;

  bool empty() const { return markers_.empty(); }

 private:
  struct Marker {
    Eigen::Vector2d top_left;  ///< [m] board frame
    double cell_size = 0.0;    ///< [m]
    int cells = 0;             ///< per side: the dictionary's bits plus the black border
    std::vector<std::uint8_t> black;  ///< row-major from the top-left cell, as seen from the front
  };
  std::vector<Marker> markers_;
};

}  // namespace l2s::sim::detail
