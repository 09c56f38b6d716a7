#include "mesh/vtp_xml.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <optional>

#include <expat.h>

#include "core/error.h"
#include "core/excerpt.h"

namespace radwalk {
namespace {

constexpr const char* kTypes[] = {"Int8",  "UInt8",  "Int16",   "UInt16",  "Int32", "UInt32",
                                  "Int64", "UInt64", "Float32", "Float64", "String"};

// A whole number >= 0 written in decimal digits (what VTK writes for counts and offsets), or nothing.
std::optional<std::int64_t> parse_count(std::string_view text) {
  std::int64_t value = 0;
  if (text.empty()) return std::nullopt;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < 0) return std::nullopt;
  return value;
}

// Where an element sits: what the parser is inside of.
enum class Context { none, vtkfile, polydata, field_data, piece, point_data, cell_data, points, cells, unknown };

struct Parser {
  explicit Parser(const std::string& file) : path(file) {}
  const std::string& path;
  XML_Parser xml = nullptr;
  VtpDocument doc;
  std::vector<Context> stack;  // the open elements' contexts
  VtpCells* cells = nullptr;   // the open <Verts>/<Lines>/<Strips>/<Polys>
  bool in_array = false;       // a <DataArray>/<Array> is open (its depth: array_depth)
  std::size_t array_depth = 0;
  VtpArray array;
  std::string error;            // the first refusal, already located
  bool appended_reached = false;
  std::size_t appended_start = 0;  // the byte after the <AppendedData ...> start tag

  long line() const { return static_cast<long>(XML_GetCurrentLineNumber(xml)); }

  void fail(const std::string& what) {
    if (error.empty()) error = locate(path, line(), -1, what);
    XML_StopParser(xml, XML_FALSE);
  }

  Context top() const { return stack.empty() ? Context::none : stack.back(); }

  static std::optional<std::string_view> attribute(const XML_Char** atts, const char* name) {
    for (int k = 0; atts[k]; k += 2)
      if (std::strcmp(atts[k], name) == 0) return std::string_view(atts[k + 1]);
    return std::nullopt;
  }

  // The count attribute `name` of element `element` (0 when absent), or a refusal (nullopt).
  std::optional<std::int64_t> count_attribute(const XML_Char** atts, const char* element, const char* name,
                                              std::int64_t absent) {
    const auto value = attribute(atts, name);
    if (!value) return absent;
    const auto n = parse_count(*value);
    if (!n) {
      fail(std::string(element) + ": " + name + "=\"" + excerpt(*value) + "\" is not a whole number >= 0");
      return std::nullopt;
    }
    return n;
  }

  void start_vtkfile(const XML_Char** atts) {
    const auto type = attribute(atts, "type");
    if (!type || *type != "PolyData")
      return fail("a VTKFile of type \"" + excerpt(type.value_or("")) +
                  "\": radwalk reads VTK XML PolyData (type=\"PolyData\")");
    const std::string_view order = attribute(atts, "byte_order").value_or("LittleEndian");
    if (order != "LittleEndian" && order != "BigEndian")
      return fail("byte_order=\"" + excerpt(order) + "\": not LittleEndian or BigEndian");
    doc.big_endian = order == "BigEndian";
    const std::string_view header = attribute(atts, "header_type").value_or("UInt32");
    if (header != "UInt32" && header != "UInt64")
      return fail("header_type=\"" + excerpt(header) + "\": not UInt32 or UInt64");
    doc.header_64 = header == "UInt64";
    const std::string_view compressor = attribute(atts, "compressor").value_or("");
    if (compressor == "vtkZLibDataCompressor")
      doc.compressed = true;
    else if (!compressor.empty())
      return fail("compressor=\"" + excerpt(compressor) +
                  "\": radwalk reads uncompressed and vtkZLibDataCompressor data only (write the file with zlib "
                  "or no compression)");
  }

  void start_array(const char* element, const XML_Char** atts) {
    array = VtpArray();
    array.element = element;
    array.line = line();
    array.name = std::string(attribute(atts, "Name").value_or(""));
    const std::string what = array.element + (array.name.empty() ? "" : " '" + excerpt(array.name) + "'");
    const auto type = attribute(atts, "type");
    if (!type) return fail(array.element + " without a type");
    if (std::none_of(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return *type == t; }))
      return fail(array.element + " of type \"" + excerpt(*type) +
                  "\": not one of Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64, "
                  "String");
    array.type = std::string(*type);
    const auto format = attribute(atts, "format");
    if (!format || (*format != "ascii" && *format != "binary" && *format != "appended"))
      return fail(array.element + " without a format of ascii, binary or appended");
    array.format = std::string(*format);
    const auto components = count_attribute(atts, element, "NumberOfComponents", 1);
    if (!components) return;
    if (*components < 1 || *components > kMaxComponents)
      return fail(what + ": NumberOfComponents=\"" + std::to_string(*components) + "\" is not between 1 and " +
                  std::to_string(kMaxComponents));
    array.components = static_cast<int>(*components);
    const auto tuples = count_attribute(atts, element, "NumberOfTuples", -1);
    if (!tuples) return;
    array.tuples = *tuples;
    if (array.format == "appended") {
      const auto offset = count_attribute(atts, element, "offset", -1);
      if (!offset) return;
      if (*offset < 0) return fail(what + ": format appended without an offset");
      array.offset = *offset;
    }
    in_array = true;
    array_depth = stack.size() - 1;  // the array's own entry (its parent's context) is on the stack
  }

  void start(const XML_Char* name_c, const XML_Char** atts) {
    const std::string_view name(name_c);
    const Context at = top();
    Context next = Context::unknown;
    if (in_array) {
      next = Context::unknown;  // InformationKey and the like inside an array
    } else if (at == Context::none) {
      if (name != "VTKFile") return fail("the root element is <" + excerpt(name) + ">, not <VTKFile>");
      start_vtkfile(atts);
      next = Context::vtkfile;
    } else if (at == Context::vtkfile && name == "PolyData") {
      next = Context::polydata;
    } else if (at == Context::vtkfile && name == "AppendedData") {
      const std::string_view encoding = attribute(atts, "encoding").value_or("raw");
      if (encoding != "raw" && encoding != "base64")
        return fail("AppendedData encoding=\"" + excerpt(encoding) + "\": not raw or base64");
      if (doc.has_appended) return fail("a second AppendedData");
      doc.has_appended = true;
      doc.appended_base64 = encoding == "base64";
      doc.appended_line = line();
      appended_reached = true;
      appended_start = static_cast<std::size_t>(XML_GetCurrentByteIndex(xml)) +
                       static_cast<std::size_t>(XML_GetCurrentByteCount(xml));
      XML_StopParser(xml, XML_FALSE);  // binary data follow: the XML ends here
      return;
    } else if (at == Context::polydata && name == "FieldData") {
      next = Context::field_data;
    } else if (at == Context::polydata && name == "Piece") {
      VtpPiece piece;
      piece.line = line();
      const std::pair<const char*, std::int64_t*> counts[] = {{"NumberOfPoints", &piece.points},
                                                               {"NumberOfVerts", &piece.verts},
                                                               {"NumberOfLines", &piece.lines},
                                                               {"NumberOfStrips", &piece.strips},
                                                               {"NumberOfPolys", &piece.polys}};
      for (const auto& [attr, target] : counts) {
        const auto n = count_attribute(atts, "Piece", attr, 0);
        if (!n) return;
        *target = *n;
      }
      doc.pieces.push_back(std::move(piece));
      next = Context::piece;
    } else if (at == Context::piece && (name == "PointData" || name == "CellData" || name == "Points")) {
      next = name == "PointData" ? Context::point_data : name == "CellData" ? Context::cell_data : Context::points;
      if (next == Context::points && doc.pieces.back().has_points) return fail("a second Points in one Piece");
    } else if (at == Context::piece && (name == "Verts" || name == "Lines" || name == "Strips" || name == "Polys")) {
      VtpPiece& piece = doc.pieces.back();
      cells = name == "Verts"    ? &piece.verts_cells
              : name == "Lines"  ? &piece.lines_cells
              : name == "Strips" ? &piece.strips_cells
                                 : &piece.polys_cells;
      if (cells->present) return fail("a second " + std::string(name) + " in one Piece");
      cells->present = true;
      cells->line = line();
      next = Context::cells;
    } else if ((name == "DataArray" || name == "Array") &&
               (at == Context::field_data || at == Context::point_data || at == Context::cell_data ||
                at == Context::points || at == Context::cells)) {
      stack.push_back(at);
      start_array(name == "DataArray" ? "DataArray" : "Array", atts);
      return;
    }
    stack.push_back(next);
  }

  void end() {
    if (in_array && stack.size() == array_depth + 1) {
      in_array = false;
      const Context at = stack[array_depth];
      if (at == Context::field_data) {
        doc.field_data.push_back(std::move(array));
      } else if (at == Context::point_data) {
        doc.pieces.back().point_data.push_back(std::move(array));
      } else if (at == Context::cell_data) {
        doc.pieces.back().cell_data.push_back(std::move(array));
      } else if (at == Context::points) {
        VtpPiece& piece = doc.pieces.back();
        if (piece.has_points) return fail("Points holds a second DataArray");
        piece.has_points = true;
        piece.point_coordinates = std::move(array);
      } else if (at == Context::cells) {
        cells->arrays.push_back(std::move(array));
      }
    }
    if (!stack.empty()) stack.pop_back();
  }

  void text(const XML_Char* s, int length) {
    if (in_array && stack.size() == array_depth + 1) array.text.append(s, static_cast<std::size_t>(length));
  }
};

}  // namespace

VtpDocument parse_vtp_document(const std::string& path, std::string_view bytes) {
  Parser p(path);
  p.xml = XML_ParserCreate(nullptr);
  if (!p.xml) throw std::bad_alloc();
  struct Free {
    XML_Parser xml;
    ~Free() { XML_ParserFree(xml); }
  } free_parser{p.xml};
  XML_SetUserData(p.xml, &p);
  XML_SetElementHandler(
      p.xml,
      [](void* user, const XML_Char* name, const XML_Char** atts) { static_cast<Parser*>(user)->start(name, atts); },
      [](void* user, const XML_Char*) { static_cast<Parser*>(user)->end(); });
  XML_SetCharacterDataHandler(p.xml, [](void* user, const XML_Char* s, int length) {
    static_cast<Parser*>(user)->text(s, length);
  });
  XML_SetStartDoctypeDeclHandler(p.xml, [](void* user, const XML_Char*, const XML_Char*, const XML_Char*, int) {
    static_cast<Parser*>(user)->fail("a DOCTYPE: a .vtp has none (entity definitions are not read)");
  });
  // expat takes an int length: the bytes go in pieces of at most 1 GiB.
  constexpr std::size_t kPiece = std::size_t(1) << 30;
  std::size_t at = 0;
  bool stopped = false;
  do {
    const std::size_t n = std::min(kPiece, bytes.size() - at);
    const bool last = at + n == bytes.size();
    if (XML_Parse(p.xml, bytes.data() + at, static_cast<int>(n), last ? 1 : 0) != XML_STATUS_OK) {
      stopped = true;
      break;
    }
    at += n;
  } while (at < bytes.size());
  if (!p.error.empty()) throw InputError(p.error);
  if (stopped && !p.appended_reached) {
    const XML_Error code = XML_GetErrorCode(p.xml);
    throw InputError(locate(path, static_cast<long>(XML_GetCurrentLineNumber(p.xml)), -1,
                            std::string("not well-formed XML: ") + XML_ErrorString(code)));
  }
  if (p.appended_reached) {
    // After the start tag: white space, then '_', then the data (VTK's layout).
    std::size_t k = std::min(p.appended_start, bytes.size());
    while (k < bytes.size() && (bytes[k] == ' ' || bytes[k] == '\t' || bytes[k] == '\r' || bytes[k] == '\n')) ++k;
    if (k >= bytes.size() || bytes[k] != '_')
      throw InputError(locate(path, p.doc.appended_line, -1, "AppendedData does not start with '_'"));
    p.doc.appended = bytes.substr(k + 1);
  }
  return std::move(p.doc);
}

}  // namespace radwalk
