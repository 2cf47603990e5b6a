// A sweep made ready for the calibrator (settle_rings in
// l2s/io/ring_recovery.hpp): the same decision for a sweep read from a PCD
// file and one decoded from a recording, so both calibrate alike.
#include <l2s/io/ring_recovery.hpp>

namespace l2s::io {

SweptRings settle_rings(LidarCloud& cloud, std::size_t rows) {
  SweptRings rings;
  std::string ignored;
  if (cloud.has_ring()) {
    const RingFieldCheck field = check_ring_field(cloud);
    if (field.usable) return rings;
    ignored = "ring field ignored: " + field.reason;  // the returns decide instead
    cloud.ring.clear();
  }
  RingRecoveryReport report = rows > 1 ? rings_from_rows(cloud, rows) : recover_ring_structure(cloud);
  if (!ignored.empty()) report.note = ignored + (report.note.empty() ? "" : "; " + report.note);
  rings.source = report.source;
  // A ring-free scan has no rings to give: the calibrator accumulates it instead.
  if (report.structure == ScanStructure::RingFree) cloud.ring.clear();
  rings.recovery = std::move(report);
  return rings;
}

}  // namespace l2s::io
