#pragma once
// A legacy VTK POLYDATA file (.vtk), read by radwalk's own reader, ASCII or BINARY (big-endian), as VTK's
// legacy writer writes it (docs/units-and-formats.md):
//
//   # vtk DataFile Version M.m        (the first line; M >= 5: cells as OFFSETS and CONNECTIVITY arrays)
//   TITLE                             (any line)
//   ASCII | BINARY
//   DATASET POLYDATA
//   then, in any order: FIELD NAME n (n arrays: NAME k tuples TYPE, or NULL_ARRAY), POINTS n TYPE,
//   VERTICES | LINES | POLYGONS | TRIANGLE_STRIPS, each as
//     M < 5:  n size, then `size` whole numbers: each cell's count of points, then its point ids;
//     M >= 5: n+1 size, OFFSETS TYPE (n+1 offsets, rising from 0 to size), CONNECTIVITY TYPE (size point ids);
//   then CELL_DATA n and POINT_DATA n sections (n: the cells and the points read), each of SCALARS NAME TYPE [k]
//   LOOKUP_TABLE T, COLOR_SCALARS NAME k, LOOKUP_TABLE NAME n, VECTORS, NORMALS, TENSORS, TENSORS6,
//   TEXTURE_COORDINATES NAME d TYPE, GLOBAL_IDS, PEDIGREE_IDS, EDGE_FLAGS (point data) and FIELD arrays
//   (mesh/vtk_legacy_array.h: the values of each).
// Keywords and type names in any case, exactly (VTK matched a prefix: "POLYGONS`1" was POLYGONS; here it is
// refused). Cell data is read the way radwalk uses it: every named numeric array of the cell sections, whichever
// section gave it (VTK's reader keeps only the first SCALARS, VECTORS, ... of a section and would drop a second
// SCALARS E after SCALARS rho); COLOR_SCALARS hold bytes as VTK stores them (ASCII: round(255 v)).
//
// Bounded where read: every count against the bytes left before anything is sized by it; points at most 2^30,
// each finite; cells: a classic section's counts must add up to its size and make n cells, ids whole numbers from
// 0 to 2^31 - 1, offsets rising from 0 to the connectivity's size, every point id below the points; CELL_DATA
// and POINT_DATA must count the cells and points read; a section given twice, or an array radwalk uses given
// twice, is refused. Every refusal is one InputError naming the file, the line (ASCII; a BINARY file after its
// first binary block: the byte) and what is wrong.
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"

namespace radwalk {

// One kind of cells: cell c's point ids are ids[offsets[c], offsets[c + 1]).
struct LegacyCells {
  std::vector<std::int64_t> offsets;  // empty when the file has none of this kind, else cells + 1 values
  std::vector<std::int32_t> ids;
  std::size_t count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

// What the caller uses: cell data arrays by name (with their component count) and field data string arrays by
// name. Only these are kept; everything else is checked and skipped.
struct LegacyWanted {
  std::map<std::string, int> cell_arrays;
  std::vector<std::string> field_strings;
};

struct LegacyPolyData {
  std::vector<Vec3> points;
  LegacyCells verts, lines, polys, strips;
  // The wanted cell data arrays present with their component count: cells x components values each, cells in
  // VTK's order (vertices, lines, polygons, strips).
  std::map<std::string, std::vector<double>> cell_data;
  std::map<std::string, std::vector<std::string>> field_strings;
};

LegacyPolyData parse_vtk_legacy(const std::string& path, std::string_view bytes, const LegacyWanted& wanted);

}  // namespace radwalk
