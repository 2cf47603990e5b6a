#pragma once
// Hypothesise, then verify (STYLE.md, "Growing the facade"). A branch guesses
// where the board is (a board-sized plane), finds four holes on it, and only
// then asks whether the guess is the target: does the sensor see *through*
// the holes, and does the surface end at the board's outline (a window cut
// out of a wall does not)? Each branch gathers that evidence from its own data
// (lidar returns behind the plane; stereo photo-consistency); BoardVerifier
// judges it the same way for every sensor, and ranks the hypotheses that pass.

#include <l2s/export.hpp>

#include <array>
#include <limits>
#include <string>

namespace l2s {

/// What a sensor saw where the target's holes and outline should be.
struct BoardEvidence {
  std::array<int, 4> hole_open{};     ///< samples inside each hole (enum Hole order; rim margin left out) that see through it
  std::array<int, 4> hole_blocked{};  ///< samples inside each hole that see a surface on the board plane
  /// [robust sigmas] how unlike the board's face beside its rim each hole's
  /// inside looks (camera: median gray level against the face's, over their
  /// combined spread); 0 when the sensor cannot tell.
  std::array<double, 4> hole_look_difference{};
  int outline_open = 0;               ///< samples in a band just outside the board outline that see past the board
  int outline_blocked = 0;            ///< samples in that band that see a surface coplanar with the board
  double fit_rms = 0.0;               ///< [m] rms of the hole rim fit
  double fit_scale = 0.005;           ///< [m] rim fit rms that halves the score (a quarter of the circle finder's inlier threshold)
  /// Share of the rims predicted by the fitted board that the sensor's own
  /// data confirm (camera: rim samples that found an image edge in both
  /// views, or, for rims too faint for that, arcs of the rims whose mean
  /// brightness step stands above the noise); NaN when the sensor cannot tell.
  double rim_support = std::numeric_limits<double>::quiet_NaN();
  /// The same share on the board's face beside the rims (camera: image edges
  /// as strong as a rim, or arcs with a step, on circles around the holes).
  /// A board's face is smoother than its rims are sharp; a patterned wall
  /// has as many edges anywhere. NaN when the sensor cannot tell.
  double rim_background = std::numeric_limits<double>::quiet_NaN();
};

/// Judges the evidence of one board hypothesis.
/// Thread safety: holds only what it was built with; its const functions may
/// run concurrently on one instance, and each call is deterministic (random
/// draws are seeded per call from the params).
class L2S_EXPORT BoardVerifier {
 public:
  struct Params {
    double hole_margin = 0.025;     ///< [m] band inside each rim left out of the hole samples (mixed returns, stereo smear, apparent shrink), >= 0
    double outline_gap = 0.05;      ///< [m] the band around the outline starts this far out (mixed returns, border smear), >= 0
    double outline_width = 0.15;    ///< [m] width of that band, > 0
    int min_samples = 5;            ///< a hole (or the outline band) with fewer samples gives no evidence, >= 1
    double min_hole_open = 0.6;     ///< a hole with evidence must see through in at least this share of its samples, 0..1
    /// ... unless its inside looks at least this unlike the face around it
    /// (hole_look_difference): then the board's surface does not cover it,
    /// and the samples that say so matched a repetitive background one period
    /// off (no evidence). On 80 random-scene frames covered wall patches
    /// showed <= 0.5, true holes of boards before far brick walls 2.3-6.7; > 0
    double min_look_difference = 2.0;
    double min_outline_open = 0.5;  ///< the outline band, with evidence, must see past the board in at least this share, 0..1
    double min_rim_support = 0.3;   ///< rim support, when known, must reach this share, 0..1
    /// ... and exceed the share of the face beside the rims (rim_background),
    /// when known, by this: on 60 random scenes true boards showed >= 0.30,
    /// patches of brick wall taken for the board <= 0.25, 0..1
    double min_rim_excess = 0.2;
    double confident_score = 0.5;   ///< a verified hypothesis scoring at least this ends the search, 0..1
    int max_hypotheses = 4;         ///< board-sized planes verified per frame at most, most board-like first, >= 1
    /// Once one is verified, a later plane is tried only when its prior is at
    /// least this share of the verified one's: pieces of a wall behind a
    /// verified board (prior ~0.1 against ~0.9) cost a region's matching and
    /// a failed hole search each, and never won on the simulated suite; 0 tries them all, 0..1
    double challenger_prior = 0.5;

    void validate() const;  ///< throws ParamError naming the field
  };

  struct Verdict {
    bool verified = false;
    double score = 0.0;  ///< 0..1, higher is more board-like; 0 when rejected
    std::string reason;  ///< why it was rejected, or a summary of the evidence when verified
  };

  // Two constructors rather than `Params params = {}` (see PlaneSegmenter).
  BoardVerifier();
  explicit BoardVerifier(Params params);

  /// Rejects a hypothesis whose holes (with evidence) are covered, whose
  /// surface continues beyond the outline, or whose rims the data do not
  /// confirm; scores the rest by how open the holes are, how clear the
  /// outline is, how well the rims fit and how well they are confirmed.
  /// Missing evidence (nothing behind the board in range) neither rejects nor
  /// helps: a hole without evidence counts as half open.
  Verdict judge(const BoardEvidence& evidence) const;
  const Params& params() const { return params_; }

 private:
  Params params_;
};

/// What a branch made of one board hypothesis (a plausible plane candidate).
struct BoardHypothesis {
  int candidate = -1;      ///< index into PlaneSegmenter::Result::candidates
  double prior = 0.0;      ///< board-likeness before verification (PlaneCandidate::prior)
  std::string stage;       ///< stage that rejected it ("discontinuities", "circles", "verify", ...); empty when verified
  std::string reason;      ///< why it lost, or the verifier's summary when verified
  BoardEvidence evidence;  ///< gathered once four holes were found
  bool verified = false;
  double score = 0.0;      ///< the verifier's score (verified only)
  bool chosen = false;     ///< the hypothesis the branch kept
};

}  // namespace l2s
