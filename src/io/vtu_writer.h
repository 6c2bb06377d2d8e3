// writeVtu: one particle frame as a VTK XML UnstructuredGrid (.vtu) with raw appended binary data.
#pragma once

#include <string>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir {

// Writes the particles atomically as points with one VTK_VERTEX cell each (so ParaView shows
// them), point data from the field registry and an Int32 `id` (field_registry.h), and `time`
// as FieldData "TimeValue". Reals are Float32 (Float64 in a WEIR_DOUBLE build), byte order
// little endian, UInt64 block headers.
// Throws IoError when the file cannot be written.
void writeVtu(const std::string& path, const HostParticles& particles, double time);

}  // namespace weir
