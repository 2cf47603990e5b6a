#pragma once
// A one-line progress bar with ETA on stderr; silent when stderr is not a terminal
// except for a final line, so logs stay readable.

#include <chrono>
#include <cstddef>
#include <string>

namespace l2s::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total);
  /// Reports that `done` of `total` items are finished.
  void update(std::size_t done);
  /// Ends the line (prints the elapsed time).
  void finish();

 private:
  std::string label_;
  std::size_t total_;
  bool interactive_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace l2s::cli
