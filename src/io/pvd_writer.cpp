// PvdCollection: keeps the entries and writes the Collection XML.
#include "io/pvd_writer.h"

#include <algorithm>
#include <filesystem>
#include <ostream>

#include "io/atomic_file.h"
#include "io/io_util.h"

namespace weir {

namespace {

// File names become XML attribute values.
std::string xmlEscaped(const std::string& text) {
    std::string escaped;
    for (char c : text) {
        switch (c) {
            case '&':
                escaped += "&amp;";
                break;
            case '<':
                escaped += "&lt;";
                break;
            case '>':
                escaped += "&gt;";
                break;
            case '"':
                escaped += "&quot;";
                break;
            default:
                escaped += c;
        }
    }
    return escaped;
}

}  // namespace

PvdCollection::PvdCollection(std::string dir, std::string baseName)
    : path_((std::filesystem::path(std::move(dir)) / (std::move(baseName) + ".pvd")).string()) {}

void PvdCollection::add(double time, const std::string& file) {
    const auto same = std::find_if(entries_.begin(), entries_.end(),
                                   [&](const auto& entry) { return entry.second == file; });
    if (same != entries_.end()) {
        same->first = time;
    } else {
        entries_.emplace_back(time, file);
    }
    rewrite();
}

void PvdCollection::rewrite() const {
    writeFileAtomically(path_, [&](std::ostream& out) {
        out << "<?xml version=\"1.0\"?>\n"
               "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "  <Collection>\n";
        for (const auto& [time, file] : entries_) {
            out << "    <DataSet timestep=\"" << numberText(time)
                << "\" group=\"\" part=\"0\" file=\"" << xmlEscaped(file) << "\"/>\n";
        }
        out << "  </Collection>\n"
               "</VTKFile>\n";
    });
}

}  // namespace weir
