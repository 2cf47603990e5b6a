#pragma once
// Turning recovered rings into a RingRecoveryReport: statistics, the scan
// structure (rings or ring-free) and the doubts a user should hear about.

#include <l2s/io/ring_recovery.hpp>

#include "lidar/rings/laser_line.hpp"

#include <vector>

namespace l2s::io {

/// The facts of the lines found: report.lasers (ring ring_of_line[k] for line
/// k, rings with returns only, ascending elevation), points, residual_rms and
/// fill, from the returns `points` and their lines `labels` (-1: none).
void describe_lines(const std::vector<fan::Line>& lines, const std::vector<int>& ring_of_line,
                    const std::vector<fan::Point>& points, const std::vector<int>& labels,
                    RingRecoveryReport& report);

/// Completes a report whose source, rings, lasers, points, residual_rms and
/// fill are set: points per ring, structure and its reason, doubts.
void finish_report(RingRecoveryReport& report);

}  // namespace l2s::io
