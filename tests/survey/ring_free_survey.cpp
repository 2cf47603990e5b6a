// Survey of the ring-free (rosette) lidar path over random scenes: not a test,
// a measurement. For each seed, a scene of the `scenes` experiment's lidar
// draw with the model forced to avia or mid360 and the board at 2-5 m; each
// window of ring_free_frames sweeps goes through the lidar branch (default
// preset). Prints one line per window: found, or the failing stage and
// reason; the worst centre error against ground truth; the apparent radius.
// SURVEY_CALIBRATE=1 also calibrates each scene from all its frames (both
// branches) and prints e_t, e_r and the check's verdict.
//
//   ring_free_survey MODEL FIRST_SEED COUNT [WINDOWS]
//
// Ground truth: the simulator's board pose; the lidar sees the front face,
// labelled as the target numbers its holes.

#include "lidar_survey_scene.hpp"

#include <l2s/calibrator.hpp>
#include <l2s/error.hpp>
#include <l2s/metrics.hpp>
#include <l2s/frame_inspector.hpp>
#include <l2s/io/image_io.hpp>
#include <l2s/sim/simulation.hpp>
#include <l2s/viz/inspection_images.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using l2s::sim::DatasetSimulator;

/// Where a point of the board (in-plane, [m]) sits in the rosette's field of
/// view: 1 = on its outline, > 1 outside it (Avia: an ellipse; Mid-360: an
/// elevation band). Azimuth and elevation in degrees go to `az`, `el`.
double field_of_view_position(const DatasetSimulator& sim, const Eigen::Vector2d& on_board, double* az = nullptr,
                              double* el = nullptr) {
  const Eigen::Isometry3d T_lidar_board =
      sim.config().setting.T_cambody_lidar().inverse() * sim.board_pose().T_cambody_board();
  const Eigen::Vector3d p = T_lidar_board * Eigen::Vector3d(on_board.x(), on_board.y(), 0.0);
  const double azimuth = std::atan2(p.y(), p.x()), elevation = std::atan2(p.z(), p.head<2>().norm());
  if (az) *az = azimuth * 180.0 / M_PI;
  if (el) *el = elevation * 180.0 / M_PI;
  return sim.lidar_model().rosette.field_of_view_position(azimuth, elevation);
}

/// The largest field-of-view position of the four hole centres: above 1, a
/// hole has more than half of its rim outside the field of view.
double worst_hole_centre_in_view(const DatasetSimulator& sim) {
  double worst = 0.0;
  for (const Eigen::Vector2d& h : sim.config().target.hole_centers())
    worst = std::max(worst, field_of_view_position(sim, h));
  return worst;
}

/// The board's corners and hole centres in the field of view, for a failure.
std::string corners_in_view(const DatasetSimulator& sim) {
  const auto& t = sim.config().target;
  std::string out = "corners (az deg, el deg, fov):";
  char buffer[64];
  for (const double sx : {-0.5, 0.5})
    for (const double sy : {-0.5, 0.5}) {
      double az = 0.0, el = 0.0;
      const double fov =
          field_of_view_position(sim, Eigen::Vector2d(sx * t.board_width, sy * t.board_height), &az, &el);
      std::snprintf(buffer, sizeof buffer, " (%.0f %.0f %.2f)", az, el, fov);
      out += buffer;
    }
  out += "; hole centres (fov):";
  for (const Eigen::Vector2d& h : t.hole_centers()) {
    std::snprintf(buffer, sizeof buffer, " %.2f", field_of_view_position(sim, h));
    out += buffer;
  }
  return out;
}

/// The whole calibration of the scene's frames (both branches, default
/// preset): e_t, e_r against ground truth and the check's verdict.
std::string calibrate(const DatasetSimulator& sim) {
  l2s::Calibrator calibrator(sim.cameras(), sim.config().target, l2s::Calibrator::Params::preset("default"));
  for (int i = 0; i < sim.config().frames; ++i) {
    const auto frame = sim.frame(i);
    calibrator.add(frame.lidar, frame.left, frame.right);
  }
  const auto result = calibrator.result();
  if (!result.found) return "calibration: not found: " + result.reason.substr(0, 200);
  const auto error = l2s::pose_error(result.T_lidar_camera, sim.T_lidar_camera());
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "calibration: e_t %.1f mm, e_r %.3f deg, %d lidar / %d camera frames, %s",
                error.translation * 1e3, error.rotation * 180.0 / M_PI, result.lidar_frames, result.camera_frames,
                l2s::verdict_name(result.quality.verdict));
  return buffer;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s MODEL FIRST_SEED COUNT [WINDOWS]\n", argv[0]);
    return 2;
  }
  const std::string model = argv[1];
  const auto first = std::strtoull(argv[2], nullptr, 10);
  const int count = std::atoi(argv[3]);
  const int windows = argc > 4 ? std::atoi(argv[4]) : 2;
  const auto params = l2s::Calibrator::Params::preset("default");
  const int n = params.ring_free_frames;
  int found = 0, total = 0, found_in_view = 0, total_in_view = 0;
  std::vector<double> errors;
  for (std::uint64_t seed = first; seed < first + static_cast<std::uint64_t>(count); ++seed) {
    const auto sim = l2s::survey::make_lidar_scene(model, seed, n * windows, 2.0, 5.0);
    if (!sim) {
      std::printf("seed %llu: no scene\n", static_cast<unsigned long long>(seed));
      continue;
    }
    const auto gt = l2s::survey::lidar_truth(*sim);
    const bool holes_in_view = worst_hole_centre_in_view(*sim) <= 1.0;
    if (std::getenv("SURVEY_VERBOSE")) {
      const auto& c = sim->config();
      const auto& b = sim->board_pose();
      std::printf("  lidar pose %.3f %.3f %.3f %.3f %.3f %.3f; board %.3f %.3f %.3f yaw %.3f pitch %.3f roll %.3f; "
                  "stand %d side walls %.2f near clutter %d pillar %d wall gap %.2f\n",
                  c.setting.tx, c.setting.ty, c.setting.tz, c.setting.yaw, c.setting.pitch, c.setting.roll, b.x, b.y,
                  b.z, b.yaw, b.pitch, b.roll, c.layout.board_stand, c.layout.side_wall_distance,
                  c.layout.near_clutter, c.layout.pillar, c.layout.wall_gap);
    }
    for (int w = 0; w < windows; ++w) {
      std::vector<l2s::LidarCloud> sweeps;
      for (int i = 0; i < n; ++i) sweeps.push_back(sim->sweep(w * n + i));
      const auto t = l2s::inspect_lidar(sweeps, sim->config().target, params);
      ++total;
      total_in_view += holes_in_view;
      if (const char* dir = std::getenv("SURVEY_PICTURES"))
        l2s::io::write_png(std::string(dir) + "/" + model + "_" + std::to_string(seed) + "_" +
                               std::to_string(w) + ".png",
                           l2s::render_lidar_inspection(t, sim->config().target));
      std::printf("%s seed %llu w%d board %.2f m: ", model.c_str(),
                  static_cast<unsigned long long>(seed), w, sim->board_pose().x);
      if (!t.report.found) {
        std::printf("FAIL [%s] %s\n    %s; occupancy holes %d\n", t.report.failed_stage.c_str(),
                    t.report.reason.substr(0, 300).c_str(), corners_in_view(*sim).c_str(),
                    t.occupancy ? t.occupancy->holes : -1);
        if (std::getenv("SURVEY_VERBOSE") && t.plane) {
          const Eigen::Vector3d board_centre = (gt[0] + gt[1] + gt[2] + gt[3]) / 4.0;
          int k = 0;
          for (const auto& c : t.plane->candidates)
            std::printf("    plane #%d %+.3f m from the board centre, %zu support: %s\n", k++,
                        c.plane.signedDistance(board_centre), c.support,
                        c.reason.empty() ? "plausible" : c.reason.c_str());
        }
        continue;
      }
      ++found;
      found_in_view += holes_in_view;
      double worst = 0.0;
      for (int h = 0; h < 4; ++h) {
        const double e = (t.report.centers[h] - gt[h]).norm();
        errors.push_back(e);
        worst = std::max(worst, e);
      }
      std::printf("found, worst centre %.1f mm, r %.1f mm, rms %.1f mm\n", worst * 1e3,
                  t.report.hole_radius * 1e3, t.report.fit_rms * 1e3);
    }
    if (std::getenv("SURVEY_CALIBRATE")) std::printf("%s seed %llu %s\n", model.c_str(),
                                                    static_cast<unsigned long long>(seed), calibrate(*sim).c_str());
    std::fflush(stdout);
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors.empty() ? 0.0 : errors[errors.size() / 2];
  std::printf("%s: found %d of %d windows (%d of %d with every hole centre in the field of view), "
              "median centre error %.1f mm (%zu centres)\n",
              model.c_str(), found, total, found_in_view, total_in_view, median * 1e3, errors.size());
  return 0;
}
