#pragma once
// The hypothesise-then-verify loop shared by the branches (private): plausible
// plane candidates are tried most board-like first (oversized ones last, and
// only while nothing is verified); each branch's `try_one`
// runs its stages on one candidate, and when four holes are found the
// BoardVerifier judges the evidence. The best verified hypothesis wins; the
// search stops early at a confident one. Every hypothesis tried is logged
// with the stage and reason that decided it.

#include <l2s/board_verifier.hpp>
#include <l2s/plane_segmenter.hpp>

#include <algorithm>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace l2s::detail {

/// A plane larger than the board (a last resort: a board close before a wall
/// merges with it) has no outline or isolation to speak for it, only its
/// holes. Its rims can be found in wall texture (on 60 random scenes every
/// such plane kept without a hole seen through was a patch of brick wall,
/// metres from the board), so it is the board only when a hole shows what
/// lies behind it.
inline BoardVerifier::Verdict judge_last_resort(const BoardEvidence& e, const BoardVerifier::Params& params,
                                                BoardVerifier::Verdict verdict) {
  for (int h = 0; h < 4; ++h)
    if (e.hole_open[h] + e.hole_blocked[h] >= params.min_samples) return verdict;
  verdict.verified = false;
  verdict.score = 0.0;
  verdict.reason = "a plane larger than the board, and no hole shows what lies behind it (" + verdict.reason + ")";
  return verdict;
}

/// `try_one(BoardHypothesis&)` -> std::optional<Outcome>: the branch's result
/// when four holes were found (with hypothesis.evidence filled), otherwise
/// nullopt with hypothesis.stage and .reason set.
template <class Outcome, class TryOne>
std::optional<Outcome> search_hypotheses(const PlaneSegmenter::Result& planes, const BoardVerifier& verifier,
                                         std::vector<BoardHypothesis>& log, TryOne&& try_one) {
  std::optional<Outcome> best;
  int best_index = -1;
  const int tries = std::min<int>(static_cast<int>(planes.ranking.size()), verifier.params().max_hypotheses);
  for (int k = 0; k < tries; ++k) {
    // Oversized patches are last resorts: not tried once a board-sized one was
    // verified; nor are planes far less board-like than the verified one.
    if (best_index >= 0) {
      const PlaneCandidate& next = planes.candidates[planes.ranking[k]];
      if (next.oversized || next.prior < verifier.params().challenger_prior * log[best_index].prior) break;
    }
    BoardHypothesis hypothesis;
    hypothesis.candidate = planes.ranking[k];
    hypothesis.prior = planes.candidates[hypothesis.candidate].prior;
    std::optional<Outcome> outcome = try_one(hypothesis);
    if (outcome) {
      BoardVerifier::Verdict verdict = verifier.judge(hypothesis.evidence);
      if (verdict.verified && planes.candidates[hypothesis.candidate].oversized)
        verdict = judge_last_resort(hypothesis.evidence, verifier.params(), std::move(verdict));
      hypothesis.verified = verdict.verified;
      hypothesis.score = verdict.score;
      hypothesis.reason = verdict.reason;
      if (!verdict.verified) hypothesis.stage = "verify";
      if (verdict.verified && (best_index < 0 || verdict.score > log[best_index].score)) {
        best = std::move(outcome);
        best_index = static_cast<int>(log.size());
      }
    }
    log.push_back(std::move(hypothesis));
    if (best_index >= 0 && log[best_index].score >= verifier.params().confident_score) break;
  }
  if (best_index >= 0) {
    log[best_index].chosen = true;
    for (BoardHypothesis& other : log)
      if (other.verified && !other.chosen) {
        std::ostringstream reason;
        reason.precision(2);
        reason << std::fixed << "verified, but scored " << other.score << " against "
               << log[best_index].score << " (" << other.reason << ")";
        other.reason = reason.str();
      }
  }
  return best;
}

/// One line per hypothesis tried, for a branch's failure reason.
inline std::string describe_failed_search(const std::vector<BoardHypothesis>& log) {
  std::ostringstream out;
  out << "none of " << log.size() << " board-sized plane(s) showed the board's holes";
  for (std::size_t i = 0; i < log.size(); ++i)
    out << (i ? "; " : ": ") << "plane #" << log[i].candidate << " (" << log[i].stage << ") " << log[i].reason;
  return out.str();
}

}  // namespace l2s::detail
