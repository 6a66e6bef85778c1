#pragma once
// What an OSC message asks of the master (docs/operator.md, "OSC"):
//   /zenith/play  /zenith/pause  /zenith/toggle      any arguments ignored (a button sends 1 on press, 0 on release)
//   /zenith/seek f   /zenith/rate f   /zenith/exposure f (N: the show's own)   /zenith/loop T|F|i
//   /zenith/preview T|F|i                            the dome preview on or off
//   /zenith/timecode/offset s                        a chasing show's start on the house's timecode,
//                                                    s a label "hh:mm:ss:ff"
//   /zenith/sun/elevation f   /zenith/sun/azimuth f (degrees in the camera's sky; the other angle stays)
//   /zenith/clear/sun   /zenith/clear/exposure   /zenith/clear/atmosphere/<body>
//                                                    any arguments ignored: the show's (or scene's) own again
//   /zenith/atmosphere/<body>/<pointer> v            a `set`: the rest of the address is the JSON
//                                                    pointer into the body's atmosphere parameters
//                                                    (/zenith/atmosphere/Earth/aerosol/scattering/turbidity 3),
//                                                    v a number, T or F, a string, or N (removes the key)
// The message becomes the JSON command and goes through parse_operator_command,
// so it has the same ranges and errors as POST /api/command. There is no
// /zenith/quit: OSC has no authentication (docs/operator.md, "Security").
#include "cluster/operator/operator_command.h"
#include "cluster/operator/osc_packet.h"

namespace zenith::cluster {

/// The command of one OSC message. Throws zenith::ConfigError (the command's
/// key, value and range) or std::invalid_argument (an unknown address, a
/// missing or unusable argument), naming the address.
OperatorCommand osc_command(const OscMessage& message);

}  // namespace zenith::cluster
