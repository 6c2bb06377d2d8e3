// writeCsv: one particle frame as CSV text, a header row then one row per particle.
#pragma once

#include <string>

#include "io/io_error.h"
#include "solver/particles.h"

namespace weir {

// Writes the particles atomically under the header `x,y,z,vx,vy,vz,density,pressure,id` (the
// field registry's columns, then each particle's id: its row number). Each number is the
// shortest text that reads back to the same Real. Throws IoError when the file cannot be written.
void writeCsv(const std::string& path, const HostParticles& particles);

}  // namespace weir
