#pragma once
// How precisely the markers' corners are placed in this image: measured on
// the markers' own outer edges, so that it follows the image's noise, blur
// and the markers' size in pixels rather than a fixed pixel count.

#include <l2s/mono_board_detector.hpp>

#include <opencv2/core.hpp>

#include <vector>

namespace l2s::detail {

/// [px] the 1-sigma error of one corner coordinate of `markers` in `gray`
/// (8-bit, one channel). Along each marker side the step from the white
/// quiet zone to the black border is located to sub-pixel at evenly spaced
/// places; a straight line fitted to them leaves a scatter that the image's
/// noise and blur set, and a corner, pinned by the lines of two sides,
/// errs by that scatter times sqrt(4 / samples per side). `bits`: the
/// dictionary's bits per side (the border cell, 1 / (bits + 2) of a side,
/// bounds the search). 0 without a side long enough to measure.
double marker_corner_sigma(const cv::Mat& gray, const std::vector<MonoBoardDetector::Marker>& markers, int bits);

}  // namespace l2s::detail
