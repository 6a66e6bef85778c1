#include "cluster/master/master_desk.h"

#include "cluster/master/master_status.h"

namespace zenith::cluster {

nlohmann::json MasterDesk::status(const DeskStatus& desk) const {
  const FrameProgress& p = p_.progress;
  const TableSchedule& t = p_.tables;
  return master_status(StatusSources{p_.config,
                                     p_.sessions,
                                     p_.barrier,
                                     t.tables(),
                                     p_.preparing(),
                                     p_.statistics,
                                     t.edits(),
                                     p_.show,
                                     p_.clock,
                                     p.started,
                                     p.stopping,
                                     p.started ? &p.in_flight : nullptr,
                                     p.presented,
                                     p_.fps,
                                     desk.exposure_override,
                                     t.pending_change(),
                                     t.last_error(),
                                     desk.sun,
                                     desk.sun_override,
                                     p_.show ? &t.overrides() : nullptr,
                                     t.show_versions(),
                                     desk.preview,
                                     desk.preview_on,
                                     p_.timecode});
}

}  // namespace zenith::cluster
