// Readers for the frames this module writes (VTU, PLY, CSV), for tests and later tools.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir {

// Each reader validates what it reads and throws IoError naming the file and what is wrong
// (cannot open, not this format, missing array or column, wrong type or size, truncated).
// Files with particle ids (field_registry.h; weir wrote none before them) come back in id order,
// so a frame that another tool re-sorted reads as weir wrote it; files without ids in file order.

// Reads a .vtu written by writeVtu; stores its FieldData "TimeValue" in *time when given.
// Float32 and Float64 arrays are both accepted and converted to Real.
HostParticles readVtu(const std::string& path, double* time = nullptr);
// Just the "TimeValue" of a .vtu written by writeVtu.
double readVtuTime(const std::string& path);

// Reads a binary little-endian .ply holding at least the columns writePly writes (any numeric
// type; `id` an integer type, optional); other vertex properties are ignored.
HostParticles readPly(const std::string& path);

// Reads a .csv written by writeCsv (the header must match exactly, with or without the
// trailing id column).
HostParticles readCsv(const std::string& path);

// Puts the particles in id order: ids[k] is the id of row k. Ids that are not 0 .. n - 1 (a run
// with emitters and sinks) go into particles.id. Throws IoError naming the file, the row and the
// id when an id is negative, past int32, or not unique.
void orderParticlesById(HostParticles& particles, const std::vector<std::int64_t>& ids,
                        const std::string& path);

// The readers above return what the file holds, NaN included (a frame of a run that blew up is
// still worth reading). Drawing or meshing a frame needs its positions to be real:
// checkFramePositions throws IoError naming the file, the particle index, the field (x, y or z)
// and the value when a position is not finite, lies past kMaxFrameCoordinate, or lies further
// than kAbsurdExtentFactor times the frame's plausible extent from the origin (the extent: the
// largest |coordinate| of the 1st..99th percentiles of every axis, at least 1 m).
inline constexpr double kMaxFrameCoordinate = 1e9;  // m; weir's scenes are metres to kilometres
inline constexpr double kAbsurdExtentFactor = 1e6;
void checkFramePositions(const HostParticles& particles, const std::string& path);

}  // namespace weir
