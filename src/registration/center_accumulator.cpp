// Accumulation of hole centres over a window of N frames (paper Sec. III-C,
// last paragraph): Euclidean clustering with tolerance delta_cluster, cluster
// sizes bounded relative to N, one point per hole.
// Centres arrive labelled, so each hole is clustered on its own: a frame with
// a wrong centre only adds a far point to that hole's set, which falls out of
// the largest cluster. With few points (one per frame) a plain O(n^2)
// single-linkage clustering is faster than building a k-d tree.

#include <l2s/center_accumulator.hpp>

#include <l2s/error.hpp>

#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace l2s {
namespace {

/// Indices of the largest single-linkage cluster (ties: the earliest point's).
std::vector<int> largest_cluster(const std::vector<Eigen::Vector3d>& points, double tolerance) {
  const int n = static_cast<int>(points.size());
  std::vector<int> label(n, -1);
  std::vector<int> best;
  for (int seed = 0; seed < n; ++seed) {
    if (label[seed] >= 0) continue;
    std::vector<int> members{seed};
    label[seed] = seed;
    for (std::size_t k = 0; k < members.size(); ++k)
      for (int j = 0; j < n; ++j)
        if (label[j] < 0 && (points[j] - points[members[k]]).norm() <= tolerance) {
          label[j] = seed;
          members.push_back(j);
        }
    if (members.size() > best.size()) best = std::move(members);
  }
  return best;
}

/// Weiszfeld's iteration, started at the mean; robust to a minority of outliers.
Eigen::Vector3d geometric_median(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& p : pts) m += p;
  m /= static_cast<double>(pts.size());
  for (int it = 0; it < 100; ++it) {
    Eigen::Vector3d num = Eigen::Vector3d::Zero();
    double den = 0.0;
    for (const auto& p : pts) {
      const double w = 1.0 / std::max((p - m).norm(), 1e-9);
      num += w * p;
      den += w;
    }
    const Eigen::Vector3d next = num / den;
    const double step = (next - m).norm();
    m = next;
    if (step < 1e-9) break;
  }
  return m;
}

/// [m] Mean distance between the holes finite in both, or +inf with fewer than two.
double label_distance(const HoleCenters& a, const HoleCenters& b) {
  double sum = 0.0;
  int n = 0;
  for (int h = 0; h < 4; ++h)
    if (a[h].allFinite() && b[h].allFinite()) sum += (a[h] - b[h]).norm(), ++n;
  return n >= 2 ? sum / n : std::numeric_limits<double>::infinity();
}

/// The quarter turn of `frame` nearest to `reference`, and that distance.
std::pair<HoleSymmetry, double> best_turn(const HoleCenters& frame, const HoleCenters& reference,
                                          const std::vector<HoleSymmetry>& turns) {
  std::pair<HoleSymmetry, double> best{turns.front(), std::numeric_limits<double>::infinity()};
  for (const HoleSymmetry& turn : turns) {
    const double d = label_distance(relabel(frame, turn.permutation), reference);
    if (d < best.second) best = {turn, d};
  }
  return best;
}

/// The frame most other frames agree with (within `tolerance` under some
/// turn); ties go to the earliest. At most 64 evenly spread candidates.
std::size_t reference_frame(const std::vector<HoleCenters>& frames, double tolerance,
                            const std::vector<HoleSymmetry>& turns) {
  const std::size_t step = std::max<std::size_t>(1, frames.size() / 64);
  std::size_t best = 0;
  int best_support = -1;
  for (std::size_t i = 0; i < frames.size(); i += step) {
    int support = 0;
    for (const HoleCenters& other : frames) support += best_turn(other, frames[i], turns).second <= tolerance;
    if (support > best_support) best = i, best_support = support;
  }
  return best;
}

}  // namespace

void CenterAccumulator::Params::validate() const {
  if (!(cluster_tolerance > 0.0)) throw ParamError("cluster_tolerance", "must be > 0");
  if (!(min_cluster_fraction > 0.0 && min_cluster_fraction <= 1.0))
    throw ParamError("min_cluster_fraction", "must be in (0, 1]");
  if (!(max_cluster_fraction >= min_cluster_fraction))
    throw ParamError("max_cluster_fraction", "must be >= min_cluster_fraction");
  if (min_frames < 1) throw ParamError("min_frames", "must be >= 1");
}

CenterAccumulator::CenterAccumulator(Params params) : params_(params) { params_.validate(); }

void CenterAccumulator::add(const HoleCenters& centers) {
  HoleCenters kept = centers;
  for (auto& c : kept)
    if (!c.allFinite()) c.setConstant(std::numeric_limits<double>::quiet_NaN());
  frames_.push_back(kept);
}

void CenterAccumulator::reset() { frames_.clear(); }

std::vector<HoleSymmetry> CenterAccumulator::frame_turns() const {
  const std::vector<HoleSymmetry> turns = quarter_turns();
  std::vector<HoleSymmetry> applied(frames_.size(), turns.front());
  if (!params_.align_labels || frames_.empty()) return applied;
  const HoleCenters& reference =
      frames_[reference_frame(frames_, 2.0 * params_.cluster_tolerance, turns)];
  for (std::size_t i = 0; i < frames_.size(); ++i) applied[i] = best_turn(frames_[i], reference, turns).first;
  return applied;
}

CenterAccumulator::Result CenterAccumulator::estimate() const {
  Result result;
  const int frames = result.frames = static_cast<int>(frames_.size());
  if (frames < params_.min_frames) {
    std::ostringstream reason;
    reason << "only " << frames << " frames added, need " << params_.min_frames;
    result.reason = reason.str();
    return result;
  }
  // Each hole's centres, every frame turned to the common labels.
  std::array<std::vector<Eigen::Vector3d>, 4> centers;
  std::array<std::vector<int>, 4> frame_of;  // the frame each of centers[h] came from
  const std::vector<HoleSymmetry> turns = frame_turns();
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    result.relabelled_frames += turns[i].degrees != 0;
    const HoleCenters turned = relabel(frames_[i], turns[i].permutation);
    for (int h = 0; h < 4; ++h)
      if (turned[h].allFinite()) {
        centers[h].push_back(turned[h]);
        frame_of[h].push_back(static_cast<int>(i));
      }
  }
  result.clustered.assign(frames_.size(), true);
  const int min_size = std::max(1, static_cast<int>(std::ceil(params_.min_cluster_fraction * frames - 1e-9)));
  const int max_size = static_cast<int>(std::floor(params_.max_cluster_fraction * frames + 1e-9));
  std::ostringstream reasons;
  for (int h = 0; h < 4; ++h) {
    const char* name = hole_name(static_cast<Hole>(h));
    const std::vector<int> members = largest_cluster(centers[h], params_.cluster_tolerance);
    const int size = static_cast<int>(members.size());
    result.counts[h] = size;
    std::vector<bool> member(centers[h].size(), false);
    for (int k : members) member[k] = true;
    for (std::size_t k = 0; k < member.size(); ++k)
      if (!member[k]) result.clustered[frame_of[h][k]] = false;
    if (size < min_size || size > max_size) {
      if (reasons.tellp() > 0) reasons << "; ";
      reasons << "hole " << name << ": largest cluster has " << size << " of " << frames
              << " centres (allowed " << min_size << ".." << max_size << ")";
      continue;
    }
    std::vector<Eigen::Vector3d> cluster;
    for (int k : members) cluster.push_back(centers[h][k]);
    Eigen::Vector3d estimate = Eigen::Vector3d::Zero();
    if (params_.estimator == Estimator::Mean) {
      for (const auto& p : cluster) estimate += p;
      estimate /= static_cast<double>(size);
    } else {
      estimate = geometric_median(cluster);
    }
    double sum_sq = 0.0;
    for (const auto& p : cluster) sum_sq += (p - estimate).squaredNorm();
    result.centers[h] = estimate;
    result.spread[h] = std::sqrt(sum_sq / size);
  }
  result.reason = reasons.str();
  result.found = result.reason.empty();
  return result;
}

}  // namespace l2s
