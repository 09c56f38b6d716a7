#pragma once
// The document of a VTK XML PolyData file (.vtp), as VTK 9 and radwalk write it: the <VTKFile> attributes that say
// how arrays are stored, the field data arrays, the pieces with their counts, Points, cell arrays (Verts, Lines,
// Strips, Polys: connectivity and offsets) and point and cell data arrays, each array with its attributes and
// its raw content (the text of an ascii or binary array, or an offset into the appended data). Nothing is decoded
// here (mesh/vtk_data_array.h decodes an array's values).
//
// Parsed by expat (well-formed XML only; a DOCTYPE, and with it every entity definition, is refused). The
// <AppendedData> element is where XML ends: after its start tag, white space and '_', the rest of the file is the
// appended bytes (raw binary or base64), which no XML parser could read; VTK reads it the same way.
// Elements radwalk does not know (InformationKey, ...) are skipped with their content. Every refusal is one
// InputError "FILE:LINE: what is wrong", LINE the XML line expat reports for the element.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace radwalk {

// One <DataArray> or <Array> element.
struct VtpArray {
  std::string element;        // "DataArray" or "Array"
  std::string name;           // Name (may be empty)
  std::string type;           // Int8 ... Float64, or String (checked: one of these)
  std::string format;         // ascii, binary or appended (checked)
  int components = 1;         // NumberOfComponents (checked: 1 .. kMaxComponents)
  std::int64_t tuples = -1;   // NumberOfTuples, or -1 when absent (checked: >= 0)
  std::int64_t offset = -1;   // offset into the appended data (format appended; checked: >= 0)
  std::string text;           // the element's own character data (ascii and binary formats)
  long line = 0;              // the XML line of its start tag
};

// One cell kind of a piece: <Verts>, <Lines>, <Strips> or <Polys>.
struct VtpCells {
  bool present = false;
  long line = 0;
  std::vector<VtpArray> arrays;  // connectivity and offsets, by Name
};

struct VtpPiece {
  long line = 0;
  std::int64_t points = 0, verts = 0, lines = 0, strips = 0, polys = 0;  // the NumberOf... attributes
  bool has_points = false;
  VtpArray point_coordinates;  // the DataArray of <Points>
  VtpCells verts_cells, lines_cells, strips_cells, polys_cells;
  std::vector<VtpArray> point_data, cell_data;
};

struct VtpDocument {
  bool big_endian = false;   // byte_order (LittleEndian when absent, as VTK takes it)
  bool header_64 = false;    // header_type UInt64 (UInt32 when absent)
  bool compressed = false;   // compressor vtkZLibDataCompressor (others refused)
  std::vector<VtpArray> field_data;
  std::vector<VtpPiece> pieces;
  bool appended_base64 = false;   // <AppendedData encoding="base64"> (else raw)
  bool has_appended = false;
  std::string_view appended;      // the appended bytes after '_' (a view into the file's bytes)
  long appended_line = 0;
};

inline constexpr int kMaxComponents = 1024;  // more components than any array radwalk or ParaView writes

// The document of the .vtp `bytes` (the file `path`, for messages). The returned document views into `bytes`.
VtpDocument parse_vtp_document(const std::string& path, std::string_view bytes);

}  // namespace radwalk
