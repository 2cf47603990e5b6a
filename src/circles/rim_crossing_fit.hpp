#pragma once
// The hole pattern of one static board pose fitted to every place its lidar
// rings crossed a hole rim, over all the pose's sweeps (private to the
// library).
//
// A ring crosses a rim somewhere between its last board return and the next
// ray: an interval one azimuth step wide (12 mm at 3.5 m for a VLP-16), with
// the rim anywhere in it. Averaging the intervals' midpoints, as each sweep's
// circle fit and then the pose's clustering do, leaves an error that falls
// only as the square root of the sweeps: on the nine settings (VLP-16, K = 1,
// 10 sweeps a pose) each pose's pattern was off by up to 1.7 mm and turned
// in the board plane by up to 0.2 deg. The pattern that keeps every
// crossing's rim inside its interval is pinned far more sharply: each
// interval cuts away what lies outside it, so the feasible set shrinks about
// as one over the number of crossings. The fit keeps the intervals as
// (squared) hinge terms and the midpoints as a weak term that picks a place
// inside what the intervals allow.

#include <l2s/geometry.hpp>
#include <l2s/target.hpp>
#include <l2s/types.hpp>

#include <optional>
#include <string>
#include <vector>

namespace l2s::detail {

struct RimCrossingFitParams {
  bool model_thickness = true;    ///< a ray sees the aperture of a thick board (front and back rim)
  bool fit_radius = true;         ///< estimate the apparent hole radius (one for all four)
  double midpoint_weight = 1e-3;  ///< weight of an interval's midpoint against a violated interval end
  double max_violation = 0.01;    ///< [m] a crossing whose interval misses the fitted rim by more is left out
  double max_shift = 0.02;        ///< [m] the fit may move a hole centre at most this far from the start
  int min_crossings = 8;          ///< fewest crossings, over at least three holes
  int iterations = 40;            ///< Gauss-Newton steps
};

struct RimCrossingFit {
  std::optional<HoleCenters> centers;  ///< [m] on `plane`, sensor frame, labelled as the start; empty when not fitted
  std::string reason;                  ///< why not
  int crossings = 0;                   ///< crossings used
  double radius = 0.0;                 ///< [m] apparent hole radius of the fit
};

/// The pattern of `target` fitted to `crossings` (sensor frame, each on its
/// sweep's board plane) on `plane` (the pose's board front face), starting at
/// `start` (the pose's clustered centres, labelled).
RimCrossingFit fit_pattern_to_rim_crossings(const HoleCenters& start, const Plane& plane,
                                            const std::vector<RimCrossing>& crossings,
                                            const Target& target,
                                            const RimCrossingFitParams& params = {});

}  // namespace l2s::detail
