#include "vgroove/support/npy.h"

#include <bit>
#include <cassert>
#include <cstdint>
#include <cstring>

namespace vgroove::support {

std::string npy_bytes(const std::vector<double>& values, const std::vector<std::size_t>& shape) {
  std::size_t count = 1;
  std::string dims;  // "2, 3"; one dimension keeps its comma: "5,"
  for (std::size_t i = 0; i < shape.size(); ++i) count *= shape[i], dims += (i ? ", " : "") + std::to_string(shape[i]);
  if (shape.size() == 1) dims += ",";
  assert(count == values.size());
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + dims + "), }";
  // magic (6) + version (2) + length (2) + header + '\n', a multiple of 64.
  const std::size_t total = (10 + header.size() + 1 + 63) / 64 * 64;
  header.append(total - 10 - header.size() - 1, ' ');
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  const auto len = static_cast<std::uint16_t>(header.size());
  out += static_cast<char>(len & 0xff);
  out += static_cast<char>(len >> 8);
  out += header;
  const std::size_t at = out.size();
  out.resize(at + 8 * values.size());
  for (std::size_t n = 0; n < values.size(); ++n) {
    std::uint64_t bits = std::bit_cast<std::uint64_t>(values[n]);
    if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap64(bits);
    std::memcpy(&out[at + 8 * n], &bits, 8);
  }
  return out;
}

}  // namespace vgroove::support
