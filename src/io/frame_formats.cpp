// The frame format table and the names, parsing and lookups derived from it.
#include "io/frame_formats.h"

#include <filesystem>
#include <stdexcept>

#include "io/csv_writer.h"
#include "io/frame_reader.h"
#include "io/io_error.h"
#include "io/optional_formats.h"
#include "io/ply_writer.h"
#include "io/vdb_file.h"
#include "io/vtu_writer.h"

namespace weir {

const std::vector<FrameFormatEntry>& frameFormatTable() {
    // The one place that lists the frame formats: add a row here (a writer, a reader, the
    // words) and `weir run --format`, FrameWriter, `weir render` and `weir mesh` take it.
    static const std::vector<FrameFormatEntry> table =
    { {"vtu", "VTK XML points with a .pvd time series (ParaView)",
       "BASE.pvd in ParaView (File > Open; it gives each frame its time)", true,
       [](const std::string& path, const HostParticles& p, const FrameInfo& info) {
           writeVtu(path, p, info.time);
       },
       [](const std::string& path, double* time) { return readVtu(path, time); }},
      {"ply", "binary PLY point clouds (Blender, Houdini, MeshLab)",
       "the BASE_NNNNN.ply point clouds in Blender, Houdini or MeshLab", false,
       [](const std::string& path, const HostParticles& p, const FrameInfo&) { writePly(path, p); },
       [](const std::string& path, double*) { return readPly(path); }},
      {"csv", "CSV text, a header then one row per particle",
       "the BASE_NNNNN.csv tables in ParaView, a spreadsheet or pandas", false,
       [](const std::string& path, const HostParticles& p, const FrameInfo&) { writeCsv(path, p); },
       [](const std::string& path, double*) { return readCsv(path); }},
#if defined(WEIR_HAS_OPENVDB)
      {"vdb",
       "OpenVDB: the surface as a level set, a velocity grid and the particles as points "
       "(Houdini, Blender)",
       "the BASE_NNNNN.vdb volumes in Houdini (File SOP) or Blender (Add > Volume > Import "
       "OpenVDB)",
       false,
       [](const std::string& path, const HostParticles& p, const FrameInfo& info) {
           writeVdbFrame(path, p, {info.time, info.spacing, info.voxelSize});
       },
       [](const std::string& path, double* time) { return readVdbFrame(path, time); }},
#endif
    };
    return table;
}

const FrameFormat FrameFormat::Vtu = parseFrameFormat("vtu");
const FrameFormat FrameFormat::Ply = parseFrameFormat("ply");
const FrameFormat FrameFormat::Csv = parseFrameFormat("csv");

FrameFormat parseFrameFormat(const std::string& text) {
    const auto& table = frameFormatTable();
    for (std::size_t i = 0; i < table.size(); ++i) {
        if (text == table[i].name) {
            return FrameFormat(i);
        }
    }
    const std::string missing = missingFormatReason(text);
    if (!missing.empty()) {
        throw std::invalid_argument("frame format \"" + text + "\": " + missing);
    }
    throw std::invalid_argument("unknown frame format \"" + text +
                                "\" (allowed: " + frameFormatList() + ")");
}

std::string formatExtension(FrameFormat format) { return format.name(); }

std::vector<std::string> frameFormatNames() {
    std::vector<std::string> names;
    for (const FrameFormatEntry& entry : frameFormatTable()) {
        names.emplace_back(entry.name);
    }
    return names;
}

std::string frameFormatList() {
    std::string list;
    for (const FrameFormatEntry& entry : frameFormatTable()) {
        list += (list.empty() ? "" : ", ") + std::string(entry.name);
    }
    return list;
}

std::string frameFormatHelp() {
    std::string help;
    for (const FrameFormatEntry& entry : frameFormatTable()) {
        help += (help.empty() ? "" : "; ") + std::string(entry.name) + ": " + entry.help;
    }
    return help;
}

FrameFormat frameFormatOfFile(const std::string& path) {
    const std::string extension = std::filesystem::path(path).extension().string();
    std::string allowed;
    for (const FrameFormatEntry& entry : frameFormatTable()) {
        if (extension.size() > 1 && extension.compare(1, std::string::npos, entry.name) == 0) {
            return parseFrameFormat(entry.name);
        }
        allowed.append(allowed.empty() ? "." : ", .").append(entry.name);
    }
    const std::string missing = missingFormatReason(extension.empty() ? "" : extension.substr(1));
    if (!missing.empty()) {
        throw IoError("cannot read '" + path + "': " + missing);
    }
    throw IoError("cannot read '" + path + "': unknown frame format '" + extension +
                  "' (allowed: " + allowed + ")");
}

}  // namespace weir
