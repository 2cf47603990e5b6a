// Fuzzes Calibrator::add with arbitrary lidar sweeps (the lidar branch, ring
// recovery, accumulation and registration; the camera side is a fixed report
// of the true hole centres, so no image work slows the loop).
//
// Input: one flags byte, then 18-byte point records (x y z intensity as
// float32, ring as uint16, little-endian) -- the layout of
// fuzz/make_seeds.cpp's seeds. Flags: bit 0 keep intensity, bit 1 keep ring,
// bit 2 drop the last intensity value, bit 3 add one ring value (sweeps whose
// attribute arrays disagree with the points), bit 4 use the paper preset.
// Contract checked: add() and result() throw nothing (bad sweeps are reported
// frames), and what they report is finite.
#include <l2s/calibrator.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace {

constexpr std::size_t kRecord = 18;

void expect(bool condition) {
  if (!condition) std::abort();
}

l2s::StereoCamera cameras() {
  l2s::StereoCamera rig;
  rig.left = l2s::CameraInfo::ideal("left", 1280, 960, 1000.0, 640.0, 480.0);
  rig.right = l2s::CameraInfo::ideal("right", 1280, 960, 1000.0, 640.0, 480.0, 0.12);
  return rig;
}

// The camera branch's answer for a board 3 m ahead: the target's true centres.
l2s::BranchReport camera_report(const l2s::Target& target) {
  l2s::BranchReport report;
  report.found = true;
  const auto holes = target.hole_centers();
  for (int i = 0; i < 4; ++i) report.centers[i] = Eigen::Vector3d(holes[i].x(), -holes[i].y(), 3.0);
  return report;
}

l2s::LidarCloud decode(const std::uint8_t* data, std::size_t size, std::uint8_t flags) {
  l2s::LidarCloud cloud;
  for (std::size_t at = 0; at + kRecord <= size; at += kRecord) {
    float xyz[3], intensity;
    std::uint16_t ring;
    std::memcpy(xyz, data + at, 12);
    std::memcpy(&intensity, data + at + 12, 4);
    std::memcpy(&ring, data + at + 16, 2);
    cloud.points.emplace_back(xyz[0], xyz[1], xyz[2]);
    if (flags & 1) cloud.intensity.push_back(intensity);
    if (flags & 2) cloud.ring.push_back(ring);
  }
  if ((flags & 4) && !cloud.intensity.empty()) cloud.intensity.pop_back();
  if (flags & 8) cloud.ring.push_back(0);
  return cloud;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  static l2s::Calibrator default_calibrator(cameras(), l2s::Target{});
  static l2s::Calibrator paper_calibrator(cameras(), l2s::Target{}, l2s::Calibrator::Params::preset("paper"));
  l2s::Calibrator& calibrator = (flags & 16) ? paper_calibrator : default_calibrator;
  calibrator.reset();

  const l2s::LidarCloud sweep = decode(data + 1, size - 1, flags);
  const l2s::FrameReport report = calibrator.add(sweep, camera_report(calibrator.target()), "fuzz");
  if (report.lidar.found)
    for (const auto& center : report.lidar.centers) expect(center.allFinite());
  else
    expect(!report.lidar.reason.empty());

  const l2s::Calibrator::Result result = calibrator.result();
  expect(result.frames_added == 1);
  if (result.found) expect(result.T_lidar_camera.matrix().allFinite());
  else expect(!result.reason.empty());
  return 0;
}
