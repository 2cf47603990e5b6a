#pragma once
// The calibration check's observations of a frame from what the branches
// found (frame_inspector.hpp), so a check sees exactly the board the
// calibration used, and a way to make them from raw frames for checking any
// transform (an old calibration, say).

#include <l2s/calibrator.hpp>
#include <l2s/export.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/scene_observer.hpp>

namespace l2s {

/// The lidar side: discontinuities of `sweep`, and the board returns of the
/// chosen plane when the branch found the board (`inspection.report.found`,
/// or `found` when the trace came from a branch run without a report).
L2S_EXPORT LidarObservation observe_lidar(const LidarCloud& sweep, const LidarInspection& inspection, bool found,
                               const SceneObserver& observer);

/// The camera side: the board pose (refined when the refiner converged)
/// when the branch found the board, the coarse stereo depth of the whole
/// frame, and, when `with_edges`, the edge distances of `left`.
L2S_EXPORT CameraObservation observe_camera(const Image& left, const CameraInspection& inspection, bool found,
                                 const StereoCamera& cameras, const SceneObserver& observer, bool with_edges = true);

/// Runs both branches on one frame, exactly as Calibrator::add does, and
/// observes it. Throws ParamError as Calibrator::add does.
L2S_EXPORT CheckFrame observe_frame(const LidarCloud& sweep, const Image& left, const Image& right, const StereoCamera& cameras,
                         const Target& target, const Calibrator::Params& params, const SceneObserver& observer,
                         const std::string& id = "");

}  // namespace l2s
