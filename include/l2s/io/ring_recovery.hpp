#pragma once
// The laser index (ring) of each return of a spinning lidar whose sweep was
// stored without a `ring` field, and whether the sweep has rings at all.
//
// A laser does not fire from the sensor origin: VLP-16 beams start 3.4 cm off
// the axis, HDL-64E lasers sit 0.15-0.22 m up in the head. Its returns lie on
// z = d * tan(elevation) + offset (d: horizontal distance), so seen from the
// origin a near return of one laser can have the elevation of another. Ring
// recovery fits that model per laser, far returns first, and gives every
// return the laser whose model explains it best.

#include <l2s/export.hpp>
#include <l2s/types.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace l2s::io {

/// Where a sweep's ring indices came from.
enum class RingSource {
  Field,          ///< the file's `ring` (or `laser_id`) field
  OrganisedRows,  ///< the rows of an organised cloud (HEIGHT > 1), one per laser
  LaserModel,     ///< recovered from the returns by per-laser models (recover_ring_structure)
};

/// Which lidar path a sweep needs.
enum class ScanStructure {
  Rings,     ///< a spinning lidar's scan lines: work ring by ring
  RingFree,  ///< no laser structure (solid-state, non-repetitive scans): accumulate frames
};

/// "field", "organised rows", "laser model"; "rings", "ring-free".
L2S_EXPORT std::string to_string(RingSource source);
L2S_EXPORT std::string to_string(ScanStructure structure);

/// One laser as recovered: its returns lie on z = d * tan(elevation) + offset.
struct LaserFit {
  int ring = 0;            ///< index its returns were given
  double elevation = 0.0;  ///< [rad]
  double offset = 0.0;     ///< [m] vertical origin offset (the model's h)
  double rms = 0.0;        ///< [rad] rms elevation residual of its returns
  std::size_t points = 0;  ///< returns given this ring
  /// Its returns in the inner quarter of the half gap to the next ring per
  /// return in the outer quarter (returns beyond 2 m): tens for a separate
  /// scan line, a few where two rings overlap; 0 when not measured.
  double contrast = 0.0;
};

/// How a sweep's rings were found, and whether they can be trusted.
struct L2S_EXPORT RingRecoveryReport {
  RingSource source = RingSource::LaserModel;
  ScanStructure structure = ScanStructure::Rings;
  std::string structure_reason;  ///< why Rings or RingFree, in words
  int rings = 0;                 ///< highest ring index + 1 (skipped silent beams count)
  std::vector<LaserFit> lasers;  ///< the rings that have returns, ascending elevation
  std::size_t points = 0;        ///< returns given a ring (finite and off the spin axis)
  std::size_t min_points = 0;    ///< fewest returns of a ring with returns
  double median_points = 0.0;    ///< median returns of the rings with returns
  double residual_rms = 0.0;     ///< [rad] elevation residual over all returns
  /// Median |residual| of the returns over half the gap to the next laser on
  /// their side: ~0.1 for scan lines, ~0.5 for elevations spread evenly.
  double fill = 0.0;
  /// The same over all rings (LaserFit::contrast): tens for scan lines, ~1
  /// for elevations spread evenly.
  double contrast = 0.0;
  bool doubtful = false;  ///< the structure looks wrong; `doubt` says why
  std::string doubt;      ///< reasons, "; "-separated (empty when not doubtful)
  std::string note;       ///< how the source was chosen, e.g. why rows were not used

  /// One line: source, ring count, returns per ring, residual, structure, doubts.
  std::string summary() const;
};

struct L2S_EXPORT RingRecoveryParams {
  /// [rad] two lasers are at least this far apart in elevation; must be below
  /// the smallest beam spacing (HDL-64E: 0.33 deg) and above the elevation
  /// noise of one beam. > 0.
  double min_gap = 0.1 * 3.14159265358979 / 180.0;
  /// a ring needs at least this many returns; >= 1
  int min_points_per_ring = 3;
  /// Where the beam spacing is locally regular, a gap of k spacings between two
  /// rings means k - 1 beams without any return: their indices are skipped so
  /// that ring numbers stay the laser indices of the sensor.
  bool infer_missing_beams = true;
  /// [m] largest |vertical origin offset| of a laser searched (HDL-64E: 0.22). > 0
  double max_offset = 0.5;
  /// returns used to fit the laser models (every k-th); all returns are then
  /// assigned. More: slower, better for lasers with very few returns. >= 100
  int max_fit_points = 16000;

  /// Throws ParamError naming the field when a value is out of range.
  void validate() const;
};

/// Fills cloud.ring (0 = lowest elevation) from per-laser models fitted to
/// the returns, and reports the structure found (Rings or RingFree, doubts).
/// Returns that are not finite or sit on the spin axis get ring 0 and count
/// for no ring. Deterministic: no randomness, the same cloud gives the same rings.
L2S_EXPORT RingRecoveryReport recover_ring_structure(LidarCloud& cloud, const RingRecoveryParams& params = {});

/// recover_ring_structure(cloud, params).rings: the ring count (0 when no
/// return is valid).
L2S_EXPORT int recover_rings(LidarCloud& cloud, const RingRecoveryParams& params = {});

/// For an organised cloud of `height` rows (PcdFile::height): when the rows
/// look like lasers (each row's returns fit one laser model tightly compared
/// with the spacing between rows; NaN padding is ignored), fills cloud.ring
/// from the rows (0 = the lowest row by elevation; rows stored top first, as
/// some drivers do, are numbered from the bottom) with source OrganisedRows.
/// Otherwise falls back to recover_ring_structure and says why in `note`.
/// Throws ParamError when height is 0 or does not divide the cloud's size.
L2S_EXPORT RingRecoveryReport rings_from_rows(LidarCloud& cloud, std::size_t height,
                                   const RingRecoveryParams& params = {});

/// Whether a sweep's ring field gives its scan lines: each value one laser,
/// its returns on one line of the laser model, successive values on
/// successive lines (numbered from the bottom or from the top). Drivers also
/// write fields that are not: a solid-state lidar's line or head number (each
/// spans the field of view), a packet counter, a constant. Such a field is
/// not `usable`, and `reason` says why; a cloud without a field (or with
/// too few returns to judge) passes.
struct RingFieldCheck {
  bool usable = true;
  std::string reason;
};
L2S_EXPORT RingFieldCheck check_ring_field(const LidarCloud& cloud);

/// Whether a sweep needs the ring path or the ring-free one, and why. A sweep
/// with a usable ring field (check_ring_field) is Rings; otherwise its rings
/// are recovered from the returns (on a copy).
struct ScanClassification {
  ScanStructure structure = ScanStructure::Rings;
  std::string reason;
};
L2S_EXPORT ScanClassification classify_scan(const LidarCloud& cloud, const RingRecoveryParams& params = {});

/// Where a sweep's rings came from, as the calibrator takes the sweep (settle_rings).
struct SweptRings {
  RingSource source = RingSource::Field;
  /// How the rings were found when the sweep had no usable ring field; empty for RingSource::Field.
  std::optional<RingRecoveryReport> recovery;
};

/// A sweep made ready for the calibrator, as io::Dataset loads each one: a
/// usable ring field (check_ring_field) kept; otherwise the rings taken from
/// the rows of an organised cloud (`rows` > 1, rings_from_rows) or recovered
/// from the returns (recover_ring_structure), the field's fault said in the
/// report's note; a ring-free scan left without rings (the calibrator
/// accumulates it instead).
L2S_EXPORT SweptRings settle_rings(LidarCloud& cloud, std::size_t rows = 1);

}  // namespace l2s::io
