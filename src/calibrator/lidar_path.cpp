// Which path a lidar sweep takes (l2s::lidar_path): forced by
// Params::lidar_scan, or decided by the sweep's returns. A ring field is
// used only when its values are the scan lines (io::check_ring_field);
// otherwise the elevations of the returns say whether there are lines at
// all (io::classify_scan): a spinning lidar's lasers, or the even spread of
// a solid-state scan.
#include "calibrator/branches.hpp"

#include <l2s/frame_inspector.hpp>
#include <l2s/io/ring_recovery.hpp>

namespace l2s {
namespace detail {

SweepPath choose_path(const LidarCloud& sweep, const Calibrator::Params& params) {
  SweepPath path;
  path.use_field = sweep.has_ring();
  std::string ignored;
  if (sweep.has_ring()) {
    const io::RingFieldCheck field = io::check_ring_field(sweep);
    path.use_field = field.usable;
    if (!field.usable) ignored = "; ring field ignored: " + field.reason;
  }
  switch (params.lidar_scan) {
    case Calibrator::LidarScan::Rings:
      path.reason = "rings, as lidar_scan forces" + ignored;
      return path;
    case Calibrator::LidarScan::RingFree:
      path.ring_free = true;
      path.use_field = false;
      path.reason = "ring-free, as lidar_scan forces";
      return path;
    case Calibrator::LidarScan::Auto:
      break;
  }
  if (path.use_field) {
    path.reason = "rings: the sweep's ring field gives its scan lines";
    return path;
  }
  LidarCloud points;
  points.points = sweep.points;
  const io::ScanClassification scan = io::classify_scan(points);
  path.ring_free = scan.structure == io::ScanStructure::RingFree;
  path.reason = std::string(path.ring_free ? "ring-free: " : "rings from the returns: ") + scan.reason + ignored;
  return path;
}

}  // namespace detail

LidarPath lidar_path(const LidarCloud& sweep, const Calibrator::Params& params) {
  const detail::SweepPath path = detail::choose_path(sweep, params);
  return {path.ring_free, path.reason};
}

}  // namespace l2s
