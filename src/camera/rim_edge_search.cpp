// The edge search of the board pose refinement (see rim_edge_search.hpp and,
// for the whole method, board_pose_refiner.cpp): along each visible rim
// sample's projected normal, the sub-pixel peak of the directional gradient,
// with the back rims' windows kept off the face-to-wall edge.

#include "camera/rim_edge_search.hpp"

#include <algorithm>
#include <cmath>

namespace l2s::detail {
namespace {

/// The first edge from the board's side counts as the rim only when it is at
/// least this share of the strongest edge in the search window: weaker bumps
/// nearer the face are its texture or noise. On three random scenes before
/// tiles and bricks (1653306487, 1060328696, 2031326890; 3 frames each) 0.3
/// refined 9 of 9 frames to 0.3-4.5 mm; 0 refined 7 (two kept circles 6-7
/// mm off), 0.5 refined 6.
constexpr double kFirstEdgeShare = 0.3;

}  // namespace

int EdgeSearch::search(const Eigen::Isometry3d& T, double range, bool locked, std::vector<Sample>& samples) {
  steps_ = static_cast<int>(std::floor(range / params_.search_step_px));
  profile_.assign(2 * steps_ + 1, 0.0);
  margin_ = params_.image_margin_px + range;
  samples.clear();
  int searched = 0;
  const Eigen::Isometry3d T_board_camera = T.inverse();
  for (std::size_t v = 0; v < views_.size(); ++v) {
    const View& view = views_[v];
    const Eigen::Vector3d eye = T_board_camera * view.center;  // camera centre, board frame
    if (!(eye.z() > 0.0)) continue;  // looking at the back face
    for (std::size_t k = 0; k < rims_.points.size(); ++k) {
      const Eigen::Vector3d& X = rims_.points[k];
      char& use = chosen_[v * rims_.points.size() + k];
      if (locked && !use) continue;
      use = 0;
      if (!locked && hidden_from(rims_, eye, k)) continue;
      RimPixel at;
      double along = 0.0;  // [px] edge position on the search line
      const Outcome outcome = find_edge(view, T, k, locked, at, along);
      if (outcome != Outcome::NotSearched) ++searched;
      if (outcome != Outcome::Edge) continue;
      use = 1;
      Sample sample{static_cast<int>(v), X, at.normal, at.u + along * at.normal};
      sample.outline = rims_.hole[k] == Rims::kOutline;
      if (sample.outline) sample.outward << -rims_.material[k], 0.0;
      samples.push_back(sample);
    }
  }
  return searched;
}

EdgeSearch::Outcome EdgeSearch::find_edge(const View& view, const Eigen::Isometry3d& T, std::size_t k,
                                          bool locked, RimPixel& at, double& along) {
  const Eigen::Vector3d& X = rims_.points[k];
  if (!project_rim(view, T, k, at)) return Outcome::NotSearched;
  int lo = 0, hi = 2 * steps_;  // profile indices (offset -steps..steps)
  if (X.z() != 0.0 && !clip_back_rim_window(view, T, X, at, locked, lo, hi)) return Outcome::NotSearched;
  if (!sample_profile(view, at, lo, hi)) return Outcome::NotSearched;
  const int board_side = params_.first_edge_from_board ? board_side_of(view, T, k, at) : 0;
  return peak(lo, hi, board_side, along) ? Outcome::Edge : Outcome::NoEdge;
}

int EdgeSearch::board_side_of(const View& view, const Eigen::Isometry3d& T, std::size_t k,
                              const RimPixel& at) const {
  const Eigen::Vector3d& X = rims_.points[k];
  const Eigen::Vector2d& into = rims_.material[k];
  // The face lies beside a front rim (outside a hole, inside the outline);
  // the wall (or side face) of a back rim towards the front rim.
  const Eigen::Vector3d toward =
      X.z() == 0.0 ? Eigen::Vector3d(X.x() + 1e-3 * into.x(), X.y() + 1e-3 * into.y(), 0.0)
                   : Eigen::Vector3d(X.x(), X.y(), 0.0);
  Eigen::Vector2d u;
  if (!view.project(T * toward, u, nullptr)) return 0;
  const double side = at.normal.dot(u - at.u);
  return side > 0.0 ? 1 : side < 0.0 ? -1 : 0;
}

bool EdgeSearch::project_rim(const View& view, const Eigen::Isometry3d& T, std::size_t k, RimPixel& at) const {
  Eigen::Matrix<double, 2, 3> J;
  const Eigen::Vector3d p = T * rims_.points[k];
  if (!view.project(p, at.u, &J)) return false;
  const double m = margin_;
  const Eigen::Vector2d& u = at.u;
  if (u.x() < m || u.y() < m || u.x() > view.width - 1 - m || u.y() > view.height - 1 - m) return false;
  const Eigen::Vector2d tangent = J * (T.linear() * rims_.tangents[k]);
  if (tangent.norm() < 1e-9) return false;
  at.normal = Eigen::Vector2d(-tangent.y() / tangent.norm(), tangent.x() / tangent.norm());
  return true;
}

bool EdgeSearch::clip_back_rim_window(const View& view, const Eigen::Isometry3d& T, const Eigen::Vector3d& X,
                                      const RimPixel& at, bool locked, int& lo, int& hi) const {
  Eigen::Vector2d u_front;
  if (!view.project(T * Eigen::Vector3d(X.x(), X.y(), 0.0), u_front, nullptr)) return false;
  const double separation = at.normal.dot(u_front - at.u);  // [px] signed, along the normal
  if (!locked && std::abs(separation) < params_.min_rim_separation_px) return false;
  const int reach = std::max(
      1, static_cast<int>(std::floor((0.5 * std::abs(separation) - 0.5) / params_.search_step_px)));
  if (separation > 0.0)
    hi = std::min(hi, steps_ + reach);
  else
    lo = std::max(lo, steps_ - reach);
  return true;
}

bool EdgeSearch::sample_profile(const View& view, const RimPixel& at, int lo, int hi) {
  const Eigen::Vector2d& u = at.u;
  const Eigen::Vector2d& normal = at.normal;
  bool inside = true;
  for (int i = lo; i <= hi && inside; ++i) {
    inside = view.grad.along(u.x() + (i - steps_) * params_.search_step_px * normal.x(),
                             u.y() + (i - steps_) * params_.search_step_px * normal.y(), normal, profile_[i]);
  }
  return inside;
}

bool EdgeSearch::peak(int lo, int hi, int board_side, double& along) const {
  const std::vector<double>& profile = profile_;
  int best = lo + 1;
  for (int i = lo + 1; i < hi; ++i)
    if (profile[i] > profile[best]) best = i;
  if (profile[best] < params_.min_edge_strength) return false;
  if ((lo > 0 && profile[lo] > profile[best]) || (hi < 2 * steps_ && profile[hi] > profile[best])) return false;
  if (board_side != 0)
    best = first_peak_from(board_side > 0 ? hi - 1 : lo + 1, -board_side, lo, hi,
                           std::max(params_.min_edge_strength, kFirstEdgeShare * profile[best]));
  const double a = profile[best - 1], b = profile[best], c = profile[best + 1];
  const double denom = a - 2.0 * b + c;
  const double offset = denom < 0.0 ? 0.5 * (a - c) / denom : 0.0;
  along = (best - steps_ + offset) * params_.search_step_px;
  return true;
}

int EdgeSearch::first_peak_from(int start, int step, int lo, int hi, double threshold) const {
  const int reach = std::max(1, static_cast<int>(std::lround(1.0 / params_.search_step_px)));
  for (int i = start; i > lo && i < hi; i += step) {
    if (profile_[i] < threshold) continue;
    bool largest = true;
    for (int j = std::max(lo, i - reach); j <= std::min(hi, i + reach) && largest; ++j)
      largest = profile_[j] <= profile_[i];
    if (largest) return i;
  }
  return start;
}

}  // namespace l2s::detail
