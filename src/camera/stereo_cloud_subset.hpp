#pragma once
// The points of a stereo cloud picked by index, with their pixels (private).

#include <l2s/geometry.hpp>

#include <cstddef>
#include <vector>

namespace l2s::detail {

inline StereoCloud subset(const StereoCloud& cloud, const std::vector<std::size_t>& indices) {
  StereoCloud out;
  out.points.reserve(indices.size());
  out.pixels.reserve(indices.size());
  for (const std::size_t i : indices) {
    out.points.push_back(cloud.points[i]);
    out.pixels.push_back(cloud.pixels[i]);
  }
  return out;
}

}  // namespace l2s::detail
