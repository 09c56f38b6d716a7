#pragma once
// The content of an inline binary DataArray of a VTK XML file (format="binary") written with
// header_type="UInt64" and compressor="vtkZLibDataCompressor": the array's bytes cut into blocks of
// kVtkBlockBytes (the last one possibly shorter), each compressed by zlib on its own, then
//   base64(header) base64(block 0 block 1 ... block n-1)
// where header = [n, kVtkBlockBytes, bytes of the last block if shorter (else 0), compressed size of block 0,
// ..., of block n-1], each a little-endian UInt64, and the two base64 texts are encoded separately (each with its
// own '=' padding), which is how VTK's reader (vtkXMLDataParser) expects them: it decodes the header, restarts
// the decoder and finds block k at the sum of the compressed sizes before it. An empty array is the header
// [0, kVtkBlockBytes, 0] alone.
//
// The blocks are compressed in parallel (core/parallel.h) and held compressed until the header, which needs their
// sizes, is written; the base64 text is written as it is encoded, never held whole. zlib's output depends only on
// the bytes and the level, so the file does not depend on the thread count.
#include <cstddef>
#include <iosfwd>

namespace radwalk {

inline constexpr std::size_t kVtkBlockBytes = 32768;  // VTK's own block size
inline constexpr int kVtkZlibLevel = 5;               // vtkZLibDataCompressor's default level

// Writes the content described above for the `bytes` bytes at `data` (host order: this writer declares
// byte_order="LittleEndian" and is built only where that holds).
void write_vtk_compressed_base64(std::ostream& out, const void* data, std::size_t bytes);

// Base64 (RFC 4648, with '=' padding) of a byte stream given in pieces, written to `out` as it goes.
class Base64Writer {
 public:
  explicit Base64Writer(std::ostream& out) : out_(out) {}
  Base64Writer(const Base64Writer&) = delete;
  Base64Writer& operator=(const Base64Writer&) = delete;
  ~Base64Writer() = default;  // finish() must be called: a destructor must not write

  void put(const void* data, std::size_t bytes);
  // Encodes the last 1 or 2 pending bytes with padding and writes everything out; the writer can start again.
  void finish();

 private:
  void flush_text();
  std::ostream& out_;
  unsigned char pending_[3] = {0, 0, 0};
  int pending_count_ = 0;
  char text_[4096];
  std::size_t text_size_ = 0;
};

}  // namespace radwalk
