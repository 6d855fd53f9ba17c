#include "vgroove/app/energy_images.h"

#include "vgroove/support/user_error.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vgroove::app {

namespace {

void png_append(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), n);
}
void png_no_flush(png_structp) {}
[[noreturn]] void png_fail(png_structp, png_const_charp message) {
  throw support::UserError(std::string("PNG: ") + message);
}
void png_quiet(png_structp, png_const_charp) {}

struct Reader {
  const std::string* bytes;
  std::size_t at = 0;
};
void png_take(png_structp png, png_bytep data, png_size_t n) {
  auto* r = static_cast<Reader*>(png_get_io_ptr(png));
  if (r->at + n > r->bytes->size()) png_error(png, "truncated");
  std::memcpy(data, r->bytes->data() + r->at, n);
  r->at += n;
}

}  // namespace

std::string png16_bytes(const std::vector<double>& values, int rows, int columns, double scale,
                        const std::string& text) {
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, png_fail, png_quiet);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw support::UserError("PNG: out of memory");
  try {
    png_set_write_fn(png, &out, png_append, png_no_flush);
    png_set_IHDR(png, info, static_cast<png_uint_32>(columns), static_cast<png_uint_32>(rows), 16, PNG_COLOR_TYPE_GRAY,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_text t{};
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<char*>("vgroove");
    t.text = const_cast<char*>(text.c_str());
    t.text_length = text.size();
    png_set_text(png, info, &t, 1);
    png_write_info(png, info);
    std::vector<unsigned char> row(static_cast<std::size_t>(columns) * 2);
    for (int y = 0; y < rows; ++y) {
      for (int x = 0; x < columns; ++x) {
        const double v = std::clamp(values[static_cast<std::size_t>(y) * columns + x] / scale, 0.0, 1.0);
        const auto q = static_cast<unsigned>(std::lround(v * 65535.0));
        row[2 * static_cast<std::size_t>(x)] = static_cast<unsigned char>(q >> 8);  // big-endian samples
        row[2 * static_cast<std::size_t>(x) + 1] = static_cast<unsigned char>(q & 0xff);
      }
      png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
  } catch (...) {
    png_destroy_write_struct(&png, &info);
    throw;
  }
  png_destroy_write_struct(&png, &info);
  return out;
}

std::vector<double> png16_values(const std::string& bytes, int& rows, int& columns, std::string& text) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, png_fail, png_quiet);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw support::UserError("PNG: out of memory");
  std::vector<double> out;
  try {
    Reader r{&bytes};
    png_set_read_fn(png, &r, png_take);
    png_read_info(png, info);
    columns = static_cast<int>(png_get_image_width(png, info));
    rows = static_cast<int>(png_get_image_height(png, info));
    if (png_get_bit_depth(png, info) != 16 || png_get_color_type(png, info) != PNG_COLOR_TYPE_GRAY)
      throw support::UserError("PNG: not 16-bit grey");
    png_textp t = nullptr;
    int n = 0;
    png_get_text(png, info, &t, &n);
    for (int k = 0; k < n; ++k)
      if (std::string(t[k].key) == "vgroove") text.assign(t[k].text, t[k].text_length);
    std::vector<unsigned char> row(static_cast<std::size_t>(columns) * 2);
    for (int y = 0; y < rows; ++y) {
      png_read_row(png, row.data(), nullptr);
      for (int x = 0; x < columns; ++x)
        out.push_back(((row[2 * static_cast<std::size_t>(x)] << 8) | row[2 * static_cast<std::size_t>(x) + 1]) /
                      65535.0);
    }
  } catch (...) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw;
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return out;
}

namespace {
// An OpenEXR output stream into memory.
class MemoryStream final : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("<memory>") {}
  void write(const char c[], int n) override {
    if (at_ + static_cast<std::size_t>(n) > bytes_.size()) bytes_.resize(at_ + static_cast<std::size_t>(n));
    std::memcpy(bytes_.data() + at_, c, static_cast<std::size_t>(n));
    at_ += static_cast<std::size_t>(n);
  }
  uint64_t tellp() override { return at_; }
  void seekp(uint64_t pos) override { at_ = static_cast<std::size_t>(pos); }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
  std::size_t at_ = 0;
};
}  // namespace

std::string exr_bytes(const std::vector<ExrChannel>& channels, int rows, int columns, const std::string& text) {
  try {
    Imf::Header header(columns, rows);
    header.insert("vgroove", Imf::StringAttribute(text));
    std::vector<std::vector<float>> data;
    for (const ExrChannel& c : channels) {
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
      data.emplace_back(c.values.begin(), c.values.end());
    }
    Imf::FrameBuffer fb;
    for (std::size_t k = 0; k < channels.size(); ++k)
      fb.insert(channels[k].name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data[k].data()), sizeof(float),
                                             sizeof(float) * static_cast<std::size_t>(columns)));
    MemoryStream stream;
    {
      Imf::OutputFile file(stream, header);
      file.setFrameBuffer(fb);
      file.writePixels(rows);
    }
    return stream.bytes();
  } catch (const std::exception& e) {
    throw support::UserError(std::string("OpenEXR: ") + e.what());
  }
}

}  // namespace vgroove::app
