#pragma once
// VTK XML PolyData (.vtp) output that ParaView opens: binary, zlib-compressed, written atomically.
// Geometry: the patch corner points and one polygon per patch (patch i = cell i).
// Cell data: the given fields. Point data: for each field, the area-weighted average over the patches that share
// the point (for smooth display; the cell data are the solution).
#include <string>
#include <vector>

#include "io/cell_field.h"

namespace radwalk {

void write_vtp(const std::string& path, const PatchSet& patches, const std::vector<CellField>& fields);

// A ParaView collection (.pvd) listing (time, file) pairs, e.g. the steps of a progressive solve.
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps);

}  // namespace radwalk
