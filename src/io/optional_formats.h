// The formats a build may lack: OpenVDB's .vdb, built only where libopenvdb-dev was found when weir
// was configured. Their names stay known, so that asking for one says why it is missing.
#pragma once

#include <string>

namespace weir {

// Whether this build writes and reads OpenVDB files.
bool openVdbBuilt();

// For a format name that this build lacks ("vdb" without OpenVDB): why, and how to get it;
// "" for any other name.
std::string missingFormatReason(const std::string& name);

}  // namespace weir
