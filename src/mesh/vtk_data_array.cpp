#include "mesh/vtk_data_array.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <string_view>

#include <zlib.h>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/text_scan.h"

namespace radwalk {
namespace {

// A numeric VTK type: its size in bytes, whether it is floating point, and the range of its values.
struct NumericType {
  int size = 0;
  bool real = false;
  bool is_signed = false;
};

NumericType numeric_type(const std::string& type) {
  if (type == "Int8") return {1, false, true};
  if (type == "UInt8") return {1, false, false};
  if (type == "Int16") return {2, false, true};
  if (type == "UInt16") return {2, false, false};
  if (type == "Int32") return {4, false, true};
  if (type == "UInt32") return {4, false, false};
  if (type == "Int64") return {8, false, true};
  if (type == "UInt64") return {8, false, false};
  if (type == "Float32") return {4, true, true};
  if (type == "Float64") return {8, true, true};
  return {};
}

[[noreturn]] void refuse(const std::string& path, const VtpArray& array, const std::string& what) {
  throw InputError(locate(path, array.line, -1, array_label(array) + ": " + what));
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// The bytes of a binary or appended array, read as far as asked: raw bytes, or base64 text decoded four
// characters at a time (white space between characters skipped; '=' only as the padding of a group).
class ByteSource {
 public:
  ByteSource(const std::string& path, const VtpArray& array, std::string_view data, bool base64)
      : path_(path), array_(array), data_(data), base64_(base64) {}

  // At least as many bytes as are left to read.
  std::size_t bound() const {
    const std::size_t left = data_.size() - at_;
    return base64_ ? left / 4 * 3 + pending_size_ : left;
  }

  // Appends the next n bytes to `out`, or refuses the array (its data end first).
  void take(std::size_t n, std::string& out) {
    if (n > bound()) truncated(n);
    if (!base64_) {
      out.append(data_.data() + at_, n);
      at_ += n;
      return;
    }
    out.reserve(out.size() + n);
    for (std::size_t k = 0; k < n; ++k) {
      if (pending_at_ == pending_size_ && !next_group()) truncated(n);
      out.push_back(static_cast<char>(pending_[pending_at_++]));
    }
  }

 private:
  [[noreturn]] void truncated(std::size_t n) {
    refuse(path_, array_, "its data end before the " + std::to_string(n) + " bytes it needs (truncated " +
                              (base64_ ? "base64" : "appended data") + " or a wrong header)");
  }

  static int digit(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  }

  // Decodes the next group of 4 characters into pending_; false at the end of the text.
  bool next_group() {
    char group[4];
    int n = 0;
    while (n < 4 && at_ < data_.size()) {
      const char c = data_[at_++];
      if (!is_space(c)) group[n++] = c;
    }
    if (n == 0) return false;
    if (n < 4)
      refuse(path_, array_, "its base64 text ends inside a group of 4 characters (truncated)");
    int padding = 0;
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) {
      int d = digit(group[k]);
      if (group[k] == '=' && k >= 2 && (k == 3 || group[3] == '=')) {
        ++padding;
        d = 0;
      } else if (d < 0 || padding > 0) {
        std::string what(1, '\'');  // built in steps: g++ 12 warns (-Wrestrict) falsely on "'" + std::string
        what += excerpt(std::string_view(&group[k], 1));
        what += "' in its base64 text is not a base64 character";
        refuse(path_, array_, what);
      }
      v = (v << 6) | static_cast<std::uint32_t>(d);
    }
    pending_[0] = static_cast<unsigned char>(v >> 16);
    pending_[1] = static_cast<unsigned char>(v >> 8);
    pending_[2] = static_cast<unsigned char>(v);
    pending_size_ = static_cast<std::size_t>(3 - padding);
    pending_at_ = 0;
    return true;
  }

  const std::string& path_;
  const VtpArray& array_;
  std::string_view data_;
  bool base64_;
  std::size_t at_ = 0;
  unsigned char pending_[3] = {0, 0, 0};
  std::size_t pending_size_ = 0, pending_at_ = 0;
};

// An unsigned integer of `size` bytes at `p` in the file's byte order.
std::uint64_t unsigned_word(const char* p, int size, bool big_endian) {
  std::uint64_t v = 0;
  for (int k = 0; k < size; ++k) {
    const auto byte = static_cast<unsigned char>(p[big_endian ? k : size - 1 - k]);
    v = (v << 8) | byte;
  }
  return v;
}

// Inflates block k (`compressed`, zlib format) into exactly `size` bytes at `out`, or refuses the array.
void inflate_block(const std::string& path, const VtpArray& array, std::size_t k, std::string_view compressed,
                   unsigned char* out, std::size_t size) {
  z_stream z{};
  if (inflateInit(&z) != Z_OK) throw std::bad_alloc();
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end{&z};
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  z.avail_in = static_cast<uInt>(compressed.size());
  z.next_out = out;
  z.avail_out = static_cast<uInt>(size);
  const std::string block = "compressed block " + std::to_string(k) + " ";
  int status = inflate(&z, Z_FINISH);
  std::size_t missing = z.avail_out;  // declared bytes not produced
  if (status == Z_BUF_ERROR && z.avail_out == 0) {
    // The declared bytes are full: the stream must end here, without one byte more.
    unsigned char extra = 0;
    z.next_out = &extra;
    z.avail_out = 1;
    status = inflate(&z, Z_FINISH);
    if (z.avail_out == 0)
      refuse(path, array, block + "inflates to more than its declared " + std::to_string(size) +
                              " bytes (a zip bomb or a wrong header)");
  }
  if (status == Z_STREAM_END) {
    if (missing != 0)
      refuse(path, array, block + "inflates to " + std::to_string(size - missing) + " bytes, fewer than its "
                              "declared " + std::to_string(size));
    return;
  }
  if (status == Z_DATA_ERROR || status == Z_NEED_DICT || status == Z_STREAM_ERROR)
    refuse(path, array, block + "is not zlib data (" + std::string(z.msg ? z.msg : "no message") + ")");
  refuse(path, array, block + "ends before its declared " + std::to_string(size) + " bytes (truncated or a wrong "
                          "header)");
}

// The data bytes of a binary or appended array whose values are `value_size` bytes, `components` to a tuple:
// `expected` values (or -1: any whole number of tuples). See vtk_data_array.h.
std::string data_bytes(const std::string& path, const VtpDocument& doc, const VtpArray& array, int value_size,
                       int components, std::int64_t expected) {
  std::string_view data;
  bool base64 = true;
  if (array.format == "binary") {
    data = array.text;
  } else {
    if (!doc.has_appended) refuse(path, array, "format appended, but the file has no AppendedData");
    if (static_cast<std::uint64_t>(array.offset) > doc.appended.size())
      refuse(path, array, "offset " + std::to_string(array.offset) + " is past the end of the appended data (" +
                              std::to_string(doc.appended.size()) + (doc.appended_base64 ? " characters)" : " bytes)"));
    data = doc.appended.substr(static_cast<std::size_t>(array.offset));
    base64 = doc.appended_base64;
  }
  ByteSource source(path, array, data, base64);
  const int word_size = doc.header_64 ? 8 : 4;
  std::string words;
  auto word = [&] {
    words.clear();
    source.take(static_cast<std::size_t>(word_size), words);
    return unsigned_word(words.data(), word_size, doc.big_endian);
  };
  const auto tuple_bytes = static_cast<std::uint64_t>(value_size) * static_cast<std::uint64_t>(components);
  // The data's size against the values the array must hold.
  auto check_size = [&](std::uint64_t n) {
    if (n % tuple_bytes != 0)
      refuse(path, array, "holds " + std::to_string(n) + " bytes, not a whole number of tuples of " +
                              std::to_string(components) + " " + array.type + " values");
    if (expected >= 0 && n / static_cast<std::uint64_t>(value_size) != static_cast<std::uint64_t>(expected))
      refuse(path, array, "holds " + std::to_string(n / static_cast<std::uint64_t>(value_size)) + " values, not " +
                              std::to_string(expected));
  };
  std::string out;
  if (!doc.compressed) {
    const std::uint64_t n = word();
    if (n > source.bound())
      refuse(path, array, "its header declares " + std::to_string(n) + " bytes, more than the " +
                              std::to_string(source.bound()) + " left in the file (truncated file or a wrong header)");
    check_size(n);
    source.take(static_cast<std::size_t>(n), out);
    return out;
  }
  const std::uint64_t blocks = word();
  if (blocks > source.bound() / static_cast<std::size_t>(word_size))
    refuse(path, array, "its header declares " + std::to_string(blocks) + " compressed blocks, more than the " +
                            std::to_string(source.bound()) + " bytes left in the file can hold");
  const std::uint64_t block_size = word(), last_size = word();
  if (blocks > 0 && block_size == 0) refuse(path, array, "its header declares compressed blocks of 0 bytes");
  if (last_size > block_size)
    refuse(path, array, "its header declares a last block of " + std::to_string(last_size) +
                            " bytes, more than its blocks of " + std::to_string(block_size));
  if (block_size > std::numeric_limits<uInt>::max())
    refuse(path, array, "its header declares compressed blocks of " + std::to_string(block_size) +
                            " bytes, more than zlib takes at once");
  std::vector<std::uint64_t> compressed_sizes(static_cast<std::size_t>(blocks));
  std::uint64_t compressed_total = 0, total = 0;
  for (std::uint64_t k = 0; k < blocks; ++k) {
    const std::uint64_t c = word();
    const std::uint64_t size = k + 1 == blocks && last_size > 0 ? last_size : block_size;
    if (c > source.bound() - std::min<std::uint64_t>(source.bound(), compressed_total))
      refuse(path, array, "its header declares compressed block " + std::to_string(k) + " of " + std::to_string(c) +
                              " bytes, more than the file holds after the blocks before it (truncated file or a "
                              "wrong header)");
    if (static_cast<double>(size) > kZlibLargestRatio * static_cast<double>(c))
      refuse(path, array, "compressed block " + std::to_string(k) + " declares " + std::to_string(size) +
                              " bytes from " + std::to_string(c) + " compressed bytes, more than zlib's largest "
                              "ratio of 1032 (a zip bomb or a wrong header)");
    compressed_sizes[static_cast<std::size_t>(k)] = c;
    compressed_total += c;
    total += size;
  }
  check_size(total);
  std::string compressed;
  source.take(static_cast<std::size_t>(compressed_total), compressed);
  out.resize(static_cast<std::size_t>(total));
  std::size_t in_at = 0, out_at = 0;
  for (std::uint64_t k = 0; k < blocks; ++k) {
    const std::size_t c = static_cast<std::size_t>(compressed_sizes[static_cast<std::size_t>(k)]);
    const std::size_t size = static_cast<std::size_t>(k + 1 == blocks && last_size > 0 ? last_size : block_size);
    inflate_block(path, array, static_cast<std::size_t>(k), std::string_view(compressed).substr(in_at, c),
                  reinterpret_cast<unsigned char*>(out.data()) + out_at, size);
    in_at += c;
    out_at += size;
  }
  return out;
}

// The white-space separated tokens of an ascii array.
template <class Each>
void for_each_token(std::string_view text, Each&& each) {
  for (std::size_t i = 0; i < text.size();) {
    if (is_space(text[i])) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < text.size() && !is_space(text[j])) ++j;
    each(text.substr(i, j - i));
    i = j;
  }
}

// The value of an ascii integer token of `type` (whole, within the type's range), or a refusal.
double ascii_integer(const std::string& path, const VtpArray& array, const NumericType& type, std::string_view token) {
  const auto v = parse_long(token);
  if (!v) {
    // UInt64 values above the largest long
    const auto d = parse_double(token);
    if (!(type.size == 8 && !type.is_signed && d && *d >= 0 && *d == std::floor(*d) &&
          token.find_first_not_of("+0123456789") == std::string_view::npos))
      refuse(path, array, "holds '" + excerpt(token) + "', not a whole number");
    return *d;
  }
  const int bits = 8 * type.size;
  const long double lo = type.is_signed ? -std::ldexp(1.0L, bits - 1) : 0.0L;
  const long double hi = std::ldexp(1.0L, type.is_signed ? bits - 1 : bits) - 1;
  if (static_cast<long double>(*v) < lo || static_cast<long double>(*v) > hi)
    refuse(path, array, "holds " + std::to_string(*v) + ", outside the range of " + array.type);
  return static_cast<double>(*v);
}

}  // namespace

std::string array_label(const VtpArray& array) {
  return array.element + (array.name.empty() ? "" : " '" + excerpt(array.name) + "'");
}

std::vector<double> decode_numbers(const std::string& path, const VtpDocument& doc, const VtpArray& array,
                                   std::int64_t expected) {
  const NumericType type = numeric_type(array.type);
  if (type.size == 0) refuse(path, array, "of type " + array.type + ", not numbers");
  if (expected < 0 && array.tuples >= 0) {
    if (array.tuples > std::numeric_limits<std::int64_t>::max() / array.components)
      refuse(path, array, "NumberOfTuples=\"" + std::to_string(array.tuples) + "\" is too large");
    expected = array.tuples * array.components;
  }
  std::vector<double> values;
  if (array.format == "ascii") {
    for_each_token(array.text, [&](std::string_view token) {
      if (type.real) {
        const auto v = parse_double(token);
        if (!v) refuse(path, array, "holds '" + excerpt(token) + "', not a number");
        values.push_back(*v);
      } else {
        values.push_back(ascii_integer(path, array, type, token));
      }
    });
    if (expected >= 0 ? values.size() != static_cast<std::uint64_t>(expected)
                      : values.size() % static_cast<std::size_t>(array.components) != 0)
      refuse(path, array, "holds " + std::to_string(values.size()) + " values, not " +
                              (expected >= 0 ? std::to_string(expected)
                                             : "a multiple of its " + std::to_string(array.components) + " components"));
    return values;
  }
  const std::string bytes = data_bytes(path, doc, array, type.size, array.components, expected);
  const std::size_t n = bytes.size() / static_cast<std::size_t>(type.size);
  values.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    char v[8];
    const char* p = bytes.data() + k * static_cast<std::size_t>(type.size);
    for (int b = 0; b < type.size; ++b)  // to host (little-endian) order
      v[b] = doc.big_endian ? p[type.size - 1 - b] : p[b];
    double x = 0;
    switch (type.size) {
      case 1:
        x = type.is_signed ? static_cast<double>(static_cast<std::int8_t>(v[0]))
                           : static_cast<double>(static_cast<std::uint8_t>(v[0]));
        break;
      case 2: {
        std::uint16_t u;
        std::memcpy(&u, v, 2);
        x = type.is_signed ? static_cast<double>(static_cast<std::int16_t>(u)) : static_cast<double>(u);
        break;
      }
      case 4: {
        std::uint32_t u;
        std::memcpy(&u, v, 4);
        if (type.real) {
          float f;
          std::memcpy(&f, v, 4);
          x = static_cast<double>(f);
        } else {
          x = type.is_signed ? static_cast<double>(static_cast<std::int32_t>(u)) : static_cast<double>(u);
        }
        break;
      }
      default: {
        std::uint64_t u;
        std::memcpy(&u, v, 8);
        if (type.real)
          std::memcpy(&x, v, 8);
        else
          x = type.is_signed ? static_cast<double>(static_cast<std::int64_t>(u)) : static_cast<double>(u);
      }
    }
    values[k] = x;
  }
  return values;
}

std::vector<std::string> decode_strings(const std::string& path, const VtpDocument& doc, const VtpArray& array) {
  if (array.type != "String") refuse(path, array, "of type " + array.type + ", not String");
  std::string bytes;
  if (array.format == "ascii") {
    const NumericType byte{1, false, false};
    for_each_token(array.text, [&](std::string_view token) {
      bytes.push_back(static_cast<char>(static_cast<unsigned char>(ascii_integer(path, array, byte, token))));
    });
  } else {
    bytes = data_bytes(path, doc, array, 1, 1, -1);
  }
  // The strings it must hold: its tuples x components (saturated), or any number without NumberOfTuples.
  const std::uint64_t components = static_cast<std::uint64_t>(array.components);
  const std::uint64_t declared =
      array.tuples < 0 ? std::numeric_limits<std::uint64_t>::max()
      : static_cast<std::uint64_t>(array.tuples) > std::numeric_limits<std::uint64_t>::max() / components
          ? std::numeric_limits<std::uint64_t>::max()
          : static_cast<std::uint64_t>(array.tuples) * components;
  const std::string tuples = std::to_string(array.tuples) + " tuples" +
                             (array.components > 1 ? " of " + std::to_string(array.components) + " components" : "");
  std::vector<std::string> strings;
  for (std::size_t i = 0; i < bytes.size();) {
    const std::size_t end = std::min(bytes.find('\0', i), bytes.size());
    if (strings.size() == declared) refuse(path, array, "holds more strings than its " + tuples);
    strings.push_back(bytes.substr(i, end - i));
    i = end + 1;
  }
  if (array.tuples >= 0 && strings.size() < declared)
    refuse(path, array, "holds " + std::to_string(strings.size()) + " strings, fewer than its " + tuples);
  return strings;
}

}  // namespace radwalk
