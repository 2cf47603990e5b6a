#include "sim/marker_texture.hpp"

#include "detail/aruco_dictionary.hpp"

#include <cmath>

namespace l2s::sim::detail {

MarkerTexture::MarkerTexture(const Target& target, const std::vector<double>& turns) {
  if (!target.markers) return;
  const MarkerLayout& layout = *target.markers;
  const auto dictionary = l2s::detail::aruco_dictionary(layout.dictionary);
  const int cells = dictionary->markerSize + 2;  // one cell of black border on each side
  for (std::size_t i = 0; i < layout.ids.size(); ++i) {
    cv::Mat bits;
    // One pixel per cell: image row 0 is the marker's top row as seen from the front.
    cv::aruco::drawMarker(dictionary, layout.ids[i], cells, bits, 1);
    Marker marker;
    marker.cells = cells;
    marker.cell_size = layout.size / cells;
    marker.centre = layout.centres[i];
    if (i < turns.size()) marker.cos_turn = std::cos(turns[i]), marker.sin_turn = std::sin(turns[i]);
    marker.top_left = layout.centres[i] + Eigen::Vector2d(-0.5 * layout.size, 0.5 * layout.size);
    marker.black.resize(static_cast<std::size_t>(cells) * cells);
    for (int r = 0; r < cells; ++r)
      for (int c = 0; c < cells; ++c)
        marker.black[static_cast<std::size_t>(r) * cells + c] = bits.at<std::uint8_t>(r, c) < 128 ? 1 : 0;
    markers_.push_back(std::move(marker));
  }
}

int MarkerTexture::cell(const Eigen::Vector2d& xy) const {
  // A printed marker comes with a white margin (its sheet, or the print's
  // quiet zone): one cell wide here. Its black border is found by its
  // contrast against that margin, whatever the face around it looks like.
  constexpr double kQuietCells = 1.0;
  for (const Marker& m : markers_) {
    // Into the marker's own axes: the point turned back about its centre.
    const Eigen::Vector2d d = xy - m.centre;
    const Eigen::Vector2d p = m.sin_turn == 0.0 ? xy
                                                : Eigen::Vector2d(m.centre + Eigen::Vector2d(m.cos_turn * d.x() + m.sin_turn * d.y(),
                                                                                             -m.sin_turn * d.x() + m.cos_turn * d.y()));
    const double u = (p.x() - m.top_left.x()) / m.cell_size;  // columns to the right
    const double v = (m.top_left.y() - p.y()) / m.cell_size;  // rows downwards
    if (u < -kQuietCells || v < -kQuietCells || u >= m.cells + kQuietCells || v >= m.cells + kQuietCells) continue;
    if (u < 0.0 || v < 0.0 || u >= m.cells || v >= m.cells) return 0;
    const int c = static_cast<int>(std::floor(u)), r = static_cast<int>(std::floor(v));
    return m.black[static_cast<std::size_t>(r) * m.cells + c];
  }
  return -1;
}

}  // namespace l2s::sim::detail
