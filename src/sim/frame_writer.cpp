#include "sim/frame_writer.hpp"

#include "sim/parallel.hpp"

#include <cstdio>
#include <exception>
#include <mutex>

namespace l2s::sim::detail {

std::string stem_of(int index) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%06d", index);
  return buffer;
}

void write_frames(const io::DatasetWriter& writer, int count, int threads,
                  const std::function<SimulatedFrame(int)>& frame, const ProgressCallback& progress,
                  FrameFiles files) {
  std::mutex mutex;
  int done = 0;
  std::exception_ptr failure;
  parallel_for(count, threads, [&](int i) {
    try {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (failure) return;
      }
      SimulatedFrame simulated = frame(i);
      io::Frame out;
      out.stem = stem_of(i);
      out.lidar = std::move(simulated.lidar);
      out.left = std::move(simulated.left);
      out.right = std::move(simulated.right);
      out.lidar2 = std::move(simulated.lidar2);
      if (files == FrameFiles::Images)
        writer.write_images(out);
      else
        writer.write(out);
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress) progress(done, count);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!failure) failure = std::current_exception();
    }
  }, 1);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace l2s::sim::detail
