#include "formfactor/npz.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string_view>
#include <vector>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/input_file.h"
#include "formfactor/form_factor_rows.h"
#include "formfactor/matrix_market.h"

namespace radwalk {
namespace {

constexpr std::uint32_t kLocalSig = 0x04034b50, kCentralSig = 0x02014b50, kEnd64Sig = 0x06064b50,
                        kLocator64Sig = 0x07064b50, kEndSig = 0x06054b50;
constexpr std::uint16_t kVersion = 45;   // ZIP64
constexpr std::uint16_t kDosDate = 0x21;  // 1980-01-01: the file does not depend on when it was written
constexpr std::uint16_t kZip64Extra = 0x0001, kPadExtra = 0x5250;  // "RP": padding, ignored by readers
constexpr std::size_t kAlign = 64;

// ---- writing -------------------------------------------------------------------------------------------------

void put16(std::string& s, std::uint16_t v) {
  for (int k = 0; k < 2; ++k) s.push_back(char((v >> (8 * k)) & 0xff));
}
void put32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(char((v >> (8 * k)) & 0xff));
}
void put64(std::string& s, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) s.push_back(char((v >> (8 * k)) & 0xff));
}

// The .npy header (version 1.0) of an array of `descr` and shape text `shape` ("(5,)", "()"), padded with
// spaces and a newline so that header plus data offset is a multiple of 64.
std::string npy_header(const std::string& descr, const std::string& shape) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': " + shape + ", }";
  std::string h = "\x93NUMPY";
  h.push_back(char(1));
  h.push_back(char(0));
  const std::size_t total = (10 + dict.size() + 1 + kAlign - 1) / kAlign * kAlign;
  dict.append(total - 10 - dict.size() - 1, ' ');
  dict.push_back('\n');
  put16(h, std::uint16_t(dict.size()));
  return h + dict;
}

// One member: its name, .npy header and raw array bytes (not owned).
struct Member {
  std::string name, header;
  const char* data = nullptr;
  std::uint64_t bytes = 0;
  std::uint32_t crc = 0;
  std::uint64_t offset = 0;  // of its local header in the file
};

std::uint32_t crc_of(std::uint32_t crc, const char* p, std::uint64_t n) {
  while (n > 0) {
    const auto step = static_cast<uInt>(std::min<std::uint64_t>(n, std::uint64_t{1} << 30));
    crc = static_cast<std::uint32_t>(crc32(crc, reinterpret_cast<const Bytef*>(p), step));
    p += step;
    n -= step;
  }
  return crc;
}

void write_members(std::ostream& os, std::vector<Member>& members) {
  std::uint64_t at = 0;
  const auto emit = [&](const std::string& s) {
    os.write(s.data(), std::streamsize(s.size()));
    at += s.size();
  };
  for (Member& m : members) {
    m.offset = at;
    const std::uint64_t size = m.header.size() + m.bytes;
    m.crc = crc_of(crc_of(0, m.header.data(), m.header.size()), m.data, m.bytes);
    std::string h;
    put32(h, kLocalSig);
    put16(h, kVersion);
    put16(h, 0);  // flags
    put16(h, 0);  // stored
    put16(h, 0);  // time
    put16(h, kDosDate);
    put32(h, m.crc);
    put32(h, 0xffffffffu);  // sizes in the ZIP64 extra field
    put32(h, 0xffffffffu);
    put16(h, std::uint16_t(m.name.size()));
    // Extra: ZIP64 sizes (4 + 16 bytes), then padding (4 + pad bytes) so the member data starts aligned.
    const std::uint64_t before_pad = at + 30 + m.name.size() + 20 + 4;
    const std::uint64_t pad = (kAlign - before_pad % kAlign) % kAlign;
    put16(h, std::uint16_t(20 + 4 + pad));
    h += m.name;
    put16(h, kZip64Extra);
    put16(h, 16);
    put64(h, size);
    put64(h, size);
    put16(h, kPadExtra);
    put16(h, std::uint16_t(pad));
    h.append(pad, '\0');
    emit(h);
    emit(m.header);
    os.write(m.data, std::streamsize(m.bytes));
    at += m.bytes;
  }
  const std::uint64_t directory = at;
  for (const Member& m : members) {
    const std::uint64_t size = m.header.size() + m.bytes;
    std::string c;
    put32(c, kCentralSig);
    put16(c, kVersion);  // made by
    put16(c, kVersion);  // needed
    put16(c, 0);
    put16(c, 0);
    put16(c, 0);
    put16(c, kDosDate);
    put32(c, m.crc);
    put32(c, 0xffffffffu);
    put32(c, 0xffffffffu);
    put16(c, std::uint16_t(m.name.size()));
    put16(c, 28);  // ZIP64 extra: sizes and offset
    put16(c, 0);   // comment
    put16(c, 0);   // disk
    put16(c, 0);   // internal attributes
    put32(c, 0);   // external attributes
    put32(c, 0xffffffffu);
    c += m.name;
    put16(c, kZip64Extra);
    put16(c, 24);
    put64(c, size);
    put64(c, size);
    put64(c, m.offset);
    emit(c);
  }
  const std::uint64_t directory_bytes = at - directory, end64 = at;
  std::string e;
  put32(e, kEnd64Sig);
  put64(e, 44);
  put16(e, kVersion);
  put16(e, kVersion);
  put32(e, 0);
  put32(e, 0);
  put64(e, members.size());
  put64(e, members.size());
  put64(e, directory_bytes);
  put64(e, directory);
  put32(e, kLocator64Sig);
  put32(e, 0);
  put64(e, end64);
  put32(e, 1);
  put32(e, kEndSig);
  put16(e, 0);
  put16(e, 0);
  put16(e, std::uint16_t(members.size()));
  put16(e, std::uint16_t(members.size()));
  put32(e, 0xffffffffu);
  put32(e, 0xffffffffu);
  put16(e, 0);
  emit(e);
}

// ---- reading -------------------------------------------------------------------------------------------------

// The file, mapped read-only for the reader's lifetime.
class MappedFile {
 public:
  MappedFile(const std::string& path, std::uint64_t size) : size_(size) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw InputError(locate(path, 0, -1, "cannot open the .npz file"));
    if (size_ > 0) {
      void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (p == MAP_FAILED) {
        ::close(fd);
        throw InputError(locate(path, 0, -1, "cannot map the .npz file into memory"));
      }
      ::madvise(p, size_, MADV_SEQUENTIAL);
      data_ = static_cast<const char*>(p);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return data_; }
  std::uint64_t size() const { return size_; }

 private:
  const char* data_ = nullptr;
  std::uint64_t size_ = 0;
};

// Drops the whole pages inside [begin, end) of the mapping from the process's resident memory (madvise
// MADV_DONTNEED), once the reader has copied them, so that the mapped file and F are not both resident: the peak of
// reading F is about F's own size. A later read of those pages faults them in again from the file (the mapping is
// private and never written), so this changes no value.
void release_mapped(const char* begin, const char* end) {
  const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t b = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) / page * page;
  const std::uintptr_t e = reinterpret_cast<std::uintptr_t>(end) / page * page;
  if (e > b) ::madvise(reinterpret_cast<void*>(b), e - b, MADV_DONTNEED);
}

// A parsed .npy member: its dtype, shape and the bytes of its array inside the mapping.
struct Array {
  std::string name, descr;
  std::vector<std::uint64_t> shape;
  const char* data = nullptr;
  std::uint64_t bytes = 0;
};

class Reader {
 public:
  Reader(const std::string& path, const MappedFile& file) : path_(path), p_(file.data()), n_(file.size()) {}

  InputError error(const std::string& what) const { return InputError(locate(path_, 0, -1, what)); }

  // Little-endian integer of `width` bytes at `at`, which must lie inside the file.
  std::uint64_t get(std::uint64_t at, int width, const char* what) const {
    if (at > n_ || std::uint64_t(width) > n_ - at)
      throw error(std::string("truncated .npz file (") + what + " past the end of the file)");
    std::uint64_t v = 0;
    for (int k = width - 1; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(p_[at + std::uint64_t(k)]);
    return v;
  }

  // The zip members as (name, data offset, size): end records, central directory, local headers.
  std::vector<Array> members() const {
    // End of central directory: the last 22+ bytes (a comment of up to 65535 bytes may follow it).
    if (n_ < 22) throw error("not a .npz (zip) file: too short, or truncated");
    std::uint64_t end = n_ - 22;
    const std::uint64_t lowest = n_ >= 22 + 65535 ? n_ - 22 - 65535 : 0;
    while (get(end, 4, "end record") != kEndSig) {
      if (end == lowest) throw error("not a .npz (zip) file: no end-of-directory record (truncated?)");
      --end;
    }
    std::uint64_t count = get(end + 10, 2, "end record"), dir_bytes = get(end + 12, 4, "end record"),
                  dir = get(end + 16, 4, "end record");
    if (end >= 20 && get(end - 20, 4, "ZIP64 locator") == kLocator64Sig) {
      const std::uint64_t e64 = get(end - 20 + 8, 8, "ZIP64 locator");
      if (get(e64, 4, "ZIP64 end record") != kEnd64Sig) throw error("bad ZIP64 end record (corrupt file)");
      count = get(e64 + 32, 8, "ZIP64 end record");
      dir_bytes = get(e64 + 40, 8, "ZIP64 end record");
      dir = get(e64 + 48, 8, "ZIP64 end record");
    }
    if (dir > n_ || dir_bytes > n_ - dir) throw error("truncated .npz file (central directory past the end)");
    if (count > dir_bytes / 46) throw error("corrupt .npz file (more members than its directory holds)");
    std::vector<Array> out;
    std::uint64_t at = dir;
    for (std::uint64_t k = 0; k < count; ++k) {
      if (get(at, 4, "central directory") != kCentralSig) throw error("corrupt .npz file (bad central directory)");
      const auto method = get(at + 10, 2, "central directory");
      std::uint64_t size = get(at + 24, 4, "central directory"), usize = get(at + 20, 4, "central directory");
      const std::uint64_t name_len = get(at + 28, 2, "central directory"),
                          extra_len = get(at + 30, 2, "central directory"),
                          comment_len = get(at + 32, 2, "central directory");
      std::uint64_t local = get(at + 42, 4, "central directory");
      if (at + 46 + name_len > n_) throw error("truncated .npz file (member name past the end)");
      Array a;
      a.name.assign(p_ + at + 46, name_len);
      // ZIP64 extra field: the 64-bit values of the fields that read 0xffffffff, in order.
      for (std::uint64_t x = at + 46 + name_len; x + 4 <= at + 46 + name_len + extra_len;) {
        const auto id = get(x, 2, "extra field"), len = get(x + 2, 2, "extra field");
        if (id == kZip64Extra) {
          std::uint64_t y = x + 4;
          if (usize == 0xffffffffu) usize = get(y, 8, "ZIP64 field"), y += 8;
          if (size == 0xffffffffu) size = get(y, 8, "ZIP64 field"), y += 8;
          if (local == 0xffffffffu) local = get(y, 8, "ZIP64 field"), y += 8;
        }
        x += 4 + len;
      }
      if (method != 0)
        throw error("member " + a.name + " is compressed (zip method " + std::to_string(method) +
                    "): radwalk maps F in place, save it with scipy.sparse.save_npz(path, F, compressed=False)");
      if (usize != size) throw error("corrupt .npz file (member " + a.name + " stored with two sizes)");
      if (get(local, 4, "local header") != kLocalSig)
        throw error("corrupt .npz file (bad local header of " + a.name + ")");
      const std::uint64_t begin =
          local + 30 + get(local + 26, 2, "local header") + get(local + 28, 2, "local header");
      if (begin > n_ || size > n_ - begin)
        throw error("truncated .npz file (member " + a.name + " ends past the end of the file)");
      a.data = p_ + begin;
      a.bytes = size;
      out.push_back(std::move(a));
      at += 46 + name_len + extra_len + comment_len;
    }
    return out;
  }

  // Parses member `m` as a .npy array (header checked; the data must hold the shape's bytes exactly).
  Array npy(Array m) const {
    const std::string what = "member " + m.name + ": ";
    if (m.bytes < 10 || std::memcmp(m.data, "\x93NUMPY", 6) != 0) throw error(what + "not a .npy array");
    const int major = static_cast<unsigned char>(m.data[6]);
    std::uint64_t hlen = 0, start = 0;
    if (major == 1) {
      hlen = static_cast<unsigned char>(m.data[8]) | std::uint64_t(static_cast<unsigned char>(m.data[9])) << 8;
      start = 10;
    } else if (major == 2 || major == 3) {
      if (m.bytes < 12) throw error(what + "truncated .npy header");
      for (int k = 3; k >= 0; --k) hlen = hlen << 8 | static_cast<unsigned char>(m.data[8 + k]);
      start = 12;
    } else {
      throw error(what + "unsupported .npy format version " + std::to_string(major));
    }
    if (hlen > m.bytes - start) throw error(what + "truncated .npy header");
    const std::string_view h(m.data + start, hlen);
    // descr
    const auto value_of = [&](std::string_view key) -> std::string_view {
      const std::size_t k = h.find(key);
      if (k == std::string_view::npos) throw error(what + "malformed .npy header (no " + std::string(key) + ")");
      std::size_t v = h.find(':', k + key.size());
      if (v == std::string_view::npos) throw error(what + "malformed .npy header");
      ++v;
      while (v < h.size() && h[v] == ' ') ++v;
      return h.substr(v);
    };
    std::string_view d = value_of("'descr'");
    if (d.empty() || (d[0] != '\'' && d[0] != '"')) throw error(what + "malformed .npy header (descr)");
    const std::size_t close = d.find(d[0], 1);
    if (close == std::string_view::npos) throw error(what + "malformed .npy header (descr)");
    m.descr = std::string(d.substr(1, close - 1));
    if (value_of("'fortran_order'").substr(0, 5) != "False") throw error(what + "Fortran-ordered arrays are not read");
    std::string_view s = value_of("'shape'");
    if (s.empty() || s[0] != '(') throw error(what + "malformed .npy header (shape)");
    std::size_t q = 1;
    while (true) {
      while (q < s.size() && (s[q] == ' ' || s[q] == ',')) ++q;
      if (q < s.size() && s[q] == ')') break;
      std::uint64_t v = 0;
      std::size_t digits = 0;
      while (q < s.size() && s[q] >= '0' && s[q] <= '9' && digits < 19) v = v * 10 + std::uint64_t(s[q++] - '0'), ++digits;
      if (digits == 0 || m.shape.size() >= 8) throw error(what + "malformed .npy header (shape)");
      m.shape.push_back(v);
    }
    m.data += start + hlen;
    m.bytes -= start + hlen;
    return m;
  }

 private:
  std::string path_;
  const char* p_;
  std::uint64_t n_;
};

std::uint64_t item_size(const std::string& descr) {
  if (descr == "<i4" || descr == "<f4") return 4;
  if (descr == "<i8" || descr == "<f8") return 8;
  return 0;
}

// Element k of an integer array of dtype '<i4' or '<i8' (little-endian host assumed: x86-64, aarch64).
std::int64_t int_at(const Array& a, std::uint64_t k) {
  if (a.descr == "<i4") {
    std::int32_t v;
    std::memcpy(&v, a.data + 4 * k, 4);
    return v;
  }
  std::int64_t v;
  std::memcpy(&v, a.data + 8 * k, 8);
  return v;
}

}  // namespace

void write_npz(const std::string& path, const SparseF& F, const std::string& run_id) {
  SparseF copy;
  const SparseF* G = &F;
  if (!F.isCompressed()) {  // an uncompressed Eigen matrix has gaps between rows; the file has none
    copy = F;
    copy.makeCompressed();
    G = &copy;
  }
  const auto nnz = static_cast<std::uint64_t>(G->nonZeros()), rows = static_cast<std::uint64_t>(G->rows());
  const std::int64_t shape[2] = {G->rows(), G->cols()};
  const std::string format = "csr";
  std::vector<Member> members;
  members.push_back({"indices.npy", npy_header("<i4", "(" + std::to_string(nnz) + ",)"),
                     reinterpret_cast<const char*>(G->innerIndexPtr()), 4 * nnz});
  members.push_back({"indptr.npy", npy_header("<i4", "(" + std::to_string(rows + 1) + ",)"),
                     reinterpret_cast<const char*>(G->outerIndexPtr()), 4 * (rows + 1)});
  members.push_back({"format.npy", npy_header("|S3", "()"), format.data(), 3});
  members.push_back({"shape.npy", npy_header("<i8", "(2,)"), reinterpret_cast<const char*>(shape), 16});
  members.push_back({"data.npy", npy_header("<f4", "(" + std::to_string(nnz) + ",)"),
                     reinterpret_cast<const char*>(G->valuePtr()), 4 * nnz});
  if (!run_id.empty())
    members.push_back({"run_id.npy", npy_header("|S" + std::to_string(run_id.size()), "()"), run_id.data(),
                       run_id.size()});
  write_atomically(path, [&](std::ostream& os) { write_members(os, members); });
}

SparseF read_npz(const std::string& path, std::size_t expected_n, RowBlocks* row_blocks) {
  const MappedFile file(path, input_file_size(path));  // refuses FIFOs, devices and files above kMaxInputBytes
  const Reader reader(path, file);
  const auto fail = [&](const std::string& what) { return reader.error(what); };
  Array indices, indptr, data, shape, format;
  for (Array& m : reader.members()) {
    Array* slot = m.name == "indices.npy" ? &indices
                  : m.name == "indptr.npy" ? &indptr
                  : m.name == "data.npy"   ? &data
                  : m.name == "shape.npy"  ? &shape
                  : m.name == "format.npy" ? &format
                                           : nullptr;
    if (slot) *slot = reader.npy(std::move(m));
  }
  for (const Array* a : {&indices, &indptr, &data, &shape, &format})
    if (a->data == nullptr)
      throw fail("not a scipy.sparse .npz file: no member " +
                 std::string(a == &indices  ? "indices.npy"
                             : a == &indptr ? "indptr.npy"
                             : a == &data   ? "data.npy"
                             : a == &shape  ? "shape.npy"
                                            : "format.npy"));
  // Each array: its dtype, one dimension (none for format), and exactly the bytes its shape needs.
  const auto check = [&](const Array& a, std::initializer_list<const char*> dtypes) {
    bool ok = false;
    std::string list;
    for (const char* d : dtypes) ok = ok || a.descr == d, list += (list.empty() ? "" : " or ") + std::string(d);
    if (!ok) throw fail("member " + a.name + " has dtype '" + a.descr + "', expected " + list);
    if (a.shape.size() != 1) throw fail("member " + a.name + " is not one-dimensional");
    const std::uint64_t size = item_size(a.descr);
    if (a.shape[0] > a.bytes / size || a.shape[0] * size != a.bytes)
      throw fail("member " + a.name + " holds " + std::to_string(a.bytes) + " bytes, not the " +
                 std::to_string(a.shape[0]) + " x " + std::to_string(size) + " its header declares (truncated?)");
  };
  // format: b'csr' or u'csr'
  std::string fmt;
  if (format.descr == "|S3" && format.shape.empty() && format.bytes == 3) {
    fmt.assign(format.data, 3);
  } else if (format.descr == "<U3" && format.shape.empty() && format.bytes == 12) {
    for (int k = 0; k < 3; ++k) fmt.push_back(format.data[4 * k]);
  }
  if (fmt != "csr") throw fail("member format.npy is not 'csr' (save F.tocsr())");
  check(shape, {"<i8", "<i4"});
  if (shape.shape[0] != 2) throw fail("member shape.npy does not hold two numbers");
  const std::int64_t rows = int_at(shape, 0), cols = int_at(shape, 1);
  if (rows != cols) throw fail("matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + ", not square");
  if (rows < 0 || std::uint64_t(rows) != expected_n)
    throw fail("matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + " but there are " +
               std::to_string(expected_n) + " patches");
  if (rows > std::numeric_limits<std::int32_t>::max())
    throw fail("matrix size " + std::to_string(rows) + " exceeds the 32-bit index range");
  check(indptr, {"<i4", "<i8"});
  check(indices, {"<i4", "<i8"});
  check(data, {"<f4", "<f8"});
  const auto N = std::uint64_t(rows);
  if (indptr.shape[0] != N + 1)
    throw fail("member indptr.npy has " + std::to_string(indptr.shape[0]) + " entries, expected N + 1 = " +
               std::to_string(N + 1));
  const std::uint64_t nnz = indices.shape[0];
  if (data.shape[0] != nnz)
    throw fail("members data.npy and indices.npy differ in length (" + std::to_string(data.shape[0]) + " and " +
               std::to_string(nnz) + ")");
  if (nnz > std::uint64_t(std::numeric_limits<std::int32_t>::max()))
    throw fail(std::to_string(nnz) + " non-zeros exceed the 32-bit index range");

  SparseF F(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  std::int32_t* outer = F.outerIndexPtr();
  if (int_at(indptr, 0) != 0) throw fail("indptr.npy[0] is " + std::to_string(int_at(indptr, 0)) + ", not 0");
  if (int_at(indptr, N) != std::int64_t(nnz))
    throw fail("indptr.npy[N] is " + std::to_string(int_at(indptr, N)) + ", not the " + std::to_string(nnz) +
               " non-zeros");
  for (std::uint64_t i = 0; i <= N; ++i) {
    const std::int64_t v = int_at(indptr, i);
    if (i > 0 && v < outer[i - 1])
      throw fail("indptr.npy decreases at row " + std::to_string(i - 1) + " (" + std::to_string(outer[i - 1]) +
                 " then " + std::to_string(v) + ")");
    if (v > std::int64_t(nnz)) throw fail("indptr.npy[" + std::to_string(i) + "] is past the non-zeros");
    outer[i] = static_cast<std::int32_t>(v);
  }
  // Over MPI with `row_blocks`: only this rank's block of rows (balanced by non-zeros) is checked and copied; the other
  // rows stay empty (form_factor_rows.h). The file is mapped, so the other rows are never read.
  distributed::Range mine{0, N};
  if (row_blocks && distributed::size() > 1) {
    *row_blocks = nonzero_row_blocks(outer, N);
    mine = own_rows(*row_blocks, N);
  }
  const std::int32_t base = outer[mine.begin];
  F.resizeNonZeros(outer[mine.end] - base);
  std::int32_t* inner = F.innerIndexPtr();
  float* value = F.valuePtr();
  // The mapped indices and values already copied are released every 2^22 non-zeros (16 to 32 MB of the file).
  const std::uint64_t index_width = item_size(indices.descr), value_width = item_size(data.descr);
  constexpr std::int64_t kReleaseStep = std::int64_t{1} << 22;
  std::int64_t released = base;
  for (std::uint64_t i = mine.begin; i < mine.end; ++i) {
    if (outer[i] - released >= kReleaseStep) {
      const auto from = std::uint64_t(released), to = std::uint64_t(outer[i]);
      release_mapped(indices.data + index_width * from, indices.data + index_width * to);
      release_mapped(data.data + value_width * from, data.data + value_width * to);
      released = outer[i];
    }
    double sum = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      const std::int64_t j = int_at(indices, std::uint64_t(k));
      if (j < 0 || std::uint64_t(j) >= N)
        throw fail("indices.npy[" + std::to_string(k) + "] (row " + std::to_string(i) + ") is " + std::to_string(j) +
                   ", out of range 0.." + std::to_string(N - 1));
      if (k > outer[i] && j <= inner[k - 1 - base])
        throw fail("columns of row " + std::to_string(i) + " are not strictly increasing (unsorted or duplicate; "
                   "call F.sum_duplicates() before saving)");
      inner[k - base] = static_cast<std::int32_t>(j);
      double v;
      if (data.descr == "<f4") {
        float f;
        std::memcpy(&f, data.data + 4 * std::uint64_t(k), 4);
        v = f;
      } else {
        std::memcpy(&v, data.data + 8 * std::uint64_t(k), 8);
      }
      if (!std::isfinite(v) || v < 0.0 || v > 1.0)
        throw fail("data.npy[" + std::to_string(k) + "] (row " + std::to_string(i) + ", column " +
                   std::to_string(j) + ") is " + std::to_string(v) + ", not in [0, 1]");
      value[k - base] = static_cast<float>(v);
      sum += value[k - base];
    }
    if (sum > kMaxRowSum)
      throw fail("row " + std::to_string(i) + " sums to " + std::to_string(sum) +
                 ", above 1 + 1e-6 (a form-factor row sums to at most 1)");
  }
  if (mine.size() < N) {
    // The own rows moved to the front of the arrays; the rows before them empty, those after them too.
    const std::int32_t end = outer[mine.end];
    for (std::uint64_t i = 0; i <= N; ++i) outer[i] = i <= mine.begin ? 0 : i >= mine.end ? end - base : outer[i] - base;
  }
  return F;
}

}  // namespace radwalk
