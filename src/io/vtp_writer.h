#pragma once
// VTK XML PolyData (.vtp) output that ParaView opens ready to look at: binary, zlib-compressed, written atomically.
//
// Geometry: the display mesh of the patches (patch/display_mesh.h): one polygon per patch (patch i = cell i),
// points split per smoothing group (plane, material, emitter status), T-junction points inserted into the
// polygons' edges.
// Cell data: every field (FieldKind::count as Int64, the others as Float64); 3-component quantities have the
// component names R, G, B. The radiosity, given as the 3-component quantity field B (RGB, W per square length
// unit), is written as three arrays: B, one component, the channel mean (B_R + B_G + B_B) / 3 in the same unit
// (for grey data the radiosity itself), the active scalars (ParaView colours by it on Apply); B_rgb, the RGB
// triple (both with the information key vtkDataArray::UNITS_LABEL "W/unit^2"); and the display array B_srgb:
// unsigned char x 3 (R, G, B), srgb8_from_radiosity(B_rgb) per channel (core/srgb.h: radiance B / pi, exposure 1,
// clamped to [0, 1], exact sRGB; the mapping of the path tracer's PNG), so that ParaView shows true colours with
// "Map Scalars" off.
// Point data: each FieldKind::quantity field averaged over the patches of one smoothing group at each display
// point (area-weighted; for smooth display: the cell data are the solution), the radiosity again as B, B_rgb and
// B_srgb of the averaged triple.
// No point fields for counts and geometry.
// Names: the cell data object_id, group_id and material_id (Int64, -1 for none) index the field data's string
// tables object_names, group_names and material_names (the patch's object, group and material as the scene file
// names them; PatchSet::object_of, group_of, material_of); a table with no name and its ids are left out.
// Field data: the metadata (vtp_metadata.h), then the name tables.
// Throws std::logic_error for a field of the wrong size or with a name that is not usable in ParaView
// (paraview_name(name) != name, or the Calculator's reserved word `var`), or a field B_rgb or B_srgb beside the
// radiosity B (the writer makes them), before the file is created.
// Memory: the file is encoded as it is written (one array at a time, each compressed in blocks; io/vtk_binary.h),
// so besides the fields the writer holds the display mesh, one point field and one compressed array at a time.
#include <string>
#include <vector>

#include "io/cell_field.h"
#include "io/vtp_metadata.h"
#include "patch/display_mesh.h"

namespace radwalk {

void write_vtp(const std::string& path, const PatchSet& patches, const std::vector<CellField>& fields,
               const VtpMetadata& metadata = {});
// The same for fields held elsewhere (no copy): fields[k] is the k-th field, alive until the call returns; and,
// when mesh is given, with that display mesh, which must be make_display_mesh(patches) (a caller builds it before
// it allocates the fields, so that the peak of building it does not come on top of them).
void write_vtp_fields(const std::string& path, const PatchSet& patches, const std::vector<const CellField*>& fields,
                      const VtpMetadata& metadata = {}, const DisplayMesh* mesh = nullptr);

// A ParaView collection (.pvd) listing (time, file) pairs, e.g. the steps of a progressive solve.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps);

}  // namespace radwalk
