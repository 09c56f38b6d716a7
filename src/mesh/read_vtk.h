#pragma once
// VTK polygonal surfaces: XML PolyData (.vtp) by radwalk's own reader (mesh/vtp_xml.h: the document;
// mesh/vtk_data_array.h: the arrays' values, every bound checked where it is read), and legacy POLYDATA (.vtk) by
// VTK's vtkPolyDataReader, both from the bytes radwalk read once (read_input_file, so the run id covers them), so
// ParaView users can bring back what they edited, and a .vtp radwalk wrote reads back.
//
// Geometry: every polygon (3 or more corners; more than 4 go through polygon_faces.h) and every triangle strip
// (into triangles, all facing one way); vertices and lines are ignored with a warning. A corner that lies on the
// straight segment between its neighbours (|(b - a) x (c - b)| <= 1e-12 |b - a| |c - b|: the T-junction points
// radwalk's .vtp inserts into polygon edges for display) is dropped first, so cell i of a radwalk .vtp is face i
// again. Points at bit-identical positions are one vertex (exact_vertices.h: the display points split per
// smoothing group join again).
// Materials from the cell data, as radwalk's .vtp writes them (docs/units-and-formats.md): `rho` (3 components)
// is Kd, `E` (3 components, exitance) gives Ke = E / pi; with `material_id` and the field data string table
// `material_names` the materials keep their names (cells of one name with different rho or E become "NAME_2",
// ...); without names, one material per distinct (rho, E), "vtk_material_K". Without a rho field every face gets
// one material named by the file's stem that has no reflectance (Material::reflectance_missing: `--set NAME.Kd`
// gives it). Groups from `object_id` / `group_id` and the tables `object_names` / `group_names`. A `side` field
// (radwalk's two-sided scenes: 0 front, 1 back) drops the back cells and makes the materials of the front cells
// two-sided, so the scene reads back as it was written.
// A .vtp: the subset of docs/units-and-formats.md; offsets rise to the end of the connectivity and every point id is
// below its piece's points, else one InputError naming the file, the XML line and the array. Several pieces are
// one mesh (their points and cells in piece order). A value of rho or E that is not finite is refused.
// A .vtk, bounded: before VTK parses anything, every count the file declares (the counts after POINTS, POLYGONS,
// TRIANGLE_STRIPS, VERTICES, LINES, CELL_DATA, POINT_DATA and FIELD arrays) times the largest component count must
// fit the file's bytes; and, since VTK 9.1's legacy reader crashes on them (found by the vtk fuzz harness,
// tests/fuzz/fuzz_vtk.cpp), the numbers of the POINTS and cell sections of an ASCII file (keywords matched by
// prefix, as VTK matches them) and the type of POINTS (one of VTK's numeric type names, exactly). A VTK error is one InputError naming the file and VTK's own message; face f is the
// f-th surface cell.
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_vtk_polydata(const std::string& path, const ReadOptions& options = {});

// The same for bytes already read; `xml` picks the .vtp reader (else the legacy .vtk reader).
Mesh read_vtk_polydata_bytes(const std::string& path, std::string_view bytes, bool xml,
                             const ReadOptions& options = {});

}  // namespace radwalk
