// The verdict on one board hypothesis (see board_verifier.hpp): the holes must
// be open where the sensor has evidence, the surface must end at the board's
// outline, and among the hypotheses that pass, open holes, a clear outline and
// a tight rim fit score best.
#include <l2s/board_verifier.hpp>

#include <l2s/error.hpp>

#include <cmath>
#include <sstream>

namespace l2s {
namespace {

constexpr const char* kHoleNames[4] = {"top-left", "top-right", "bottom-left", "bottom-right"};
constexpr double kNoEvidence = 0.5;  // the share used when a sensor saw nothing there

double share(int open, int blocked) { return static_cast<double>(open) / static_cast<double>(open + blocked); }

}  // namespace

void BoardVerifier::Params::validate() const {
  if (!(hole_margin >= 0.0)) throw ParamError("hole_margin", "must be >= 0 m");
  if (!(outline_gap >= 0.0)) throw ParamError("outline_gap", "must be >= 0 m");
  if (!(outline_width > 0.0)) throw ParamError("outline_width", "must be > 0 m");
  if (min_samples < 1) throw ParamError("min_samples", "must be >= 1");
  if (!(min_hole_open >= 0.0 && min_hole_open <= 1.0)) throw ParamError("min_hole_open", "must be in [0, 1]");
  if (!(min_look_difference > 0.0)) throw ParamError("min_look_difference", "must be > 0");
  if (!(min_outline_open >= 0.0 && min_outline_open <= 1.0))
    throw ParamError("min_outline_open", "must be in [0, 1]");
  if (!(confident_score >= 0.0 && confident_score <= 1.0)) throw ParamError("confident_score", "must be in [0, 1]");
  if (!(min_rim_support >= 0.0 && min_rim_support <= 1.0)) throw ParamError("min_rim_support", "must be in [0, 1]");
  if (!(min_rim_excess >= 0.0 && min_rim_excess <= 1.0)) throw ParamError("min_rim_excess", "must be in [0, 1]");
  if (max_hypotheses < 1) throw ParamError("max_hypotheses", "must be >= 1");
  if (!(challenger_prior >= 0.0 && challenger_prior <= 1.0)) throw ParamError("challenger_prior", "must be in [0, 1]");
}

BoardVerifier::BoardVerifier() : BoardVerifier(Params{}) {}

BoardVerifier::BoardVerifier(Params params) : params_(params) { params_.validate(); }

BoardVerifier::Verdict BoardVerifier::judge(const BoardEvidence& e) const {
  Verdict verdict;
  std::ostringstream summary;
  double open_sum = 0.0;
  int holes_seen = 0, holes_unlike_face = 0;
  for (int h = 0; h < 4; ++h) {
    const int samples = e.hole_open[h] + e.hole_blocked[h];
    if (samples < params_.min_samples) {
      open_sum += kNoEvidence;
      continue;
    }
    const double open = share(e.hole_open[h], e.hole_blocked[h]);
    if (open < params_.min_hole_open && e.hole_look_difference[h] >= params_.min_look_difference) {
      open_sum += kNoEvidence;  // not the board's face: a background aliased onto the plane
      ++holes_unlike_face;
      continue;
    }
    if (open < params_.min_hole_open) {
      std::ostringstream reason;
      reason << "the " << kHoleNames[h] << " hole is covered: " << e.hole_blocked[h] << " of " << samples
             << " samples inside it lie on the board plane (a surface without holes?)";
      verdict.reason = reason.str();
      return verdict;
    }
    open_sum += open;
    ++holes_seen;
  }
  const int outline_samples = e.outline_open + e.outline_blocked;
  double outline = kNoEvidence;
  if (outline_samples >= params_.min_samples) {
    outline = share(e.outline_open, e.outline_blocked);
    if (outline < params_.min_outline_open) {
      std::ostringstream reason;
      reason << "the surface continues beyond the board's outline: " << e.outline_blocked << " of "
             << outline_samples << " samples around it are coplanar (a wall, not the board)";
      verdict.reason = reason.str();
      return verdict;
    }
  }
  if (std::isfinite(e.rim_support) && e.rim_support < params_.min_rim_support) {
    std::ostringstream reason;
    reason << "the rims are not where the fit puts them: " << static_cast<int>(std::lround(100.0 * e.rim_support))
           << "% of the predicted rim samples are confirmed (needs " << params_.min_rim_support * 100.0 << "%)";
    verdict.reason = reason.str();
    return verdict;
  }
  if (std::isfinite(e.rim_support) && std::isfinite(e.rim_background) &&
      e.rim_support - e.rim_background < params_.min_rim_excess) {
    std::ostringstream reason;
    reason << "the rims are no sharper than the surface around them: "
           << static_cast<int>(std::lround(100.0 * e.rim_support)) << "% of the rim samples confirmed, "
           << static_cast<int>(std::lround(100.0 * e.rim_background))
           << "% beside the rims on the face (a patterned wall, not the board; needs "
           << params_.min_rim_excess * 100.0 << " points more on the rims)";
    verdict.reason = reason.str();
    return verdict;
  }
  const double holes = open_sum / 4.0;
  const double fit = 1.0 / (1.0 + std::pow(e.fit_rms / e.fit_scale, 2));
  const double rims = std::isfinite(e.rim_support) ? e.rim_support : 1.0;
  verdict.verified = true;
  verdict.score = holes * outline * fit * rims;
  summary.precision(2);
  summary << std::fixed << "holes open " << holes << " (" << holes_seen << " of 4 with evidence";
  if (holes_unlike_face > 0)
    summary << "; " << holes_unlike_face << " matched on the plane but unlike the face around them, taken as none";
  summary << "), outline clear "
          << outline << (outline_samples >= params_.min_samples ? "" : " (no evidence)") << ", rim fit rms "
          << e.fit_rms * 1e3 << " mm";
  if (std::isfinite(e.rim_support)) summary << ", rims confirmed " << e.rim_support;
  if (std::isfinite(e.rim_background)) summary << " (face beside them " << e.rim_background << ")";
  summary << ": score " << verdict.score;
  verdict.reason = summary.str();
  return verdict;
}

}  // namespace l2s
