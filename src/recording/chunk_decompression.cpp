#include "recording/chunk_decompression.hpp"

#include <bzlib.h>
#include <lz4frame.h>

#include <cstring>
#include <memory>
#include <stdexcept>

namespace l2s::detail {
namespace {

std::vector<std::uint8_t> from_bz2(const std::uint8_t* data, std::size_t data_size, std::size_t size) {
  std::vector<std::uint8_t> out(size);
  auto produced = static_cast<unsigned int>(size);
  const int status = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &produced,
                                                const_cast<char*>(reinterpret_cast<const char*>(data)),
                                                static_cast<unsigned int>(data_size), 0, 0);
  if (status == BZ_OUTBUFF_FULL) throw std::runtime_error("its bz2 data holds more than the stated " + std::to_string(size) + " bytes");
  if (status != BZ_OK) throw std::runtime_error("its bz2 data does not decompress (bzip2 error " + std::to_string(status) + ")");
  if (produced != size)
    throw std::runtime_error("its bz2 data holds " + std::to_string(produced) + " bytes, not the stated " + std::to_string(size));
  return out;
}

std::vector<std::uint8_t> from_lz4(const std::uint8_t* data, std::size_t data_size, std::size_t size) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
    throw std::runtime_error("no lz4 decompression context");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(raw, LZ4F_freeDecompressionContext);
  std::vector<std::uint8_t> out(size);
  std::size_t produced = 0, consumed = 0;
  while (consumed < data_size) {
    std::size_t out_room = size - produced, in_left = data_size - consumed;
    const std::size_t hint = LZ4F_decompress(context.get(), out.data() + produced, &out_room, data + consumed, &in_left, nullptr);
    if (LZ4F_isError(hint))
      throw std::runtime_error(std::string("its lz4 data does not decompress (") + LZ4F_getErrorName(hint) + ")");
    produced += out_room;
    consumed += in_left;
    if (hint == 0) break;  // the frame ended
    if (out_room == 0 && in_left == 0)
      throw std::runtime_error("its lz4 data holds more than the stated " + std::to_string(size) + " bytes");
  }
  if (produced != size)
    throw std::runtime_error("its lz4 data holds " + std::to_string(produced) + " bytes, not the stated " + std::to_string(size));
  return out;
}

}  // namespace

std::vector<std::uint8_t> decompress_chunk(const std::string& compression, const std::uint8_t* data,
                                           std::size_t data_size, std::size_t size) {
  // Recorders write chunks of about a megabyte (rosbag's default 768 KiB);
  // a stated size far beyond is a corrupt header, not a chunk to allocate.
  constexpr std::size_t kMaxChunk = std::size_t{256} << 20;
  if (size > kMaxChunk)
    throw std::runtime_error("it states " + std::to_string(size) + " bytes once decompressed, more than the " +
                             std::to_string(kMaxChunk >> 20) + " MiB a chunk may hold");
  if (compression == "none") {
    if (data_size != size)
      throw std::runtime_error("it holds " + std::to_string(data_size) + " bytes, not the stated " + std::to_string(size));
    return std::vector<std::uint8_t>(data, data + data_size);
  }
  if (compression == "bz2") return from_bz2(data, data_size, size);
  if (compression == "lz4") return from_lz4(data, data_size, size);
  throw std::runtime_error("its compression '" + compression + "' is not one of none, bz2, lz4");
}

}  // namespace l2s::detail
