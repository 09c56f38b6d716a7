#pragma once
// VTK polygonal surfaces: XML PolyData (.vtp) by radwalk's own reader (mesh/vtp_xml.h: the document;
// mesh/vtk_data_array.h: the arrays' values, every bound checked where it is read), and legacy POLYDATA (.vtk) by
// radwalk's own reader too (mesh/vtk_legacy.h: ASCII and BINARY, the classic and the version 5 cell layouts), both
// from the bytes radwalk read once (read_input_file, so the run id covers them), so ParaView users can bring back
// what they edited, and a .vtp radwalk wrote reads back. Neither uses VTK.
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
// radwalk's own file as written (the cell fields `patch` and `face` present, `patch` numbering the cells 0, 1, ...
// in order, no vertex or line cells) sets Mesh::as_written: its faces are a run's patches, which that run already
// oriented and gave their sides, so validation keeps their orientation and sides (mesh/validate.h). In such a file
// only, a `contact_pair` field (patch/contact_pairs.h: the pair id of two front cells lying on each other back to
// back, -1 for none) fills Mesh::source_contact_pair for ids of exactly two front polygon cells, so that validation
// keeps each pair as two one-sided faces instead of merging them into one two-sided face. So a .vtp radwalk wrote
// reads back cell for cell: the same faces in the same order, facing the same way.
// A .vtp: the subset of docs/units-and-formats.md; offsets rise to the end of the connectivity and every point id is
// below its piece's points, else one InputError naming the file, the XML line and the array. Several pieces are
// one mesh (their points and cells in piece order). A value of rho or E that is not finite is refused.
// A .vtk: the subset and the bounds of mesh/vtk_legacy.h (every count against the bytes left where it is read,
// point ids below the points, CELL_DATA counting the cells); the cell data arrays above from any section of the
// cell data (SCALARS, VECTORS, FIELD, ...), the name tables from the data set's FIELD. Face f is the f-th surface
// cell.
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_vtk_polydata(const std::string& path, const ReadOptions& options = {});

// The same for bytes already read; `xml` picks the .vtp reader (else the legacy .vtk reader).
Mesh read_vtk_polydata_bytes(const std::string& path, std::string_view bytes, bool xml,
                             const ReadOptions& options = {});

}  // namespace radwalk
