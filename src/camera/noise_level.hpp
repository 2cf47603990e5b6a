#pragma once
// The noise level of an 8-bit image (private): thresholds that must stay
// above noise (edges, photo evidence) scale with it, so a noisy camera does
// not turn its noise into edges.

#include <opencv2/core.hpp>

namespace l2s::detail {

/// [gray levels] sigma of the image noise from the median absolute
/// difference of horizontal neighbours on a grid of about 20k pixels: texture
/// makes few large differences, noise many small ones. A colour image (8-bit,
/// any number of channels) gives its noisiest channel's.
double image_noise_sigma(const cv::Mat& image);

}  // namespace l2s::detail
