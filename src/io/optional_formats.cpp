// Which optional formats this build has (WEIR_HAS_OPENVDB is defined for io/ where it was found).
#include "io/optional_formats.h"

#include "io/vdb_file.h"

namespace weir {

bool openVdbBuilt() {
#if defined(WEIR_HAS_OPENVDB)
    return true;
#else
    return false;
#endif
}

std::string missingFormatReason(const std::string& name) {
    if (name == "vdb" && !openVdbBuilt()) {
        return "this build has no OpenVDB: weir was configured without libopenvdb-dev, so it "
               "cannot write .vdb files (on Debian/Ubuntu: apt-get install libopenvdb-dev, then "
               "configure and build again, or run scripts/setup.sh)";
    }
    return "";
}

#if !defined(WEIR_HAS_OPENVDB)
// Without OpenVDB the vdb functions exist, so that callers build the same either way, and say why
// they cannot work.
void writeVdbFrame(const std::string& path, const HostParticles&, const VdbFrameOptions&,
                   const TriangleMesh*) {
    throw IoError("cannot write '" + path + "': " + missingFormatReason("vdb"));
}

HostParticles readVdbFrame(const std::string& path, double*) {
    throw IoError("cannot read '" + path + "': " + missingFormatReason("vdb"));
}
#endif

}  // namespace weir
