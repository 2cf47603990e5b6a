// Grouping of a frame stream into static board poses (issue 9). Two passes:
// 1. Stretches: consecutive frames that agree with the stretch's first view
//    (per stream, within the tolerance) form a stretch; a frame that does not
//    starts the next one. Comparing with the first view, not the previous
//    frame, stops a slow drift from chaining a moving board into one pose.
// 2. Merging: one bad detection (a wrong plane, a hole missed) breaks a
//    stretch of a static board in two; when short stretches separate two
//    that agree, the two are one pose and the frames between are outliers.
// Stretches long enough are poses; the frames of the others were taken while
// the board moved. A recording that is one short stretch is still one pose.
// 3. Consensus: within a pose, each stream keeps the views that agree with
//    most of its others; a sensor that found a wrong board in some frames
//    (while another sensor saw the board stay) loses those views only.

#include <l2s/pose_grouper.hpp>

#include <l2s/error.hpp>
#include <l2s/hole_symmetry.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace l2s {
namespace {

struct Stretch {
  std::vector<int> frames;
  std::vector<int> outliers;
  FrameCenters anchor;  ///< per stream: the first view of the board in the stretch
};

bool finite_enough(const std::optional<HoleCenters>& c) {
  if (!c) return false;
  int finite = 0;
  for (const auto& p : *c) finite += p.allFinite();
  return finite >= 2;
}

/// Does `frame` show the board where `anchor` does? Yes when a stream seen in
/// both agrees. A stream that disagrees while another agrees made a bad
/// detection (a wrong plane, a mislabelled set): a move of the board moves
/// it for every sensor. Sorting out which views of a pose to use is left to
/// consensus_outliers(), which sees all of them.
bool agrees(const FrameCenters& anchor, const FrameCenters& frame, double tolerance) {
  for (std::size_t s = 0; s < frame.size(); ++s)
    if (finite_enough(anchor[s]) && finite_enough(frame[s]) &&
        pattern_distance(*anchor[s], *frame[s]) <= tolerance)
      return true;
  return false;
}

/// Per stream, the frames of a pose whose view disagrees with the stream's
/// consensus: the view that most others agree with (the earliest on a tie)
/// and those agreeing with it are kept. The consensus, not the pose's first
/// view, decides, so a bad detection that happens to come first does not
/// turn all the good ones into outliers.
std::vector<std::vector<int>> consensus_outliers(const std::vector<FrameCenters>& frames,
                                                 const std::vector<int>& pose_frames, double tolerance) {
  const std::size_t streams = frames.empty() ? 0 : frames.front().size();
  std::vector<std::vector<int>> out(streams);
  for (std::size_t s = 0; s < streams; ++s) {
    std::vector<int> seen;
    for (int f : pose_frames)
      if (finite_enough(frames[f][s])) seen.push_back(f);
    const auto near = [&](int a, int b) { return pattern_distance(*frames[a][s], *frames[b][s]) <= tolerance; };
    int best = -1, best_count = -1;
    for (int a : seen) {
      const auto count = std::count_if(seen.begin(), seen.end(), [&](int b) { return near(a, b); });
      if (count > best_count) best = a, best_count = static_cast<int>(count);
    }
    for (int f : seen)
      if (!near(best, f)) out[s].push_back(f);
  }
  return out;
}

std::vector<Stretch> stretches(const std::vector<FrameCenters>& frames, double tolerance,
                               std::vector<int>* empty) {
  std::vector<Stretch> out;
  for (int i = 0; i < static_cast<int>(frames.size()); ++i) {
    const FrameCenters& frame = frames[i];
    if (std::none_of(frame.begin(), frame.end(), finite_enough)) {
      empty->push_back(i);
      continue;
    }
    if (out.empty() || !agrees(out.back().anchor, frame, tolerance))
      out.push_back(Stretch{{}, {}, FrameCenters(frame.size())});
    Stretch& current = out.back();
    current.frames.push_back(i);
    for (std::size_t s = 0; s < frame.size(); ++s)
      if (!finite_enough(current.anchor[s]) && finite_enough(frame[s])) current.anchor[s] = frame[s];
  }
  return out;
}

/// Joins stretches that agree when only short ones (fewer than
/// `min_frames`) lie between them; the frames between become outliers.
std::vector<Stretch> merged(std::vector<Stretch> in, double tolerance, int min_frames) {
  std::vector<Stretch> out;
  std::size_t i = 0;
  while (i < in.size()) {
    Stretch current = std::move(in[i]);
    std::size_t next = i + 1;
    for (;;) {
      std::size_t k = next;
      while (k < in.size() && static_cast<int>(in[k].frames.size()) < min_frames &&
             !agrees(current.anchor, in[k].anchor, tolerance))
        ++k;
      if (k >= in.size() || !agrees(current.anchor, in[k].anchor, tolerance)) break;
      for (std::size_t j = next; j < k; ++j)
        current.outliers.insert(current.outliers.end(), in[j].frames.begin(), in[j].frames.end());
      current.frames.insert(current.frames.end(), in[k].frames.begin(), in[k].frames.end());
      next = k + 1;
    }
    out.push_back(std::move(current));
    i = next;
  }
  return out;
}

std::string frame_range(const std::vector<int>& frames) {
  std::ostringstream s;
  s << (frames.size() == 1 ? "frame " : "frames ") << frames.front();
  if (frames.size() > 1) s << "-" << frames.back();
  return s.str();
}

/// A stretch long enough to be a pose, with its notes: frames that disagree
/// with it, and per stream the views of the board elsewhere.
PoseGrouper::Pose make_pose(const Stretch& s, const std::vector<FrameCenters>& frames, double tolerance,
                            const std::vector<std::string>& stream_names, std::size_t index,
                            std::vector<std::string>& notes) {
  using Pose = PoseGrouper::Pose;
  Pose p;
  p.frames = s.frames;
  p.outliers = s.outliers;
  std::sort(p.outliers.begin(), p.outliers.end());
  p.first = std::min(p.frames.front(), p.outliers.empty() ? p.frames.front() : p.outliers.front());
  p.last = std::max(p.frames.back(), p.outliers.empty() ? p.frames.back() : p.outliers.back());
  if (!p.outliers.empty()) {
    std::ostringstream note;
    note << "pose " << index << ": " << p.outliers.size() << " frame(s) disagree with the pose and are not used (first "
         << p.outliers.front() << ")";
    notes.push_back(note.str());
  }
  p.stream_outliers = consensus_outliers(frames, p.frames, tolerance);
  for (std::size_t k = 0; k < p.stream_outliers.size(); ++k) {
    const std::vector<int>& bad = p.stream_outliers[k];
    if (bad.empty()) continue;
    std::ostringstream note;
    note << "pose " << index << ": the " << (k < stream_names.size() ? stream_names[k] : "stream " + std::to_string(k))
         << " saw the board elsewhere in " << bad.size() << " frame(s) (first " << bad.front()
         << "; a wrong detection, not used)";
    notes.push_back(note.str());
  }
  return p;
}

}  // namespace

double pattern_distance(const HoleCenters& a, const HoleCenters& b) {
  double best = std::numeric_limits<double>::infinity();
  for (const HoleSymmetry& turn : quarter_turns()) {
    const HoleCenters turned = relabel(b, turn.permutation);
    double sum = 0.0;
    int n = 0;
    for (int h = 0; h < 4; ++h)
      if (a[h].allFinite() && turned[h].allFinite()) sum += (a[h] - turned[h]).norm(), ++n;
    if (n >= 2) best = std::min(best, sum / n);
  }
  return best;
}

void PoseGrouper::Params::validate() const {
  if (!(tolerance > 0.0)) throw ParamError("tolerance", "must be > 0");
  if (min_frames < 1) throw ParamError("min_frames", "must be >= 1");
}

PoseGrouper::PoseGrouper(Params params) : params_(params) { params_.validate(); }

PoseGrouper::Result PoseGrouper::group(const std::vector<FrameCenters>& frames,
                                       const std::vector<std::string>& stream_names) const {
  for (const FrameCenters& frame : frames)
    if (frame.size() != frames.front().size())
      throw InputError("frames", "every frame needs the same number of observation streams");
  Result result;
  const std::vector<Stretch> all =
      merged(stretches(frames, params_.tolerance, &result.empty), params_.tolerance, params_.min_frames);
  // A recording too short for any full pose still has its longest stretch.
  std::size_t fallback = all.size();
  for (std::size_t i = 0; i < all.size(); ++i)
    if (fallback == all.size() || all[i].frames.size() > all[fallback].frames.size()) fallback = i;
  const bool any_full = std::any_of(all.begin(), all.end(), [&](const Stretch& s) {
    return static_cast<int>(s.frames.size()) >= params_.min_frames;
  });
  // Consecutive short stretches are one move of the board: one note for them.
  std::vector<int> moving_run;
  const auto flush_moving = [&] {
    if (moving_run.empty()) return;
    std::sort(moving_run.begin(), moving_run.end());
    result.moving.insert(result.moving.end(), moving_run.begin(), moving_run.end());
    std::ostringstream note;
    note << frame_range(moving_run) << ": the board moved (no " << params_.min_frames
         << " frames in a row agree; not used)";
    result.notes.push_back(note.str());
    moving_run.clear();
  };
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Stretch& s = all[i];
    const bool pose = static_cast<int>(s.frames.size()) >= params_.min_frames || (!any_full && i == fallback);
    if (!pose) {
      moving_run.insert(moving_run.end(), s.frames.begin(), s.frames.end());
      moving_run.insert(moving_run.end(), s.outliers.begin(), s.outliers.end());
      continue;
    }
    flush_moving();
    result.poses.push_back(make_pose(s, frames, params_.tolerance, stream_names, result.poses.size(), result.notes));
  }
  flush_moving();
  std::sort(result.moving.begin(), result.moving.end());
  return result;
}

}  // namespace l2s
