#include "mesh/read_vtk.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string_view>
#include <cctype>
#include <tuple>
#include <vector>

#include <vtkAbstractArray.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/exact_vertices.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"
#include "mesh/triangulate.h"

namespace radwalk {
namespace {

constexpr double kZlibMaxRatio = 1032;  // zlib's largest compression ratio: a bound on what compressed bytes hold

// Collects what VTK prints while radwalk reads, instead of printing it: the first error becomes the refusal.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
  void DisplayText(const char* text) override { keep(text, false); }
  void DisplayErrorText(const char* text) override { keep(text, true); }
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  const std::string& error() const { return error_; }

 private:
  // VTK's message is "ERROR: In FILE, line N\nCLASS (0x...): WHAT\n\n": WHAT is kept.
  void keep(const char* text, bool is_error) {
    if (!text || !error_.empty()) return;
    std::string t(text);
    if (!is_error && t.find("ERROR") == std::string::npos) return;
    std::string last;
    std::size_t start = 0;
    while (start <= t.size()) {
      const std::size_t end = t.find('\n', start);
      const std::string line = t.substr(start, end == std::string::npos ? std::string::npos : end - start);
      if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
      if (end == std::string::npos) break;
      start = end + 1;
    }
    const std::size_t colon = last.find("): ");
    if (colon != std::string::npos) last = last.substr(colon + 3);
    error_ = last.empty() ? "unreadable" : last;
  }
  std::string error_;
};
vtkStandardNewMacro(CapturingOutputWindow);

// Installs a CapturingOutputWindow for its lifetime, and keeps VTK's logger (which writes errors to stderr on its
// own) quiet meanwhile.
class CaptureScope {
 public:
  CaptureScope() : previous_(vtkOutputWindow::GetInstance()), verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    window_ = vtkSmartPointer<CapturingOutputWindow>::New();
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~CaptureScope() {
    vtkLogger::SetStderrVerbosity(verbosity_);
    vtkOutputWindow::SetInstance(previous_);
  }
  const std::string& error() const { return window_->error(); }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity verbosity_;
  vtkSmartPointer<CapturingOutputWindow> window_;
};

// The legacy keyword a token stands for, as VTK's legacy reader matches it: the token lowercased starts with the
// keyword (VTK compares the keyword's length only: "POLYGONS`1" is POLYGONS); "" for none.
std::string legacy_keyword(std::string_view token) {
  static const char* const kKeywords[] = {"POINTS",   "POLYGONS", "TRIANGLE_STRIPS", "VERTICES",  "LINES",
                                          "OFFSETS",  "CONNECTIVITY", "CELL_DATA", "POINT_DATA", "FIELD",
                                          "SCALARS", "COLOR_SCALARS"};
  for (const char* k : kKeywords) {
    const std::string_view key(k);
    if (token.size() < key.size()) continue;
    bool same = true;
    for (std::size_t i = 0; i < key.size() && same; ++i)
      same = std::toupper(static_cast<unsigned char>(token[i])) == key[i];
    if (same) return k;
  }
  return "";
}

// The value of the attribute `name` in an element's start tag (the text from '<' to before '>'), as an XML parser
// reads it (the name preceded by white space, then optional white space, '=', optional white space and a quoted
// value), or nullopt. Substring matches would be wrong: in `byte_orderheader_type="UInt64"` VTK sees no
// header_type (and takes 32-bit headers) where a search for `header_type="UInt64"` finds one, and `foreat="ascii"`
// is no format (both fuzz findings: VTK then divided by a block size of 0, or crashed reading the piece).
std::optional<std::string_view> tag_attribute(std::string_view tag, std::string_view name) {
  for (std::size_t at = tag.find(name); at != std::string_view::npos; at = tag.find(name, at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(tag[at - 1]))) continue;
    std::size_t k = at + name.size();
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (k >= tag.size() || tag[k] != '=') continue;
    ++k;
    while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
    if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
    const std::size_t close = tag.find(tag[k], k + 1);
    if (close == std::string_view::npos) return std::nullopt;
    return tag.substr(k + 1, close - k - 1);
  }
  return std::nullopt;
}

// The attribute `name` of the file's <VTKFile ...> element ("" when the element or the attribute is missing).
std::string_view vtkfile_attribute(std::string_view text, std::string_view name) {
  const std::size_t start = text.find("<VTKFile");
  if (start == std::string_view::npos) return {};
  const std::size_t end = text.find('>', start);
  return tag_attribute(text.substr(start, end == std::string_view::npos ? text.npos : end - start), name)
      .value_or(std::string_view());
}

// The bound of read_vtk.h on the counts a file declares, before VTK allocates anything.
void check_declared_counts(const std::string& path, std::string_view bytes, bool xml) {
  const double size = static_cast<double>(bytes.size());
  double largest_count = 0, largest_components = 1;
  std::string_view text = bytes;
  if (xml) {
    // Only the XML markup: a raw appended section is binary and declares nothing.
    const std::size_t appended = text.find("<AppendedData");
    if (appended != std::string_view::npos) text = text.substr(0, appended);
    const bool compressed = !vtkfile_attribute(text, "compressor").empty();
    // Every NumberOfNAME="VALUE" attribute (scanned by hand: no regex backtracking over megabytes of markup).
    for (std::size_t at = text.find("NumberOf"); at != std::string_view::npos; at = text.find("NumberOf", at + 1)) {
      std::size_t k = at + 8;
      while (k < text.size() && std::isalpha(static_cast<unsigned char>(text[k]))) ++k;
      const std::string what(text.substr(at + 8, k - at - 8));
      if (text.substr(k, 2) != "=\"") continue;
      const std::size_t close = text.find('"', k + 2);
      if (close == std::string_view::npos) continue;
      const std::string value(text.substr(k + 2, close - k - 2));
      const auto n = parse_double(value);
      if (!n || !(*n >= 0))
        throw InputError(locate(path, 0, -1, "NumberOf" + excerpt(what) + "=\"" + excerpt(value) +
                                                 "\" is not a count"));
      if (what == "Components")
        largest_components = std::max(largest_components, *n);
      else
        largest_count = std::max(largest_count, *n);
    }
    // Every array's type is one VTK knows: VTK 9.1's XML reader dereferences the array it could not create for
    // another (a DataArray of type "Int28" crashed it; found by the vtk fuzz harness).
    for (const std::string_view element : {std::string_view("<DataArray"), std::string_view("<Array")}) {
      for (std::size_t at = text.find(element); at != std::string_view::npos; at = text.find(element, at + 1)) {
        const std::size_t end = text.find('>', at);
        const std::string_view tag = text.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at);
        const std::size_t t = tag.find(" type=\"");
        if (t == std::string_view::npos)  // VTK 9.1 crashed on an array without a type too (the vtk fuzz harness)
          throw InputError(locate(path, 0, -1, std::string(element.substr(1)) + " without a type"));
        const std::size_t close = tag.find('"', t + 7);
        const std::string_view type = tag.substr(t + 7, close == std::string_view::npos ? 0 : close - t - 7);
        static const char* const kTypes[] = {"Int8",  "UInt8",  "Int16",   "UInt16",  "Int32", "UInt32",
                                             "Int64", "UInt64", "Float32", "Float64", "String"};
        bool known = false;
        for (const char* k : kTypes) known = known || type == k;
        if (!known)
          throw InputError(locate(path, 0, -1, std::string(element.substr(1)) + " of type \"" + excerpt(type) +
                                                   "\": not one of Int8, UInt8, Int16, UInt16, Int32, UInt32, "
                                                   "Int64, UInt64, Float32, Float64, String"));
        // Every array names its format, one of VTK's three (an array whose format attribute was mangled crashed
        // VTK 9.1's reader; found by the vtk fuzz harness).
        const std::optional<std::string_view> format = tag_attribute(tag, "format");
        if (!format || (*format != "ascii" && *format != "binary" && *format != "appended"))
          throw InputError(locate(path, 0, -1, std::string(element.substr(1)) + " without a format of ascii, binary "
                                                   "or appended"));
        // An ascii array holds numbers only (whole ones but for Float32 and Float64; a String array its bytes):
        // VTK 9.1's XML reader crashed on a word among an ascii array's numbers (found by the vtk fuzz harness).
        if (end == std::string_view::npos || *format != "ascii") continue;
        const std::size_t stop = text.find('<', end + 1);
        const std::string_view content =
            text.substr(end + 1, stop == std::string_view::npos ? std::string_view::npos : stop - end - 1);
        const bool real = type == "Float32" || type == "Float64";
        std::size_t values = 0, zeros = 0;  // zeros: a String array's terminators
        bool last_zero = true;
        for (std::size_t i = 0; i < content.size();) {
          if (std::isspace(static_cast<unsigned char>(content[i]))) {
            ++i;
            continue;
          }
          std::size_t j = i;
          while (j < content.size() && !std::isspace(static_cast<unsigned char>(content[j]))) ++j;
          const std::string_view token = content.substr(i, j - i);
          if (real ? !parse_double(token) : !parse_long(token))
            throw InputError(locate(path, 0, -1, "an ascii " + std::string(element.substr(1)) + " of type " +
                                                     std::string(type) + " holds '" + excerpt(token) + "', not " +
                                                     (real ? "a number" : "a whole number")));
          i = j;
          ++values;
          last_zero = type == "String" && parse_long(token) && *parse_long(token) == 0;
          if (last_zero) ++zeros;
        }
        // As many values as the array declares: a multiple of its components, its tuples when it names them, and
        // in a piece's CellData one tuple per cell, in its PointData and Points one per point (a short E array
        // crashed VTK 9.1's XML reader too; found by the vtk fuzz harness).
        const auto attribute = [&](const char* name) -> double {
          const std::size_t a = tag.find(std::string(" ") + name + "=\"");
          if (a == std::string_view::npos) return -1;
          const std::size_t v = a + std::strlen(name) + 3, e = tag.find('"', v);
          const auto n = parse_double(tag.substr(v, e == std::string_view::npos ? 0 : e - v));
          return n && *n >= 0 ? *n : -1;
        };
        if (type == "String") {
          // Its values are the bytes of its strings, each ended by 0: VTK 9.1 stores every string it finds and
          // wrote past an array of NumberOfTuples strings when the text held more (found by the vtk fuzz harness).
          const double strings = static_cast<double>(zeros + (last_zero ? 0 : 1));
          const double declared = attribute("NumberOfTuples") * std::max(1.0, attribute("NumberOfComponents"));
          if (values > 0 && attribute("NumberOfTuples") >= 0 && strings > declared)
            throw InputError(locate(path, 0, -1, "an ascii " + std::string(element.substr(1)) + " of strings holds " +
                                                     number_text(strings) + " strings, more than the " +
                                                     number_text(declared) + " it declares"));
          continue;
        }
        const double components = std::max(1.0, attribute("NumberOfComponents"));
        double tuples = attribute("NumberOfTuples");
        const std::size_t piece = text.rfind("<Piece", at);
        if (tuples < 0 && piece != std::string_view::npos) {
          const std::size_t piece_end = text.find('>', piece);
          const std::string_view piece_tag = text.substr(piece, piece_end == std::string_view::npos ? 0 : piece_end - piece);
          const auto count = [&](const char* name) {
            const std::size_t a = piece_tag.find(std::string(name) + "=\"");
            if (a == std::string_view::npos) return 0.0;
            const std::size_t v = a + std::strlen(name) + 2, e = piece_tag.find('"', v);
            const auto n = parse_double(piece_tag.substr(v, e == std::string_view::npos ? 0 : e - v));
            return n && *n >= 0 ? *n : 0.0;
          };
          const auto inside = [&](const char* open, const char* close) {
            const std::size_t o = text.rfind(open, at);
            return o != std::string_view::npos && o > piece && (text.rfind(close, at) == std::string_view::npos ||
                                                                text.rfind(close, at) < o);
          };
          if (inside("<CellData", "</CellData"))
            tuples = count("NumberOfVerts") + count("NumberOfLines") + count("NumberOfStrips") + count("NumberOfPolys");
          else if (inside("<PointData", "</PointData") || inside("<Points", "</Points"))
            tuples = count("NumberOfPoints");
        }
        const bool fits = tuples >= 0 ? values == tuples * components
                                      : std::fmod(static_cast<double>(values), components) == 0;
        if (!fits)
          throw InputError(locate(path, 0, -1, "an ascii " + std::string(element.substr(1)) + " holds " +
                                                   std::to_string(values) + " values, not " +
                                                   (tuples >= 0 ? number_text(tuples) + " tuples of "
                                                                : std::string("a multiple of ")) +
                                                   number_text(components) + " components"));
      }
    }
    // The header of every inline binary array (base64) must fit the file before VTK sizes its buffers by it (a
    // mutated block size made VTK 9.1 allocate petabytes; found by the vtk fuzz harness): uncompressed, its byte
    // count at most the file's bytes; compressed, the number of blocks (each with a header word in the file) at
    // most the file's words, the block sizes at most 1032 (zlib's largest ratio) times the file's bytes and each
    // block's compressed size at most the file's bytes.
    const bool wide = vtkfile_attribute(text, "header_type") == "UInt64";
    for (const std::string_view element : {std::string_view("<DataArray"), std::string_view("<Array")}) {
      for (std::size_t at = text.find(element); at != std::string_view::npos; at = text.find(element, at + 1)) {
        const std::size_t end = text.find('>', at);
        if (end == std::string_view::npos) break;
        if (tag_attribute(text.substr(at, end - at), "format").value_or("") != "binary") continue;
        std::size_t k = end + 1;
        while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
        const std::size_t word_bytes = wide ? 8 : 4;
        // The little-endian words of the header (the base64 text decoded as far as needed); false when the text is
        // not base64 that far (VTK refuses it).
        std::vector<double> words;
        auto decode = [&](std::size_t n_words) {
          words.clear();
          std::vector<unsigned char> raw;
          const std::size_t need = n_words * word_bytes;
          for (std::size_t q = k; raw.size() < need; q += 4) {
            if (q + 4 > text.size()) return false;
            std::uint32_t v = 0;
            for (std::size_t c = 0; c < 4; ++c) {
              const char ch = text[q + c];
              int d = -1;
              if (ch >= 'A' && ch <= 'Z') d = ch - 'A';
              else if (ch >= 'a' && ch <= 'z') d = ch - 'a' + 26;
              else if (ch >= '0' && ch <= '9') d = ch - '0' + 52;
              else if (ch == '+') d = 62;
              else if (ch == '/') d = 63;
              else if (ch == '=') d = 0;  // the header's own padding: the words needed end before it
              if (d < 0) return false;
              v = (v << 6) | static_cast<std::uint32_t>(d);
            }
            raw.push_back(static_cast<unsigned char>(v >> 16));
            raw.push_back(static_cast<unsigned char>(v >> 8));
            raw.push_back(static_cast<unsigned char>(v));
          }
          for (std::size_t w = 0; w < n_words; ++w) {
            double x = 0;
            for (std::size_t b = word_bytes; b-- > 0;) x = x * 256 + raw[w * word_bytes + b];
            words.push_back(x);
          }
          return true;
        };
        auto refuse = [&](double value, const char* what) {
          throw InputError(locate(path, 0, -1, "a binary " + std::string(element.substr(1)) + "'s header declares " +
                                                   number_text(value) + what + ", more than its " +
                                                   std::to_string(bytes.size()) +
                                                   " bytes can hold (truncated file or wrong count)"));
        };
        if (!decode(1)) continue;
        if (!compressed) {
          if (words[0] > size) refuse(words[0], " bytes");
          continue;
        }
        // Compressed: [blocks, block size, last block's size, compressed size of each block].
        const double blocks = words[0];
        if (blocks > size / static_cast<double>(word_bytes)) refuse(blocks, " compressed blocks");
        if (!decode(3 + static_cast<std::size_t>(blocks))) continue;
        // VTK divides by the block size (a block size of 0 stopped it with a floating-point exception; found by the
        // vtk fuzz harness).
        if (blocks > 0 && !(words[1] > 0))
          throw InputError(locate(path, 0, -1, "a binary " + std::string(element.substr(1)) +
                                                   "'s header declares compressed blocks of 0 bytes"));
        for (std::size_t w = 1; w < words.size(); ++w)
          if (words[w] > (w < 3 ? kZlibMaxRatio : 1.0) * size) refuse(words[w], w < 3 ? " bytes in a block" : " compressed bytes");
      }
    }
    const double bound = (compressed ? kZlibMaxRatio : 1.0) * size;
    if (largest_count * largest_components > bound)
      throw InputError(locate(path, 0, -1, "declares " + number_text(largest_count) + " items of " +
                                               number_text(largest_components) + " components, more than its " +
                                               std::to_string(bytes.size()) + " bytes can hold (truncated file or "
                                               "wrong count)"));
    return;
  }
  // Legacy: the numbers after the keywords that size VTK's arrays.
  long line_number = 0;
  bool field_arrays = false;
  for_each_line(text, [&](long line, std::string_view content) {
    line_number = line;
    const auto tokens = split_tokens(content);
    if (tokens.empty()) return;
    const std::string key = legacy_keyword(tokens[0]);
    std::vector<double> counts;
    auto number = [&](std::size_t k) {
      if (k >= tokens.size()) return;
      const auto n = parse_double(tokens[k]);
      if (n && *n >= 0) counts.push_back(*n);
    };
    if (key == "POINTS" || key == "CELL_DATA" || key == "POINT_DATA") {
      number(1);
      field_arrays = false;
    } else if (key == "POLYGONS" || key == "TRIANGLE_STRIPS" || key == "VERTICES" || key == "LINES" ||
               key == "OFFSETS" || key == "CONNECTIVITY") {
      number(1);
      number(2);
      field_arrays = false;
    } else if (key == "FIELD") {
      number(2);
      field_arrays = true;
    } else if (field_arrays && tokens.size() == 4 && !parse_double(tokens[0])) {  // NAME COMPONENTS TUPLES TYPE
      const auto c = parse_double(tokens[1]), t = parse_double(tokens[2]);
      if (c && t && *c >= 0 && *t >= 0) counts.push_back(*c * *t);
    } else if ((key == "SCALARS" || key == "COLOR_SCALARS") && tokens.size() >= 3) {
      const auto c = parse_double(tokens[tokens.size() - 1]);
      if (c && *c >= 0) largest_components = std::max(largest_components, *c);
    }
    for (double n : counts)
      if (n > size)
        throw InputError(locate(path, line, -1, "declares " + number_text(n) + " items, more than its " +
                                                    std::to_string(bytes.size()) +
                                                    " bytes can hold (truncated file or wrong count)"));
    for (double n : counts) largest_count = std::max(largest_count, n);
  });
  if (largest_count * largest_components > 4 * size)
    throw InputError(locate(path, 0, -1, "declares " + number_text(largest_count) + " items of " +
                                             number_text(largest_components) + " components, more than its " +
                                             std::to_string(bytes.size()) + " bytes can hold"));
}

// An ASCII legacy file's geometry sections hold what their headers say, before VTK reads them: POINTS n TYPE is
// followed by 3 n numbers; POLYGONS, TRIANGLE_STRIPS, VERTICES and LINES n size by `size` whole numbers >= 0 (the
// format of version 5.1 instead by OFFSETS TYPE and CONNECTIVITY TYPE sections of whole numbers >= 0, of n and
// size). VTK 9.1's legacy reader, given a section whose numbers do not parse (a word among a polygon's indices),
// goes on reading the stream it closed and crashes (found by the vtk fuzz harness); the first section that is
// short or holds something else is refused here in one line naming its line. The header's first three lines (the
// version, the title, ASCII) are not sections.
void check_ascii_legacy_sections(const std::string& path, std::string_view bytes) {
  // The tokens as VTK's reader sees them: separated by white space, lines by '\n' (views into bytes).
  struct Token {
    std::string_view text;
    long line;
  };
  std::vector<Token> tokens;
  std::vector<std::string_view> third_line;
  long line_at = 1;
  for (std::size_t i = 0; i < bytes.size();) {
    const char c = bytes[i];
    if (c == '\n') {
      ++line_at;
      ++i;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[j]))) ++j;
    if (line_at == 3) third_line.push_back(bytes.substr(i, j - i));
    if (line_at > 3) tokens.push_back({bytes.substr(i, j - i), line_at});
    i = j;
  }
  // VTK takes the file as ASCII when the third line starts with "ascii" in any case ("ASCII\\0" is ASCII).
  const auto ascii_word = [](std::string_view w) {
    if (w.size() < 5) return false;
    for (std::size_t i = 0; i < 5; ++i)
      if (std::tolower(static_cast<unsigned char>(w[i])) != "ascii"[i]) return false;
    return true;
  };
  if (third_line.empty() || !ascii_word(third_line[0])) return;
  std::size_t k = 0;
  // Requires `count` tokens after k of the kind `whole` (else numbers), naming `what` and the line of its header.
  auto require = [&](double count, bool whole, const std::string& what, long header_line) {
    for (double i = 0; i < count; ++i, ++k) {
      if (k >= tokens.size())
        throw InputError(locate(path, header_line, -1, what + " ends before its " + number_text(count) +
                                                           (whole ? " indices" : " numbers")));
      const bool ok = whole ? parse_long(tokens[k].text).value_or(-1) >= 0 : parse_double(tokens[k].text).has_value();
      if (!ok)
        throw InputError(locate(path, tokens[k].line, -1,
                                what + " (line " + std::to_string(header_line) + "): '" + excerpt(tokens[k].text) +
                                    "' is not " + (whole ? "a whole number >= 0" : "a number")));
    }
  };
  auto count_at = [&](std::size_t at) -> double {
    if (at >= tokens.size()) return -1;
    const auto n = parse_double(tokens[at].text);
    return n && *n >= 0 && *n == std::floor(*n) ? *n : -1;
  };
  while (k < tokens.size()) {
    const std::string key = legacy_keyword(tokens[k].text);
    const long line = tokens[k].line;
    if (key == "POINTS") {
      const double n = count_at(k + 1);
      if (n < 0) throw InputError(locate(path, line, -1, "POINTS needs a count"));
      k += 3;  // POINTS n TYPE
      require(3 * n, false, "POINTS", line);
    } else if (key == "POLYGONS" || key == "TRIANGLE_STRIPS" || key == "VERTICES" || key == "LINES") {
      const double n = count_at(k + 1), size = count_at(k + 2);
      if (n < 0 || size < 0) throw InputError(locate(path, line, -1, std::string(key) + " needs two counts"));
      k += 3;
      if (k < tokens.size() && legacy_keyword(tokens[k].text) == "OFFSETS") {  // version 5.1: n offsets, size connectivity
        k += 2;
        require(n, true, std::string(key) + " OFFSETS", line);
        if (k >= tokens.size() || legacy_keyword(tokens[k].text) != "CONNECTIVITY")
          throw InputError(locate(path, line, -1, std::string(key) + ": OFFSETS is not followed by CONNECTIVITY"));
        k += 2;
        require(size, true, std::string(key) + " CONNECTIVITY", line);
      } else {
        require(size, true, std::string(key), line);
      }
    } else if (key == "FIELD") {
      // FIELD NAME n, then n arrays NAME components tuples TYPE of components x tuples values (a bad array
      // header crashed VTK 9.1's legacy reader too; found by the vtk fuzz harness).
      const double arrays = count_at(k + 2);
      if (arrays < 0) throw InputError(locate(path, line, -1, "FIELD needs a name and a count of arrays"));
      k += 3;
      static const char* const kLegacyTypes[] = {"bit",  "unsigned_char", "char",   "unsigned_short", "short",
                                                 "unsigned_int", "int", "unsigned_long", "long", "float",
                                                 "double", "vtkIdType", "vtktypeint64", "vtktypeuint64"};
      for (double a = 0; a < arrays; ++a) {
        if (k + 3 >= tokens.size())
          throw InputError(locate(path, line, -1, "FIELD ends before its " + number_text(arrays) + " arrays"));
        const long at_line = tokens[k].line;
        const double components = count_at(k + 1), tuples = count_at(k + 2);
        const std::string_view type = tokens[k + 3].text;
        bool known = false;
        for (const char* t : kLegacyTypes) known = known || type == t;
        if (components < 0 || tuples < 0 || !known)
          throw InputError(locate(path, at_line, -1, "FIELD (line " + std::to_string(line) + "): the array '" +
                                                         excerpt(tokens[k].text) +
                                                         "' needs NAME COMPONENTS TUPLES TYPE with a numeric type"));
        k += 4;
        require(components * tuples, false, "FIELD array", at_line);
      }
    } else if (key == "CELL_DATA" || key == "POINT_DATA") {
      return;  // the attributes after the geometry: VTK's own checks (no crash found there)
    } else {
      ++k;
    }
  }
}

vtkSmartPointer<vtkPolyData> parse(const std::string& path, std::string_view bytes, bool xml) {
  CaptureScope capture;
  vtkSmartPointer<vtkPolyData> out;
  if (xml) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->ReadFromInputStringOn();
    reader->SetInputString(std::string(bytes));
    reader->Update();
    out = reader->GetOutput();
  } else {
    if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      throw InputError(locate(path, 0, -1, "a legacy .vtk file above 2 GiB is not read (write it as .vtp)"));
    vtkNew<vtkPolyDataReader> reader;
    reader->ReadFromInputStringOn();
    reader->SetBinaryInputString(bytes.data(), static_cast<int>(bytes.size()));
    reader->Update();
    out = reader->GetOutput();
  }
  if (!capture.error().empty())
    throw InputError(locate(path, 0, -1, "VTK cannot read it: " + excerpt(capture.error())));
  if (!out) throw InputError(locate(path, 0, -1, "VTK read no polygonal data"));
  return out;
}

// A cell array of `components` numbers per cell by name, or nullptr.
vtkDataArray* cell_array(vtkPolyData* data, const char* name, int components, std::size_t cells) {
  vtkDataArray* a = data->GetCellData()->GetArray(name);
  if (!a || a->GetNumberOfComponents() != components || static_cast<std::size_t>(a->GetNumberOfTuples()) != cells)
    return nullptr;
  return a;
}

std::vector<std::string> string_table(vtkPolyData* data, const char* name) {
  std::vector<std::string> out;
  auto* a = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(name));
  if (!a) return out;
  for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k) out.push_back(a->GetValue(k));
  return out;
}

// Drops corners on the segment between their neighbours (see read_vtk.h), keeping at least 3.
std::vector<std::int32_t> without_straight_corners(const std::vector<std::int32_t>& corners,
                                                   const std::vector<Vec3>& points) {
  std::vector<std::int32_t> kept = corners;
  bool dropped = true;
  while (dropped && kept.size() > 3) {
    dropped = false;
    for (std::size_t k = 0; k < kept.size() && kept.size() > 3; ++k) {
      const Vec3& a = points[static_cast<std::size_t>(kept[(k + kept.size() - 1) % kept.size()])];
      const Vec3& b = points[static_cast<std::size_t>(kept[k])];
      const Vec3& c = points[static_cast<std::size_t>(kept[(k + 1) % kept.size()])];
      const Vec3 u = b - a, v = c - b;
      if (u.cross(v).norm() <= 1e-12 * u.norm() * v.norm() && u.dot(v) > 0) {
        kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(k));
        dropped = true;
        break;
      }
    }
  }
  return kept;
}

}  // namespace

Mesh read_vtk_polydata(const std::string& path, const ReadOptions& options) {
  const std::string ext = lower_extension(path);
  return read_vtk_polydata_bytes(path, read_input_file(path), ext == "vtp", options);
}

Mesh read_vtk_polydata_bytes(const std::string& path, std::string_view bytes, bool xml, const ReadOptions& options) {
  check_declared_counts(path, bytes, xml);
  if (!xml) check_ascii_legacy_sections(path, bytes);
  const vtkSmartPointer<vtkPolyData> data = parse(path, bytes, xml);
  Mesh mesh;
  mesh.path = path;
  const vtkIdType n_points = data->GetNumberOfPoints();
  if (n_points > std::numeric_limits<std::int32_t>::max() / 2)
    throw InputError(locate(path, 0, -1, "too many points"));
  std::vector<Vec3> points(static_cast<std::size_t>(n_points));
  std::vector<std::int32_t> vertex_of(points.size());
  ExactVertices vertices(mesh.vertices);
  for (vtkIdType k = 0; k < n_points; ++k) {
    double p[3];
    data->GetPoint(k, p);
    points[static_cast<std::size_t>(k)] = Vec3(p[0], p[1], p[2]);
    vertex_of[static_cast<std::size_t>(k)] = vertices.index(points[static_cast<std::size_t>(k)]);
  }
  const vtkIdType n_verts = data->GetNumberOfVerts(), n_lines = data->GetNumberOfLines();
  const vtkIdType n_polys = data->GetNumberOfPolys(), n_strips = data->GetNumberOfStrips();
  const auto cells = static_cast<std::size_t>(n_verts + n_lines + n_polys + n_strips);
  if (n_polys + n_strips == 0) throw InputError(locate(path, 0, -1, "no polygons or triangle strips"));
  if (n_verts + n_lines > 0)
    mesh.findings.push_back(mesh.finding_of(-1, 0, -1, -1, "line and point elements ignored", Severity::warning,
                                            std::to_string(n_verts + n_lines) +
                                                " vertex and line cells ignored: radiosity needs surfaces"));

  vtkDataArray* rho = cell_array(data, "rho", 3, cells);
  vtkDataArray* E = cell_array(data, "E", 3, cells);
  vtkDataArray* side = cell_array(data, "side", 1, cells);
  vtkDataArray* material_id = cell_array(data, "material_id", 1, cells);
  vtkDataArray* group_id = cell_array(data, "group_id", 1, cells);
  vtkDataArray* object_id = cell_array(data, "object_id", 1, cells);
  const std::vector<std::string> material_names = string_table(data, "material_names");
  const std::vector<std::string> group_names = string_table(data, "group_names");
  const std::vector<std::string> object_names = string_table(data, "object_names");
  auto name_at = [](const std::vector<std::string>& table, vtkDataArray* ids, std::size_t cell) -> std::string {
    if (!ids) return "";
    const double id = ids->GetComponent(static_cast<vtkIdType>(cell), 0);
    if (!(id >= 0 && id < static_cast<double>(table.size()))) return "";
    return table[static_cast<std::size_t>(id)];
  };

  // Materials: by (name, rho, E); see read_vtk.h.
  std::map<std::tuple<std::string, double, double, double, double, double, double>, std::int32_t> material_of;
  std::map<std::string, int> name_uses;
  auto material_for = [&](std::size_t cell) -> std::int32_t {
    Rgb kd = Rgb::Zero(), e = Rgb::Zero();
    for (int c = 0; c < 3; ++c) {
      if (rho) kd[c] = rho->GetComponent(static_cast<vtkIdType>(cell), c);
      if (E) e[c] = E->GetComponent(static_cast<vtkIdType>(cell), c);
    }
    std::string base = name_at(material_names, material_id, cell);
    if (!rho) base = std::filesystem::path(path).stem().string();
    const auto key = std::make_tuple(base, kd[0], kd[1], kd[2], e[0], e[1], e[2]);
    const auto it = material_of.find(key);
    if (it != material_of.end()) return it->second;
    Material m;
    if (base.empty()) {
      m.name = "vtk_material_" + std::to_string(material_of.size());
    } else {
      const int uses = ++name_uses[base];
      m.name = uses == 1 ? base : base + "_" + std::to_string(uses);
    }
    m.Kd = kd;
    m.Ke = e / kPi;
    m.reflectance_missing = rho == nullptr;
    const auto index = static_cast<std::int32_t>(mesh.materials.size());
    mesh.materials.push_back(m);
    material_of.emplace(key, index);
    return index;
  };
  std::map<std::pair<std::string, std::string>, std::int32_t> group_of;
  auto group_for = [&](std::size_t cell) -> std::int32_t {
    const std::string object = name_at(object_names, object_id, cell), group = name_at(group_names, group_id, cell);
    if (object.empty() && group.empty()) return -1;
    const auto [it, added] = group_of.emplace(std::make_pair(object, group), static_cast<std::int32_t>(mesh.groups.size()));
    if (added) {
      std::string label;
      if (!object.empty()) label = "object '" + object + "'";
      if (!group.empty()) label += (label.empty() ? "" : ", ") + ("group '" + group + "'");
      mesh.groups.push_back(label);
      mesh.group_object.push_back(object);
      mesh.group_name.push_back(group);
    }
    return it->second;
  };

  PolygonFaces faces(mesh, options.strict);
  std::int32_t face = 0;
  vtkNew<vtkIdList> ids;
  auto add_cell = [&](std::size_t cell, const std::vector<std::int32_t>& point_ids) {
    const std::int32_t source = face++;
    if (side && side->GetComponent(static_cast<vtkIdType>(cell), 0) == 1) {  // a back cell: its front stands for it
      mesh.materials[static_cast<std::size_t>(material_for(cell))].two_sided = true;
      return;
    }
    const std::int32_t material = material_for(cell);  // two-sided only if a back cell has its material
    std::vector<std::int32_t> corners;
    for (const std::int32_t p : without_straight_corners(point_ids, points))
      corners.push_back(vertex_of[static_cast<std::size_t>(p)]);
    if (corners.size() < 3) {
      mesh.findings.push_back(mesh.finding_of(source, 0, material, group_for(cell), "face of fewer than 3 corners",
                                              Severity::error,
                                              "has " + std::to_string(corners.size()) +
                                                  " corners, a face needs at least 3"));
      return;
    }
    faces.add(corners, 0, material, group_for(cell), source);
  };
  auto point_ids_of = [&](vtkIdList* list) {
    std::vector<std::int32_t> out;
    for (vtkIdType k = 0; k < list->GetNumberOfIds(); ++k) {
      const vtkIdType id = list->GetId(k);
      if (id < 0 || id >= n_points)
        throw InputError(locate(path, 0, face, "point id " + std::to_string(id) + " is out of range (" +
                                                   std::to_string(n_points) + " points)"));
      out.push_back(static_cast<std::int32_t>(id));
    }
    return out;
  };
  std::size_t cell = static_cast<std::size_t>(n_verts + n_lines);
  vtkCellArray* polys = data->GetPolys();
  for (vtkIdType c = 0; c < n_polys; ++c, ++cell) {
    polys->GetCellAtId(c, ids);
    if (static_cast<std::size_t>(ids->GetNumberOfIds()) > kMaxPolygonCorners)
      throw InputError(locate(path, 0, face, "polygon of " + std::to_string(ids->GetNumberOfIds()) + " corners, more than " +
                                                 std::to_string(kMaxPolygonCorners)));
    add_cell(cell, point_ids_of(ids));
  }
  vtkCellArray* strips = data->GetStrips();
  for (vtkIdType c = 0; c < n_strips; ++c, ++cell) {
    strips->GetCellAtId(c, ids);
    const std::vector<std::int32_t> strip = point_ids_of(ids);
    for (std::size_t t = 0; t + 2 < strip.size(); ++t) {
      if (t % 2 == 0)
        add_cell(cell, {strip[t], strip[t + 1], strip[t + 2]});
      else
        add_cell(cell, {strip[t + 1], strip[t], strip[t + 2]});
    }
  }
  return mesh;
}

}  // namespace radwalk
