#include "camera/noise_level.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace l2s::detail {

double image_noise_sigma(const cv::Mat& image) {
  if (image.channels() > 1) {
    std::vector<cv::Mat> channels;
    cv::split(image, channels);
    double sigma = 0.0;
    for (const cv::Mat& channel : channels) sigma = std::max(sigma, image_noise_sigma(channel));
    return sigma;
  }
  const cv::Mat& gray = image;
  std::vector<int> differences;
  const int step = std::max(1, static_cast<int>(std::sqrt(gray.rows * gray.cols / 20000.0)));
  for (int y = 0; y < gray.rows; y += step) {
    const std::uint8_t* row = gray.ptr<std::uint8_t>(y);
    for (int x = 0; x + 1 < gray.cols; x += step) differences.push_back(std::abs(row[x + 1] - row[x]));
  }
  if (differences.empty()) return 0.0;
  std::nth_element(differences.begin(), differences.begin() + differences.size() / 2, differences.end());
  // A difference of two pixels has sqrt(2) sigma; the median of |N(0, s)| is 0.674 s.
  return 1.4826 * differences[differences.size() / 2] / std::sqrt(2.0);
}

}  // namespace l2s::detail
