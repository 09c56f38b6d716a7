#include "formfactor/npz.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <ostream>
#include <string_view>
#include <vector>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/excerpt.h"
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
//
// The file is read with pread in pieces (core/input_file.h), never mapped: a mapped file truncated by another
// process while it is read kills the reader with SIGBUS, a short read is an error message. Every rule below that
// Python's zipfile or numpy.load applies is applied too (and a little more), so that whatever radwalk accepts,
// scipy.sparse.load_npz reads as the same matrix (tests/python/test_npz_mutations.py checks it on mutated files).

constexpr std::size_t kChunkBytes = std::size_t{1} << 20;  // bytes read at a time: the reader's only buffer
constexpr std::uint64_t kMaxNpyHeader = 10000;              // numpy.load's limit (max_header_size)
constexpr unsigned kMaxZipVersion = 63;                     // zipfile refuses members that need a later version
constexpr std::uint64_t kRefusedFlags = 0x1 | 0x20 | 0x40;  // encrypted, patched, strongly encrypted

// Little-endian integer of `width` bytes at p.
std::uint64_t le(const char* p, int width) {
  std::uint64_t v = 0;
  for (int k = width - 1; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(p[k]);
  return v;
}

// A member the reader uses: where its bytes are in the file, its CRC-32, and what its .npy header says.
struct Array {
  std::string name, descr;
  std::vector<std::uint64_t> shape;
  bool found = false;
  std::uint64_t begin = 0, bytes = 0;           // the member: offset in the file and size (.npy header and array)
  std::uint32_t crc = 0;                        // the member's CRC-32, from the central directory
  std::uint64_t data = 0, data_bytes = 0;       // the array after the .npy header: offset in the file and size
  std::uint32_t header_crc = 0;                 // the CRC-32 of the bytes before the array (magic, version, header)
};

// The .npy header dictionary as numpy reads it (ast.literal_eval, then its checks on the keys and values), in a
// strict subset: {'descr': STRING, 'fortran_order': BOOL, 'shape': TUPLE} with each key once in any order, strings
// in ' or " without escapes or prefixes, shape a tuple of unsigned decimal integers without leading zeros ("(5,)":
// "(5)" is an integer to Python, not a tuple), blanks (space, tab, newline) between tokens, an optional trailing
// comma, nothing but blanks after the closing brace. Whatever numpy refuses is refused; so is a little that it
// reads but nobody writes (comments, escapes, Python 2 longs "5L").
class NpyDict {
 public:
  NpyDict(std::string_view text, std::function<InputError(const std::string&)> fail)
      : s_(text), fail_(std::move(fail)) {}

  void parse(Array& a) {
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t')) ++p_;
    expect('{');
    bool descr = false, fortran = false, shape = false, fortran_order = false;
    while (!peek('}')) {
      const std::string key = string();
      expect(':');
      if (key == "descr" && !descr) {
        a.descr = string();
        descr = true;
      } else if (key == "fortran_order" && !fortran) {
        fortran_order = boolean();
        fortran = true;
      } else if (key == "shape" && !shape) {
        a.shape = tuple();
        shape = true;
      } else {
        throw malformed("key '" + excerpt(key) + "' unknown or repeated");
      }
      if (!peek('}')) expect(',');
    }
    expect('}');
    blanks();
    if (p_ != s_.size()) throw malformed("text after the dictionary");
    if (!descr || !fortran || !shape) throw malformed("it needs the keys descr, fortran_order and shape");
    if (fortran_order) throw fail_("Fortran-ordered arrays are not read");
  }

 private:
  InputError malformed(const std::string& what) const { return fail_("malformed .npy header (" + what + ")"); }
  void blanks() {
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t' || s_[p_] == '\n')) ++p_;
  }
  bool peek(char c) {
    blanks();
    return p_ < s_.size() && s_[p_] == c;
  }
  void expect(char c) {
    if (!peek(c)) throw malformed(std::string("expected '") + c + "'");
    ++p_;
  }
  std::string string() {
    blanks();
    if (p_ >= s_.size() || (s_[p_] != '\'' && s_[p_] != '"')) throw malformed("expected a string");
    const char quote = s_[p_++];
    const std::size_t start = p_;
    while (p_ < s_.size() && s_[p_] != quote) {
      if (s_[p_] == '\\' || s_[p_] == '\n') throw malformed("escape or line break in a string");
      ++p_;
    }
    if (p_ >= s_.size()) throw malformed("unterminated string");
    return std::string(s_.substr(start, p_++ - start));
  }
  static bool identifier_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  }
  bool boolean() {
    blanks();
    for (const auto& [word, value] : {std::pair<std::string_view, bool>{"True", true}, {"False", false}})
      if (s_.substr(p_, word.size()) == word &&
          (p_ + word.size() == s_.size() || !identifier_char(s_[p_ + word.size()]))) {
        p_ += word.size();
        return value;
      }
    throw malformed("fortran_order is not True or False");
  }
  std::uint64_t integer() {
    blanks();
    std::uint64_t v = 0;
    std::size_t digits = 0;
    const std::size_t start = p_;
    while (p_ < s_.size() && s_[p_] >= '0' && s_[p_] <= '9') {
      if (++digits > 18) throw malformed("shape entry too large");
      v = v * 10 + std::uint64_t(s_[p_++] - '0');
    }
    const bool glued = p_ < s_.size() && (identifier_char(s_[p_]) || s_[p_] == '.');  // 5L, 5.0, 5e3
    if (digits == 0 || (digits > 1 && s_[start] == '0') || glued)
      throw malformed("shape");
    return v;
  }
  std::vector<std::uint64_t> tuple() {
    expect('(');
    std::vector<std::uint64_t> shape;
    if (peek(')')) return ++p_, shape;
    shape.push_back(integer());
    expect(',');  // a one-element tuple needs its comma
    while (!peek(')')) {
      if (shape.size() >= 8) throw malformed("shape has more than 8 dimensions");
      shape.push_back(integer());
      if (!peek(')')) expect(',');
    }
    ++p_;
    return shape;
  }

  std::string_view s_;
  std::size_t p_ = 0;
  std::function<InputError(const std::string&)> fail_;
};

class Reader {
 public:
  explicit Reader(const InputFileReader& file) : file_(file), n_(file.size()) {}

  InputError error(const std::string& what) const { return InputError(locate(file_.path(), 0, -1, what)); }

  // The n bytes at `at` (records and headers, at most 64 KiB + 22); a range past the end of the file is refused.
  std::string bytes(std::uint64_t at, std::uint64_t n, const char* what) const {
    if (at > n_ || n > n_ - at)
      throw error(std::string("truncated .npz file (") + what + " past the end of the file)");
    std::string s(static_cast<std::size_t>(n), '\0');
    if (n > 0) file_.read_at(at, s.data(), s.size());
    return s;
  }

  // Finds the members through the end record and the central directory and checks their local headers; slot(name)
  // says where a member goes (nullptr: ignored; a later member of the same name replaces an earlier one, as in
  // zipfile). Reads only records: O(members) small reads, nothing proportional to a declared size.
  void read_directory(const std::function<Array*(const std::string&)>& slot) const {
    if (n_ < 22) throw error("not a .npz (zip) file: too short, or truncated");
    if (bytes(0, 4, "first header") != std::string("PK\x03\x04", 4))
      throw error("not a .npz (zip) file: it does not start with a zip member");
    // End record: the last 22 bytes when there is no archive comment, else the last signature in the last
    // 64 KiB + 22 bytes (as zipfile finds it), which must be followed by a whole record.
    const std::uint64_t tail_at = n_ > 22 + 65535 ? n_ - 22 - 65535 : 0;
    const std::string tail = bytes(tail_at, n_ - tail_at, "end record");
    const std::string end_sig("PK\x05\x06", 4);
    std::size_t e = tail.size() - 22;
    if (tail.compare(e, 4, end_sig) != 0 || tail[e + 20] != 0 || tail[e + 21] != 0) {
      e = tail.rfind(end_sig);
      if (e == std::string::npos) throw error("not a .npz (zip) file: no end-of-directory record (truncated?)");
      if (e + 22 > tail.size()) throw error("not a .npz (zip) file: truncated end-of-directory record");
    }
    const std::uint64_t end = tail_at + e;
    std::uint64_t count = le(tail.data() + e + 10, 2), dir_bytes = le(tail.data() + e + 12, 4),
                  dir = le(tail.data() + e + 16, 4), dir_end = end;
    // ZIP64: a locator just before the end record, and the ZIP64 end record (56 bytes) just before it.
    if (end >= 20) {
      const std::string loc = bytes(end - 20, 20, "ZIP64 locator");
      if (le(loc.data(), 4) == kLocator64Sig) {
        if (le(loc.data() + 4, 4) != 0 || le(loc.data() + 16, 4) > 1)
          throw error("a zip archive split over several disks is not read");
        if (end < 76 || le(loc.data() + 8, 8) != end - 76)
          throw error("corrupt .npz file (the ZIP64 end record is not just before its locator)");
        const std::string e64 = bytes(end - 76, 56, "ZIP64 end record");
        if (le(e64.data(), 4) != kEnd64Sig) throw error("bad ZIP64 end record (corrupt file)");
        count = le(e64.data() + 32, 8);
        dir_bytes = le(e64.data() + 40, 8);
        dir = le(e64.data() + 48, 8);
        dir_end = end - 76;
      }
    }
    // zipfile takes a directory that does not end where the end records start as data prepended to the archive
    // and shifts every offset: refused here, so that both read the same bytes.
    if (dir > dir_end || dir_bytes != dir_end - dir)
      throw error("corrupt .npz file (the central directory does not end where the end record starts)");
    std::uint64_t at = dir, entries = 0;
    while (at < dir_end) {
      if (dir_end - at < 46) throw error("corrupt .npz file (truncated central directory)");
      const std::string c = bytes(at, 46, "central directory");
      const char* h = c.data();
      if (le(h, 4) != kCentralSig) throw error("corrupt .npz file (bad central directory)");
      const auto needed = static_cast<unsigned char>(h[6]);
      const std::uint64_t flags = le(h + 8, 2), method = le(h + 10, 2), name_len = le(h + 28, 2),
                          extra_len = le(h + 30, 2), comment_len = le(h + 32, 2);
      const auto crc = static_cast<std::uint32_t>(le(h + 16, 4));
      std::uint64_t packed = le(h + 20, 4), size = le(h + 24, 4), local = le(h + 42, 4);
      const std::uint64_t entry_bytes = 46 + name_len + extra_len + comment_len;
      if (entry_bytes > dir_end - at) throw error("corrupt .npz file (a directory entry past the directory's end)");
      const std::string rest = bytes(at + 46, name_len + extra_len, "central directory");
      const std::string name = rest.substr(0, name_len);
      for (const char ch : name)
        if (ch < 0x20 || ch >= 0x7f)
          throw error("corrupt .npz file (member name '" + excerpt(name) + "' is not printable ASCII)");
      // Extra fields; ZIP64's holds the 64-bit values of the fields that read 0xffffffff, in this order.
      for (std::size_t x = name_len; rest.size() - x >= 4;) {
        const std::uint64_t id = le(rest.data() + x, 2), len = le(rest.data() + x + 2, 2);
        if (len > rest.size() - x - 4)
          throw error("corrupt .npz file (extra field of " + excerpt(name) + " past its end)");
        std::size_t y = x + 4;
        const std::size_t stop = y + len;
        for (std::uint64_t* field : {&size, &packed, &local}) {
          if (id != kZip64Extra || *field != 0xffffffffu) continue;
          if (stop - y < 8) throw error("corrupt .npz file (ZIP64 field of " + excerpt(name) + " missing)");
          *field = le(rest.data() + y, 8);
          y += 8;
        }
        x = stop;
      }
      if (needed > kMaxZipVersion)
        throw error("member " + excerpt(name) + " needs zip version " + std::to_string(needed / 10) + "." +
                    std::to_string(needed % 10) + " (corrupt file?)");
      at += entry_bytes;
      ++entries;
      Array* a = slot(name);
      if (a == nullptr) continue;
      if (flags & kRefusedFlags)
        throw error("member " + name + " is encrypted or patched (zip flags " + std::to_string(flags) + ")");
      if (method != 0)
        throw error("member " + name + " is compressed (zip method " + std::to_string(method) +
                    "): radwalk reads F in place, save it with scipy.sparse.save_npz(path, F, compressed=False)");
      if (packed != size) throw error("corrupt .npz file (member " + name + " stored with two sizes)");
      const std::string lh = bytes(local, 30, "local header");
      if (le(lh.data(), 4) != kLocalSig) throw error("corrupt .npz file (bad local header of " + name + ")");
      const std::uint64_t local_name = le(lh.data() + 26, 2), local_extra = le(lh.data() + 28, 2);
      if (bytes(local + 30, local_name, "local header") != name)
        throw error("corrupt .npz file (member " + name + " has another name in its local header)");
      const std::uint64_t begin = local + 30 + local_name + local_extra;
      if (begin > n_ || size > n_ - begin)
        throw error("truncated .npz file (member " + name + " ends past the end of the file)");
      a->name = name;
      a->found = true;
      a->begin = begin;
      a->bytes = size;
      a->crc = crc;
    }
    if (entries != count)
      throw error("corrupt .npz file (the end record counts " + std::to_string(count) + " members, the directory " +
                  "holds " + std::to_string(entries) + ")");
  }

  // Reads member a's .npy header (version 1.0, 2.0 or 3.0, at most kMaxNpyHeader bytes): its descr and shape, and
  // where its array starts.
  void npy(Array& a) const {
    const std::string what = "member " + a.name + ": ";
    if (a.bytes < 10) throw error(what + "not a .npy array");
    const std::string pre = bytes(a.begin, std::min<std::uint64_t>(a.bytes, 12), "member");
    if (pre.compare(0, 6, "\x93NUMPY") != 0) throw error(what + "not a .npy array");
    const int major = static_cast<unsigned char>(pre[6]), minor = static_cast<unsigned char>(pre[7]);
    if (major < 1 || major > 3 || minor != 0)
      throw error(what + "unsupported .npy format version " + std::to_string(major) + "." + std::to_string(minor));
    const std::uint64_t start = major == 1 ? 10 : 12;
    if (a.bytes < start) throw error(what + "truncated .npy header");
    const std::uint64_t header = le(pre.data() + 8, major == 1 ? 2 : 4);
    if (header > kMaxNpyHeader)
      throw error(what + ".npy header of " + std::to_string(header) + " bytes, above numpy's limit of 10000");
    if (header > a.bytes - start) throw error(what + "truncated .npy header");
    const std::string h = bytes(a.begin + start, header, ".npy header");
    NpyDict(h, [&](const std::string& w) { return error(what + w); }).parse(a);
    a.data = a.begin + start + header;
    a.data_bytes = a.bytes - start - header;
    a.header_crc = crc_of(crc_of(0, pre.data(), start), h.data(), header);
  }

  // Reads member a's array in pieces of at most kChunkBytes (whole items of `item` bytes, item > 0 dividing
  // a.data_bytes), calling visit(first item, bytes, items) on each; then the member's CRC-32 must be the one the
  // directory holds (so a value changed inside the file is refused even when it is a valid value).
  template <class Visit>
  void stream(const Array& a, std::uint64_t item, Visit&& visit) const {
    const std::uint64_t piece = kChunkBytes / item * item;
    std::vector<char> buffer(static_cast<std::size_t>(std::min(a.data_bytes, piece)));
    std::uint32_t crc = a.header_crc;
    for (std::uint64_t done = 0; done < a.data_bytes;) {
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), a.data_bytes - done));
      file_.read_at(a.data + done, buffer.data(), n);
      crc = crc_of(crc, buffer.data(), n);
      visit(done / item, static_cast<const char*>(buffer.data()), std::uint64_t(n) / item);
      done += n;
    }
    if (crc != a.crc)
      throw error("member " + a.name +
                  ": CRC-32 mismatch (the file is corrupt, or was changed after it was written)");
  }

 private:
  const InputFileReader& file_;
  std::uint64_t n_;
};

std::uint64_t item_size(const std::string& descr) {
  if (descr == "<i4" || descr == "<f4") return 4;
  if (descr == "<i8" || descr == "<f8") return 8;
  return 0;
}

// Element t of a piece of an integer array of dtype '<i4' or '<i8' (little-endian host assumed: x86-64, aarch64).
std::int64_t int_at(const char* p, std::uint64_t width, std::uint64_t t) {
  if (width == 4) {
    std::int32_t v;
    std::memcpy(&v, p + 4 * t, 4);
    return v;
  }
  std::int64_t v;
  std::memcpy(&v, p + 8 * t, 8);
  return v;
}

// Element t of a piece of a float array of dtype '<f4' or '<f8'.
double real_at(const char* p, std::uint64_t width, std::uint64_t t) {
  if (width == 4) {
    float f;
    std::memcpy(&f, p + 4 * t, 4);
    return f;
  }
  double v;
  std::memcpy(&v, p + 8 * t, 8);
  return v;
}

}  // namespace

void write_npz(const std::string& path, const SparseF& F, const std::string& run_id) {
  check_writable_form_factors(path, F);
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
  const InputFileReader file(path);  // refuses FIFOs, devices and files above kMaxInputBytes
  const Reader reader(file);
  const auto fail = [&](const std::string& what) { return reader.error(what); };

  // Step 1: the members, their .npy headers. numpy reads a member "data" (no .npy) for the key data, before
  // data.npy: such a name is refused rather than read differently.
  Array indices, indptr, data, shape, format;
  const std::pair<std::string, Array*> wanted[] = {
      {"indices.npy", &indices}, {"indptr.npy", &indptr}, {"data.npy", &data}, {"shape.npy", &shape},
      {"format.npy", &format}};
  reader.read_directory([&](const std::string& name) -> Array* {
    for (const auto& [member, slot] : wanted) {
      if (name == member) return slot;
      if (name + ".npy" == member) throw fail("member " + name + " (without .npy) would be read for " + member);
    }
    return nullptr;
  });
  for (const auto& [member, slot] : wanted)
    if (!slot->found) throw fail("not a scipy.sparse .npz file: no member " + member);
  for (const auto& [member, slot] : wanted) reader.npy(*slot);

  // Each array: its dtype, one dimension, and exactly the bytes its shape needs (so that every count below is
  // bounded by the bytes of the file).
  const auto check = [&](const Array& a, std::initializer_list<const char*> dtypes) {
    bool ok = false;
    std::string list;
    for (const char* d : dtypes) ok = ok || a.descr == d, list += (list.empty() ? "" : " or ") + std::string(d);
    if (!ok) throw fail("member " + a.name + " has dtype '" + excerpt(a.descr) + "', expected " + list);
    if (a.shape.size() != 1) throw fail("member " + a.name + " is not one-dimensional");
    const std::uint64_t size = item_size(a.descr);
    if (a.shape[0] > a.data_bytes / size || a.shape[0] * size != a.data_bytes)
      throw fail("member " + a.name + " holds " + std::to_string(a.data_bytes) + " bytes, not the " +
                 std::to_string(a.shape[0]) + " x " + std::to_string(size) + " its header declares (truncated?)");
  };

  // Step 2: format b'csr' or u'csr', shape (N, N) for the expected N.
  const bool bytes_csr = format.descr == "|S3" && format.shape.empty() && format.data_bytes == 3;
  const bool unicode_csr = format.descr == "<U3" && format.shape.empty() && format.data_bytes == 12;
  if (!bytes_csr && !unicode_csr) throw fail("member format.npy is not 'csr' (save F.tocsr())");
  reader.stream(format, format.data_bytes, [&](std::uint64_t, const char* p, std::uint64_t) {
    const std::string_view csr =
        bytes_csr ? std::string_view("csr", 3) : std::string_view("c\0\0\0s\0\0\0r\0\0\0", 12);  // UTF-32LE
    if (std::string_view(p, csr.size()) != csr) throw fail("member format.npy is not 'csr' (save F.tocsr())");
  });
  check(shape, {"<i8", "<i4"});
  if (shape.shape[0] != 2) throw fail("member shape.npy does not hold two numbers");
  const std::uint64_t shape_width = item_size(shape.descr);
  std::int64_t rows = 0, cols = 0;
  reader.stream(shape, shape_width, [&](std::uint64_t, const char* p, std::uint64_t) {
    rows = int_at(p, shape_width, 0);
    cols = int_at(p, shape_width, 1);
  });
  if (rows != cols) throw fail("matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + ", not square");
  if (rows < 0 || std::uint64_t(rows) != expected_n)
    throw fail("matrix is " + std::to_string(rows) + " x " + std::to_string(cols) + " but there are " +
               std::to_string(expected_n) + " patches");
  if (rows > std::numeric_limits<std::int32_t>::max())
    throw fail("matrix size " + std::to_string(rows) + " exceeds the 32-bit index range");

  // Step 3: the declared sizes, checked before anything proportional to them is allocated.
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
  if (nnz > N * N)
    throw fail(std::to_string(nnz) + " non-zeros declared, more than the " + std::to_string(N * N) + " entries of a " +
               std::to_string(N) + " x " + std::to_string(N) + " matrix");
  if (nnz > std::uint64_t(std::numeric_limits<std::int32_t>::max()))
    throw fail(std::to_string(nnz) + " non-zeros exceed the 32-bit index range");

  // Step 4: indptr, checked as it is read: from 0, never decreasing, no row longer than N, ending at nnz.
  SparseF F(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  std::int32_t* outer = F.outerIndexPtr();
  const std::uint64_t indptr_width = item_size(indptr.descr);
  reader.stream(indptr, indptr_width, [&](std::uint64_t first, const char* p, std::uint64_t count) {
    for (std::uint64_t t = 0; t < count; ++t) {
      const std::uint64_t i = first + t;
      const std::int64_t v = int_at(p, indptr_width, t);
      if (i == 0 && v != 0) throw fail("indptr.npy[0] is " + std::to_string(v) + ", not 0");
      if (i > 0 && v < outer[i - 1])
        throw fail("indptr.npy decreases at row " + std::to_string(i - 1) + " (" + std::to_string(outer[i - 1]) +
                   " then " + std::to_string(v) + ")");
      if (v > std::int64_t(nnz)) throw fail("indptr.npy[" + std::to_string(i) + "] is past the non-zeros");
      if (i > 0 && std::uint64_t(v - outer[i - 1]) > N)
        throw fail("row " + std::to_string(i - 1) + " has " + std::to_string(v - outer[i - 1]) +
                   " non-zeros, more than the " + std::to_string(N) + " columns");
      outer[i] = static_cast<std::int32_t>(v);
    }
  });
  if (outer[N] != std::int64_t(nnz))
    throw fail("indptr.npy[N] is " + std::to_string(outer[N]) + ", not the " + std::to_string(nnz) + " non-zeros");

  // Over MPI with `row_blocks`: only this rank's block of rows (balanced by non-zeros) is checked and kept; the
  // other rows stay empty (form_factor_rows.h). Every rank reads the whole members, for their CRC-32.
  distributed::Range mine{0, N};
  if (row_blocks && distributed::size() > 1) {
    *row_blocks = nonzero_row_blocks(outer, N);
    mine = own_rows(*row_blocks, N);
  }
  const std::int64_t base = outer[mine.begin], stop = outer[mine.end];
  F.resizeNonZeros(static_cast<Eigen::Index>(stop - base));  // at most nnz <= N^2, and nnz items are in the file
  std::int32_t* inner = F.innerIndexPtr();
  float* value = F.valuePtr();
  // The items [first, first + count) of a piece that fall in this rank's non-zeros, each with its row.
  const auto own_items = [&](std::uint64_t first, std::uint64_t count, auto&& use) {
    const auto from = std::max<std::int64_t>(base, std::int64_t(first));
    const auto to = std::min<std::int64_t>(stop, std::int64_t(first + count));
    if (from >= to) return;
    // The row of item `from`: the last row of this rank starting at or before it.
    auto i = std::uint64_t(std::upper_bound(outer + mine.begin, outer + mine.end + 1, from) - outer - 1);
    for (std::int64_t k = from; k < to; ++k) {
      while (outer[i + 1] <= k) ++i;
      use(k, i, std::uint64_t(k) - first);
    }
  };

  // Step 5: the column indices, in range; the values, finite and in [0, 1] (as float).
  const std::uint64_t index_width = item_size(indices.descr), value_width = item_size(data.descr);
  reader.stream(indices, index_width, [&](std::uint64_t first, const char* p, std::uint64_t count) {
    own_items(first, count, [&](std::int64_t k, std::uint64_t i, std::uint64_t t) {
      const std::int64_t j = int_at(p, index_width, t);
      if (j < 0 || std::uint64_t(j) >= N)
        throw fail("indices.npy[" + std::to_string(k) + "] (row " + std::to_string(i) + ") is " + std::to_string(j) +
                   ", out of range 0.." + std::to_string(N - 1));
      inner[k - base] = static_cast<std::int32_t>(j);
    });
  });
  reader.stream(data, value_width, [&](std::uint64_t first, const char* p, std::uint64_t count) {
    own_items(first, count, [&](std::int64_t k, std::uint64_t i, std::uint64_t t) {
      const double v = real_at(p, value_width, t);
      if (!std::isfinite(v) || v < 0.0 || v > 1.0)
        throw fail("data.npy[" + std::to_string(k) + "] (row " + std::to_string(i) + ", column " +
                   std::to_string(inner[k - base]) + ") is " + number_text(v) + ", not in [0, 1]");
      value[k - base] = static_cast<float>(v);
    });
  });
  file.check_unchanged();

  // Step 6: each row's columns strictly increasing, its sum at most kMaxRowSum.
  for (std::uint64_t i = mine.begin; i < mine.end; ++i) {
    double sum = 0;
    for (std::int64_t k = outer[i]; k < outer[i + 1]; ++k) {
      if (k > outer[i] && inner[k - base] <= inner[k - 1 - base])
        throw fail("columns of row " + std::to_string(i) + " are not strictly increasing (unsorted or duplicate; "
                   "call F.sum_duplicates() before saving)");
      sum += value[k - base];
    }
    if (sum > kMaxRowSum)
      throw fail("row " + std::to_string(i) + " sums to " + std::to_string(sum) +
                 ", above 1 + 1e-3 (a form-factor row sums to at most 1)");
  }
  if (mine.size() < N) {
    // The own rows moved to the front of the arrays; the rows before them empty, those after them too.
    const std::int32_t end = outer[mine.end];
    for (std::uint64_t i = 0; i <= N; ++i)
      outer[i] = i <= mine.begin ? 0 : i >= mine.end ? end - std::int32_t(base) : outer[i] - std::int32_t(base);
  }
  return F;
}

}  // namespace radwalk
