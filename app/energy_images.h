// vgroove app: the image files of `vgroove energy --export` (validation/energy_export.h): 16-bit
// PNG (libpng) and OpenEXR (Debian's libopenexr-dev), each encoded in memory, so that a file is
// written whole or not at all (support/atomic_file.h).
#pragma once

#include "vgroove/validation/energy_export.h"

#include <string>
#include <vector>

namespace vgroove::app {

// One 2D table (rows x columns, row-major) as a 16-bit grey PNG: round(v / scale * 65535), v / scale
// clamped to [0, 1]; `text` in a tEXt chunk with the keyword "vgroove".
std::string png16_bytes(const std::vector<double>& values, int rows, int columns, double scale,
                        const std::string& text);
// The decoded values of such a PNG (its tests), and its "vgroove" text.
std::vector<double> png16_values(const std::string& bytes, int& rows, int& columns, std::string& text);

// Named 2D tables of one size as 32-bit float channels of one OpenEXR image, `text` in a string
// attribute "vgroove".
struct ExrChannel {
  std::string name;
  std::vector<double> values;  // rows x columns, row-major
};
std::string exr_bytes(const std::vector<ExrChannel>& channels, int rows, int columns, const std::string& text);

}  // namespace vgroove::app
