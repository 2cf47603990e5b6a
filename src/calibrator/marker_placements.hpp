#pragma once
// Where a mono board's markers lie, over the frames of a calibration: a
// marker glued off its place in target.yaml is off by the same amount in
// every frame, while one frame's measure scatters by a millimetre or two.

#include <l2s/calibrator.hpp>

#include <string>
#include <vector>

namespace l2s::detail {

struct MarkerPlacements {
  std::vector<MonoBoardDetector::MarkerPlacement> markers;  ///< per marker id, the medians over its frames
  std::vector<std::string> notes;                           ///< one per marker clearly off its place
};

/// The frames' marker placements (BranchReport::marker_placements of the
/// camera side) summed up per marker: its median offset, turn and corner
/// rms over the frames that placed it, and a note when the median lies
/// more than 1.5 mm and three standard errors off the nominal place.
MarkerPlacements summarise_marker_placements(const std::vector<FrameReport>& frames);

}  // namespace l2s::detail
