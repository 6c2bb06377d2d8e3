// The particle frame formats as one table (frame_formats.cpp): each entry gives a format's name
// (also its file extension), its help text, how to open its frames, and its writer and reader.
// The CLI's --format list and help, the parser, FrameWriter and readFrameFile all come from it,
// so adding a format is adding one entry.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "solver/particles.h"

namespace weir {

// What a frame is written with besides its particles.
struct FrameInfo {
    double time = 0;       // simulation time [s]
    double spacing = 0;    // the run's particle spacing d [m]; 0: measured where a format needs it
    double voxelSize = 0;  // voxel of the volume formats (vdb) [m]; 0: d / 2
};

struct FrameFormatEntry {
    const char* name;  // CLI name, file extension and the format's name in frames.json
    const char* help;  // one line for --format's help
    // How to open a run's frames, completing "open ..." (DIR is replaced by the frames folder).
    const char* openHint;
    bool pvdSeries;  // the writer also keeps DIR/<base>.pvd, a ParaView time series
    // Writes one frame atomically; throws IoError.
    void (*write)(const std::string& path, const HostParticles& particles, const FrameInfo& info);
    // Reads one frame back; stores its time in *time where the format holds it and time is
    // given. Throws IoError naming the file and what is wrong.
    HostParticles (*read)(const std::string& path, double* time);
};

// The table, in the order --format lists them; the first is the default.
const std::vector<FrameFormatEntry>& frameFormatTable();

// One entry of the table. Named constants for the formats that code refers to by name.
class FrameFormat {
   public:
    static const FrameFormat Vtu, Ply, Csv;

    const FrameFormatEntry& entry() const { return frameFormatTable()[index_]; }
    const char* name() const { return entry().name; }
    friend bool operator==(FrameFormat a, FrameFormat b) { return a.index_ == b.index_; }
    friend std::ostream& operator<<(std::ostream& out, FrameFormat f) { return out << f.name(); }

   private:
    friend FrameFormat parseFrameFormat(const std::string& text);
    explicit FrameFormat(std::size_t index) : index_(index) {}
    std::size_t index_;
};

// A table name ("vtu", "ply", "csv", "vdb" where OpenVDB is built); anything else throws
// std::invalid_argument naming the value and the allowed list, or, for a format this build lacks,
// why (io/optional_formats.h).
FrameFormat parseFrameFormat(const std::string& text);
// The file extension without the dot, also the format's name in frames.json.
std::string formatExtension(FrameFormat format);
// Every format's name, in table order.
std::vector<std::string> frameFormatNames();
// "vtu, ply, csv".
std::string frameFormatList();
// For --format's help: "vtu (VTK ... ), ply (...), csv (...)".
std::string frameFormatHelp();
// The format whose extension a frame file has ("frame_00003.ply": ply); throws IoError naming the
// file and the allowed extensions for any other.
FrameFormat frameFormatOfFile(const std::string& path);

}  // namespace weir
