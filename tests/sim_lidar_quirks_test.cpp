// The quirks of real spinning lidars in the simulator: per-laser calibration
// tables (beams that start off the sensor origin, irregular angles) and beam
// divergence (mixed returns at depth edges, holes that look smaller).

#include <l2s/io/ring_recovery.hpp>
#include <l2s/sim/lidar_quirks.hpp>
#include <l2s/sim/lidar_simulator.hpp>
#include <l2s/sim/ray_caster.hpp>
#include <l2s/sim/settings.hpp>

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>

namespace l2s::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

// ---------------------------------------------------------------- laser tables

TEST(LaserTable, DrawnTablesLookLikeRealOnes) {
  const LidarModel vlp = LidarModel::vlp16();
  const auto table = draw_laser_table(vlp, 5);
  ASSERT_EQ(table.size(), 16u);
  // One unit: every beam starts on the same side of the axis, 0.4-5.6 cm off.
  const double sign = table[0].vertical_offset > 0 ? 1.0 : -1.0;
  for (const auto& c : table) {
    EXPECT_GT(sign * c.vertical_offset, 0.003);
    EXPECT_LT(std::abs(c.vertical_offset), 0.056);
    EXPECT_LT(std::abs(c.elevation), 0.8 * kDeg);
    EXPECT_LT(std::abs(c.azimuth), 0.3 * kDeg);
  }
  // Deterministic per seed; another seed is another unit.
  EXPECT_EQ(draw_laser_table(vlp, 5)[3].vertical_offset, table[3].vertical_offset);
  EXPECT_NE(draw_laser_table(vlp, 6)[3].vertical_offset, table[3].vertical_offset);

  const auto hdl = draw_laser_table(LidarModel::hdl64(), 5);
  for (int k = 0; k < 64; ++k) {
    if (k < 32) EXPECT_NEAR(hdl[k].vertical_offset, -0.06, 0.0101) << k;
    else EXPECT_LE(std::abs(hdl[k].vertical_offset), 0.0101) << k;
    EXPECT_NEAR(std::abs(hdl[k].horizontal_offset), 0.026, 0.008) << k;
    EXPECT_LE(std::abs(hdl[k].azimuth), 0.1) << k;
  }
  // Corrected elevations keep the ring order of every model.
  for (const char* name : {"vlp16", "hdl32", "hdl64"}) {
    const LidarModel m = with_quirks(LidarModel::by_name(name), LidarQuirks::all(9));
    ASSERT_EQ(m.corrections.size(), m.elevations.size());
    for (int k = 1; k < m.rings(); ++k)
      EXPECT_GT(m.elevations[k] + m.corrections[k].elevation, m.elevations[k - 1] + m.corrections[k - 1].elevation)
          << name << " ring " << k;
  }
  EXPECT_THROW(draw_laser_table(LidarModel::avia(), 1), ParamError);
  EXPECT_TRUE(with_quirks(LidarModel::avia(), LidarQuirks::all()).corrections.empty());
}

/// A corridor like the recording: side walls 1.3 m away, low boxes
/// and a stand, the board 3.3 m ahead.
Scene corridor_scene() {
  SceneLayout layout;
  layout.side_wall_distance = 1.3;
  layout.near_clutter = 3;
  layout.board_stand = true;
  return make_scene(Target{}, BoardPose{3.3, 0.0, -0.1, 0.2, 0.0, 0.0}, layout);
}

TEST(LaserTable, PointsAreExactHitsFromEachLasersOwnOrigin) {
  const Scene scene = corridor_scene();
  const RayCaster caster(scene);
  LidarSimulator::Params params;
  params.noise_factor = 0.0;
  const LidarModel model = with_quirks(LidarModel::hdl64(), LidarQuirks::all(2));
  const Eigen::Isometry3d T = paper_setting(7).T_cambody_lidar();
  std::vector<SurfaceId> surfaces;
  const LidarCloud cloud = LidarSimulator(model, params).sweep(caster, T, 0, &surfaces);
  const Eigen::Isometry3d T_board_lidar = scene.T_cambody_board.inverse() * T;
  int board = 0, ground = 0, side = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p_body = T * cloud.points[i];
    if (surfaces[i] == SurfaceId::Ground) {
      ASSERT_NEAR(p_body.z(), scene.ground_z, 1e-9);
      ++ground;
    } else if (surfaces[i] == SurfaceId::SideWall) {
      ASSERT_NEAR(std::abs(p_body.y()), 1.3, 1e-9);
      ++side;
    } else if (surfaces[i] == SurfaceId::Board) {
      const Eigen::Vector3d q = T_board_lidar * cloud.points[i];
      ASSERT_GE(q.z(), -scene.target.board_thickness - 1e-9);
      ASSERT_LE(q.z(), 1e-9);
      ++board;
    }
  }
  EXPECT_GT(board, 200);
  EXPECT_GT(ground, 1000);
  EXPECT_GT(side, 1000);
}

struct SpreadCase {
  std::string model;
  int beams;
};

void PrintTo(const SpreadCase& c, std::ostream* os) { *os << c.model; }

class OffsetBeams : public ::testing::TestWithParam<SpreadCase> {};

TEST_P(OffsetBeams, SpreadInElevationAtCloseRange) {
  // Seen from the sensor origin, a laser that starts h above it appears at
  // elevation + atan(h / d): its points at 1-2 m and at 5+ m no longer share
  // one elevation, which is what splits it into several "rings" when rings
  // are recovered from elevations alone.
  const Scene scene = corridor_scene();
  const RayCaster caster(scene);
  LidarSimulator::Params params;
  params.noise_factor = 0.0;
  const LidarModel model = with_quirks(LidarModel::by_name(GetParam().model), LidarQuirks::all(1));
  const Eigen::Isometry3d T = paper_setting(7).T_cambody_lidar();
  LidarCloud cloud = LidarSimulator(model, params).sweep(caster, T, 0);
  std::map<int, std::pair<double, double>> range_of;  // ring -> (min, max) apparent elevation
  std::map<int, std::pair<double, double>> distance_of;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    const double d = std::hypot(p.x(), p.y());
    const double el = std::atan2(p.z(), d);
    auto [it, fresh] = range_of.try_emplace(cloud.ring[i], el, el);
    it->second.first = std::min(it->second.first, el);
    it->second.second = std::max(it->second.second, el);
    auto [jt, fresh2] = distance_of.try_emplace(cloud.ring[i], d, d);
    jt->second.first = std::min(jt->second.first, d);
    jt->second.second = std::max(jt->second.second, d);
  }
  int spread_rings = 0;
  for (const auto& [ring, span] : range_of) {
    const LidarModel::LaserCorrection& c = model.corrections[ring];
    const auto [near, far] = distance_of[ring];
    // What the laser's vertical offset alone predicts over its distances.
    const double predicted = std::abs(std::atan2(c.vertical_offset, near) - std::atan2(c.vertical_offset, far));
    EXPECT_GT(span.second - span.first, 0.8 * predicted) << "ring " << ring;
    if (span.second - span.first > 0.3 * kDeg) ++spread_rings;
  }
  EXPECT_GE(spread_rings, GetParam().beams / 2);

  // Ring recovery from elevations (a colleague is fixing it): record what it
  // makes of this sweep. Measured: VLP-16 19 rings for 16 beams (splits),
  // HDL-64E 46 for 64 (the lower block's 6 cm offset merges neighbours).
  cloud.ring.clear();
  const int recovered = io::recover_rings(cloud);
  RecordProperty("recovered_rings", recovered);
}

INSTANTIATE_TEST_SUITE_P(Models, OffsetBeams,
                         ::testing::Values(SpreadCase{"vlp16", 16}, SpreadCase{"hdl64", 64}),
                         [](const auto& info) { return info.param.model; });

TEST(LaserTable, IdealModelKeepsOneElevationPerRing) {
  const Scene scene = corridor_scene();
  const RayCaster caster(scene);
  const LidarModel model = LidarModel::vlp16();
  const LidarCloud cloud = LidarSimulator(model).sweep(caster, paper_setting(7).T_cambody_lidar(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    ASSERT_NEAR(std::atan2(p.z(), std::hypot(p.x(), p.y())), model.elevations[cloud.ring[i]], 1e-9);
  }
}

// -------------------------------------------------------------- beam footprint

/// A board squarely 3 m ahead of the lidar (slightly yawed), wall `gap` behind.
Scene facing_board(double distance, double gap = 3.0) {
  SceneLayout layout;
  layout.wall_gap = gap;
  return make_scene(Target{}, BoardPose{distance, 0.0, 0.0, 0.05, 0.0, 0.0}, layout);
}

/// The board-frame point where a ray from the lidar origin along `dir` meets
/// the board's front plane, and the range to it.
struct PlaneCrossing {
  Eigen::Vector2d q;
  double t;
};
PlaneCrossing cross_board(const Scene& scene, const Eigen::Vector3d& dir_body) {
  const Eigen::Isometry3d T_board = scene.T_cambody_board.inverse();
  const Eigen::Vector3d o = T_board.translation();
  const Eigen::Vector3d d = T_board.linear() * dir_body;
  const double t = -o.z() / d.z();
  return {(o + t * d).head<2>(), t};
}

/// Distance in the board plane to the nearest outline: border or hole rim.
double outline_distance(const Target& target, const Eigen::Vector2d& q) {
  double best = std::min(std::abs(std::abs(q.x()) - 0.5 * target.board_width),
                         std::abs(std::abs(q.y()) - 0.5 * target.board_height));
  for (const Eigen::Vector2d& c : target.hole_centers())
    best = std::min(best, std::abs((q - c).norm() - target.hole_radius));
  return best;
}

LidarSimulator::Params footprint_params(bool on, ReturnMode mode = ReturnMode::Strongest) {
  LidarSimulator::Params params;
  params.noise_factor = 0.0;
  params.beam_footprint = on;
  params.return_mode = mode;
  return params;
}

TEST(BeamFootprint, MixedReturnsAppearAtDepthEdgesBetweenTheSurfaces) {
  // The wall 0.7 m behind the board: closer than the Velodyne's 1 m echo
  // separation, so a footprint on both merges into one return between them.
  const Scene scene = facing_board(3.0, 0.7);
  const RayCaster caster(scene);
  const double wall_x = 3.0 + 0.7;
  for (bool on : {false, true}) {
    const LidarCloud cloud = LidarSimulator(LidarModel::vlp16(), footprint_params(on))
                                 .sweep(caster, Eigen::Isometry3d::Identity(), 1);
    int mixed = 0;
    for (const Eigen::Vector3d& p : cloud.points) {
      const Eigen::Vector3d dir = p.normalized();
      const PlaneCrossing c = cross_board(scene, dir);
      const double t_wall = wall_x / dir.x();
      const double range = p.norm();
      const bool toward_board = c.t > 0.0 && std::abs(c.q.x()) < 0.8 && std::abs(c.q.y()) < 0.6;
      if (!toward_board || !(range > c.t + 0.03 && range < t_wall - 0.03)) continue;
      ++mixed;
      // Only where the beam's footprint straddles an outline of the board.
      EXPECT_LT(outline_distance(scene.target, c.q), 0.02) << "range " << range;
    }
    if (on) EXPECT_GT(mixed, 10);
    else EXPECT_EQ(mixed, 0);
  }
}

/// The hole radius as the returns show it: the mean distance from the true
/// hole centre of the midpoints between neighbouring board and through-hole
/// firings of a ring, on the left and right rims (not where a ring grazes).
double apparent_hole_radius(const LidarModel& model, const LidarSimulator::Params& params) {
  const Scene scene = facing_board(3.0);
  const RayCaster caster(scene);
  const LidarCloud cloud = LidarSimulator(model, params).sweep(caster, Eigen::Isometry3d::Identity(), 0);
  const auto holes = scene.target.hole_centers();
  const double r = scene.target.hole_radius;
  std::map<int, std::vector<std::pair<Eigen::Vector2d, bool>>> rings;  // (plane point, on board)
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const PlaneCrossing c = cross_board(scene, cloud.points[i].normalized());
    bool near_hole = false;
    for (const Eigen::Vector2d& h : holes) near_hole = near_hole || (c.q - h).norm() < 1.6 * r;
    if (near_hole) rings[cloud.ring[i]].push_back({c.q, std::abs(cloud.points[i].norm() - c.t) < 0.1});
  }
  double sum = 0.0;
  int count = 0;
  for (const auto& [ring, points] : rings)
    for (std::size_t k = 1; k < points.size(); ++k) {
      if (points[k].second == points[k - 1].second) continue;
      const Eigen::Vector2d m = 0.5 * (points[k].first + points[k - 1].first);
      for (const Eigen::Vector2d& h : holes)
        if ((m - h).norm() < 1.3 * r && std::abs(m.y() - h.y()) < 0.7 * r) sum += (m - h).norm(), ++count;
    }
  return count > 8 ? sum / count : -1.0;
}

TEST(BeamFootprint, HolesLookSmallerWithDivergence) {
  // A VLP-16 firing every 0.02 deg resolves the rims to 1 mm at 3 m.
  LidarModel fine = LidarModel::vlp16();
  fine.azimuth_step = 2.0 * M_PI / 18000.0;
  LidarModel wide = fine;
  wide.optics.divergence_horizontal *= 3.0;
  wide.optics.divergence_vertical *= 3.0;
  const double ideal = apparent_hole_radius(fine, footprint_params(false));
  const double vlp = apparent_hole_radius(fine, footprint_params(true));
  const double three = apparent_hole_radius(wide, footprint_params(true));
  RecordProperty("radius_ideal_mm", std::to_string(ideal * 1000));
  RecordProperty("radius_vlp16_mm", std::to_string(vlp * 1000));
  RecordProperty("radius_3x_divergence_mm", std::to_string(three * 1000));
  // Measured at 3 m: 118.7 mm ideal (rim midpoints of a 2 cm thick board),
  // 113.8 mm with the VLP-16's footprint, 109.0 mm with three times its divergence.
  EXPECT_NEAR(ideal, 0.12, 0.003);
  EXPECT_LT(vlp, ideal - 0.003);
  EXPECT_LT(three, vlp - 0.003);
  // The return mode matters: the last echo is the wall behind the hole as soon
  // as it carries enough of the beam, so holes look larger; the first echo
  // is the board, so they look smallest.
  const double last = apparent_hole_radius(fine, footprint_params(true, ReturnMode::Last));
  const double first = apparent_hole_radius(fine, footprint_params(true, ReturnMode::First));
  EXPECT_GT(last, ideal + 0.002);
  EXPECT_LE(first, vlp + 0.0005);
}

TEST(BeamFootprint, StrayBoardReturnsInsideHolesNextToTheRim) {
  const Scene scene = facing_board(3.0);
  const RayCaster caster(scene);
  const auto holes = scene.target.hole_centers();
  for (bool on : {false, true}) {
    int stray = 0;
    for (std::uint64_t frame = 0; frame < 4; ++frame) {
      const LidarCloud cloud = LidarSimulator(LidarModel::vlp16(), footprint_params(on))
                                   .sweep(caster, Eigen::Isometry3d::Identity(), frame);
      for (const Eigen::Vector3d& p : cloud.points) {
        const PlaneCrossing c = cross_board(scene, p.normalized());
        bool inside = false;
        for (const Eigen::Vector2d& h : holes) inside = inside || (c.q - h).norm() < 0.12 - 0.006;
        if (inside && std::abs(p.norm() - c.t) < 0.05) ++stray;  // a board-range point inside a hole
      }
    }
    if (on) EXPECT_GT(stray, 0);
    else EXPECT_EQ(stray, 0);
  }
}

TEST(BeamFootprint, SameSweepAnyThreadCount) {
  const Scene scene = facing_board(2.5, 0.7);
  const RayCaster caster(scene);
  LidarSimulator::Params one = footprint_params(true), two = footprint_params(true);
  one.noise_factor = two.noise_factor = 1.0;
  one.threads = 1;
  two.threads = 2;
  const LidarModel model = with_quirks(LidarModel::vlp16(), LidarQuirks::all(4));
  const LidarCloud a = LidarSimulator(model, one).sweep(caster, paper_setting(3).T_cambody_lidar(), 5);
  const LidarCloud b = LidarSimulator(model, two).sweep(caster, paper_setting(3).T_cambody_lidar(), 5);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]);
}

TEST(BeamFootprint, RejectsBadParams) {
  LidarSimulator::Params params = footprint_params(true);
  params.footprint_rays = 3;
  EXPECT_THROW(LidarSimulator(LidarModel::vlp16(), params), ParamError);
  params = footprint_params(true);
  params.min_return_share = 1.5;
  EXPECT_THROW(LidarSimulator(LidarModel::vlp16(), params), ParamError);
}

}  // namespace
}  // namespace l2s::sim
