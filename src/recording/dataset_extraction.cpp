// A recording to a dataset folder: its frames (RecordedFrames) written one
// by one under a temporary name beside the folder's place, renamed when
// complete.
#include <l2s/recording/dataset_extraction.hpp>

#include <l2s/error.hpp>
#include <l2s/io/dataset.hpp>
#include <l2s/recording/recorded_frames.hpp>

#include <filesystem>
#include <optional>
#include <unistd.h>

namespace l2s {
namespace {

namespace fs = std::filesystem;

/// A folder beside `folder`, removed unless released.
class TemporaryFolder {
 public:
  explicit TemporaryFolder(const fs::path& folder)
      : path_(folder.string() + ".partial-" + std::to_string(::getpid())) {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ~TemporaryFolder() {
    std::error_code ignored;
    if (!released_) fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }
  void release() { released_ = true; }

 private:
  fs::path path_;
  bool released_ = false;
};

}  // namespace

ExtractionReport extract_dataset(const Ros1Bag& bag, const std::string& folder, const ExtractionOptions& options) {
  const fs::path target_folder(folder);
  std::error_code error;
  if (fs::exists(target_folder, error) && !(fs::is_directory(target_folder) && fs::is_empty(target_folder)))
    throw FileError(folder, "exists and is not an empty folder: the dataset is written into a new one");
  const RecordedFrames frames(bag, options.topics, options.pairing);
  ExtractionReport report;
  report.topics = frames.topics();
  report.raw_images = frames.raw_images();
  report.sweeps = frames.sweeps();
  report.tolerance_s = frames.tolerance_s();
  report.dropped = frames.dropped();
  const RecordingTopics& t = report.topics;

  TemporaryFolder partial(target_folder);
  std::optional<io::DatasetWriter> writer;
  if (frames.lidar_pair()) {
    writer.emplace(io::DatasetWriter::lidar_pair(partial.path().string(), options.target));
  } else {
    try {
      writer.emplace(partial.path().string(), frames.cameras(), options.target,
                     frames.mono() ? io::CameraLayout::Mono : io::CameraLayout::Stereo);
    } catch (const FileError& e) {
      throw FileError(bag.path(), "camera_info of " + t.left_info + (t.right.empty() ? "" : " and " + t.right_info) +
                                      ": " + e.what());
    }
  }
  frames.read([&](RecordedFrame&& recorded) {
    try {
      writer->write(recorded.frame);
    } catch (const ParamError& e) {
      throw FileError(bag.path(), "frame " + recorded.frame.stem + " (" + (frames.lidar_pair() ? t.lidar2 : t.left) +
                                      "): " + e.what());
    }
    ++report.frames;
    return true;
  });

  if (fs::exists(target_folder, error)) fs::remove(target_folder, error);  // an empty folder, checked above
  fs::rename(partial.path(), target_folder, error);
  if (error) throw FileError(folder, "cannot be made from " + partial.path().string() + ": " + error.message());
  partial.release();
  return report;
}

}  // namespace l2s
