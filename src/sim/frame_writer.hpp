#pragma once
// Writing simulated frames to a dataset folder (private to the simulator),
// shared by the single- and multi-pose simulators.

#include <l2s/io/dataset.hpp>
#include <l2s/sim/simulation.hpp>

#include <functional>
#include <string>

namespace l2s::sim::detail {

/// The dataset stem of frame `index`: "000042".
std::string stem_of(int index);

/// Writes frames 0..count-1, each made by `frame(i)`, through `writer` on
/// `threads` workers (0 = all cores). Frames are independent (each draws its
/// own noise), so workers take them in any order: PNG encoding dominates and
/// would leave a core idle otherwise. Progress is reported as a count of
/// frames done, from under a lock; the first exception stops the others and
/// is rethrown. `files`: whole frames, or their images alone (a `lidar:
/// accumulated` dataset, whose cloud is written apart).
enum class FrameFiles { All, Images };
void write_frames(const io::DatasetWriter& writer, int count, int threads,
                  const std::function<SimulatedFrame(int)>& frame, const ProgressCallback& progress,
                  FrameFiles files = FrameFiles::All);

}  // namespace l2s::sim::detail
