#include "io/vtk_binary.h"

#include <zlib.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <ostream>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"

namespace radwalk {
namespace {

static_assert(std::endian::native == std::endian::little, "the .vtp files declare byte_order=\"LittleEndian\"");

constexpr char kBase64Alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// The 4 characters of 3 bytes.
void encode_triple(const unsigned char* b, char* text) {
  const std::uint32_t v = (std::uint32_t{b[0]} << 16) | (std::uint32_t{b[1]} << 8) | std::uint32_t{b[2]};
  text[0] = kBase64Alphabet[(v >> 18) & 63];
  text[1] = kBase64Alphabet[(v >> 12) & 63];
  text[2] = kBase64Alphabet[(v >> 6) & 63];
  text[3] = kBase64Alphabet[v & 63];
}

// zlib's compress2 of `bytes` bytes into `out` (room for compressBound(bytes)); returns the compressed size.
// zlib cannot refuse a buffer of compressBound bytes (InternalError if it does).
std::size_t compress_block(const unsigned char* data, std::size_t bytes, unsigned char* out) {
  uLongf size = compressBound(static_cast<uLong>(bytes));
  const int status = compress2(out, &size, data, static_cast<uLong>(bytes), kVtkZlibLevel);
  RADWALK_CHECK_EQ(status, Z_OK);
  return static_cast<std::size_t>(size);
}

}  // namespace

void Base64Writer::flush_text() {
  out_.write(text_, static_cast<std::streamsize>(text_size_));
  text_size_ = 0;
}

void Base64Writer::put(const void* data, std::size_t bytes) {
  const auto* b = static_cast<const unsigned char*>(data);
  // Complete a pending triple first.
  while (pending_count_ > 0 && pending_count_ < 3 && bytes > 0) {
    pending_[pending_count_++] = *b++;
    --bytes;
  }
  if (pending_count_ == 3) {
    if (text_size_ + 4 > sizeof text_) flush_text();
    encode_triple(pending_, text_ + text_size_);
    text_size_ += 4;
    pending_count_ = 0;
  }
  for (; bytes >= 3; bytes -= 3, b += 3) {
    if (text_size_ + 4 > sizeof text_) flush_text();
    encode_triple(b, text_ + text_size_);
    text_size_ += 4;
  }
  for (; bytes > 0; --bytes) pending_[pending_count_++] = *b++;
}

void Base64Writer::finish() {
  if (pending_count_ > 0) {
    const unsigned char last[3] = {pending_[0], pending_count_ > 1 ? pending_[1] : static_cast<unsigned char>(0), 0};
    if (text_size_ + 4 > sizeof text_) flush_text();
    encode_triple(last, text_ + text_size_);
    // 1 byte: 2 characters and "=="; 2 bytes: 3 characters and "=".
    for (int k = pending_count_ + 1; k < 4; ++k) text_[text_size_ + static_cast<std::size_t>(k)] = '=';
    text_size_ += 4;
    pending_count_ = 0;
  }
  flush_text();
}

void write_vtk_compressed_base64(std::ostream& out, const void* data, std::size_t bytes) {
  const auto* b = static_cast<const unsigned char*>(data);
  const std::size_t blocks = (bytes + kVtkBlockBytes - 1) / kVtkBlockBytes;
  // One buffer with a slot of compressBound(block) for each block: a single allocation, returned to the system
  // when freed (thousands of small ones per array fragmented the heap: 1.3 GB stayed resident at 10^7 patches),
  // and only the pages a block's compressed bytes reach are ever touched.
  const std::size_t slot = compressBound(static_cast<uLong>(kVtkBlockBytes));
  std::unique_ptr<unsigned char[]> compressed(new unsigned char[blocks * slot]);
  std::vector<std::uint64_t> header(3 + blocks);
  header[0] = blocks;
  header[1] = kVtkBlockBytes;
  header[2] = bytes % kVtkBlockBytes;
  parallel_for(
      blocks,
      [&](std::size_t k) {
        const std::size_t begin = k * kVtkBlockBytes;
        header[3 + k] = compress_block(b + begin, std::min(kVtkBlockBytes, bytes - begin), compressed.get() + k * slot);
      },
      4);
  Base64Writer text(out);
  text.put(header.data(), header.size() * sizeof(std::uint64_t));
  text.finish();
  for (std::size_t k = 0; k < blocks; ++k) text.put(compressed.get() + k * slot, header[3 + k]);
  text.finish();
}

}  // namespace radwalk
