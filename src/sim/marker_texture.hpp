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
  /// No markers when the target has none. `turns`: [rad] each marker's turn
  /// in the board plane about its centre (empty: none). Throws ParamError
  /// for an unknown dictionary.
  explicit MarkerTexture(const Target& target, const std::vector<double>& turns = {});

  /// At board-frame point `xy` [m] of the front face: -1 off every marker,
  /// 0 on a white cell or the white margin one cell wide around the marker,
  /// 1 on a black cell (the border included).
  int cell(const Eigen::Vector2d& xy) const;

  bool empty() const { return markers_.empty(); }

 private:
  struct Marker {
    Eigen::Vector2d centre;    ///< [m] board frame
    double cos_turn = 1.0, sin_turn = 0.0;  ///< its turn in the board plane
    Eigen::Vector2d top_left;  ///< [m] board frame, before the turn
    double cell_size = 0.0;    ///< [m]
    int cells = 0;             ///< per side: the dictionary's bits plus the black border
    std::vector<std::uint8_t> black;  ///< row-major from the top-left cell, as seen from the front
  };
  std::vector<Marker> markers_;
};

}  // namespace l2s::sim::detail
