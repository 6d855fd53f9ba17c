// vgroove support: NumPy's .npy format (version 1.0) for arrays of doubles: the magic string,
// the version, a little-endian header length, a Python dict literal {'descr': '<f8',
// 'fortran_order': False, 'shape': (...), } padded with spaces to a multiple of 64 bytes and
// ended by a newline, then the values as raw little-endian IEEE doubles in row-major order.
// numpy.load reads it as it is.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vgroove::support {

// The bytes of a .npy file holding `values` (row-major) with `shape` (their product = values.size()).
std::string npy_bytes(const std::vector<double>& values, const std::vector<std::size_t>& shape);

}  // namespace vgroove::support
