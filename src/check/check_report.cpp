// The readable report of the calibration check.

#include <l2s/calibration_check.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace l2s {
namespace {

constexpr double kDeg = M_PI / 180.0;

template <class... Numbers>
std::string line(const char* pattern, Numbers... numbers) {
  char text[320];
  std::snprintf(text, sizeof text, pattern, static_cast<double>(numbers)...);
  return text;
}

void describe_scores(std::ostringstream& out, const CalibrationCheck::Scores& s, const char* indent) {
  out << indent
      << line("edges      %.3f of %.0f lidar edges on image edges; off the board %.3f of %.0f\n", s.edge_score,
              s.edge_points, s.scene_edge_score, s.scene_edge_points);
  if (std::isfinite(s.depth_agreement))
    out << indent
        << line("depth      %.3f of %.0f lidar returns agree with stereo; bias %+.1f %%, ", s.depth_agreement,
                s.depth_points, 100.0 * s.depth_bias)
        << (std::isfinite(s.depth_tilt) ? line("tilt off the board %.2f +- %.2f deg", s.depth_tilt / kDeg,
                                               s.depth_tilt_sigma / kDeg)
                                        : std::string("tilt off the board not measured"))
        << (std::isfinite(s.depth_tilt_texture) ? line(" (its plane %.0f %% on texture)", 100.0 * s.depth_tilt_texture)
                                                : std::string())
        << "\n";
  if (std::isfinite(s.plane_offset))
    out << indent
        << line("board      plane offset %+.1f mm (spread %.1f mm), tilt %.2f deg (scatter over frames %.2f deg)\n",
                s.plane_offset * 1e3, s.plane_spread * 1e3, s.plane_tilt / kDeg, s.pose_scatter / kDeg);
  if (std::isfinite(s.stereo_offset))
    out << indent
        << line("stereo     board plane %+.1f mm (%+.2f px) from the rims' pose; %.0f %% of its points textured "
                "along the rows only\n",
                s.stereo_offset * 1e3, s.stereo_offset_px, 100.0 * s.stereo_row_texture);
  if (std::isfinite(s.outside_fraction))
    out << indent
        << line("outline    lidar board edges %.1f px from the outline and rims; %.1f %% of returns off the board\n",
                s.outline_px, 100.0 * s.outside_fraction);
  if (std::isfinite(s.center_offset))
    out << indent << line("centres    lidar hole centres %.1f mm from the camera's holes (board plane)\n",
                          s.center_offset * 1e3);
  out << indent << line("support    %.3f\n", s.support);
}

}  // namespace

const char* verdict_name(CalibrationCheck::Verdict verdict) {
  switch (verdict) {
    case CalibrationCheck::Verdict::Ok: return "ok";
    case CalibrationCheck::Verdict::Suspect: return "suspect";
    case CalibrationCheck::Verdict::Failed: return "failed";
  }
  return "?";
}

std::string describe(const CalibrationCheck::Report& report) {
  std::ostringstream out;
  out << "verdict    " << verdict_name(report.verdict) << "\n";
  for (const auto& reason : report.reasons) out << "  - " << reason << "\n";
  out << line("frames     %.0f given: %.0f with the board on both sides, %.0f with image edges, %.0f with stereo depth\n",
              report.frames, report.board_frames, report.edge_frames, report.depth_frames);
  describe_scores(out, report.scores, "");
  if (report.scores.edge_points > 0) {
    out << line("alignment  best near this transform %.1f px away, edge score %.3f there (%.0f %% better)\n",
                report.misalignment_px, report.optimum_edge_score, 100.0 * report.misalignment_gain);
    if (report.optimum_board)
      out << line("           the board there: hole centres %.1f mm off, outline %.1f px, %.0f %% of returns outside\n",
                  report.optimum_board->center_offset * 1e3, report.optimum_board->outline_px,
                  100.0 * report.optimum_board->outside_fraction);
    out << line("peaks      edges at median depth %.2f m; offset / half width at half height:\n", report.median_depth);
    for (const auto& peak : report.peaks) {
      const double unit = peak.rotation ? 1.0 / kDeg : 100.0;
      out << "  " << peak.name << line(" %+8.3f / %7.3f ", peak.offset * unit, peak.width * unit)
          << (peak.rotation ? "deg" : "cm ") << line("  (prominence %.2f)\n", peak.prominence);
    }
  }
  out << line("up         the lidar's +z %.0f deg from the image's up\n", report.up_angle / kDeg);
  for (const auto& alternative : report.alternatives) {
    out << "alternative '" << alternative.name << "'" << line(" (lidar's +z %.0f deg from the image's up)\n", alternative.up_angle / kDeg);
    describe_scores(out, alternative.scores, "  ");
  }
  out << line("time       %.0f ms\n", report.milliseconds);
  return out.str();
}

}  // namespace l2s
