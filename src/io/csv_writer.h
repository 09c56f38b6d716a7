#pragma once
// Per-patch CSV: a header row, then one row per patch. Columns: patch,face,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,
// rho_b,E_r,E_g,E_b,object,group,material (the names of the patch's object, group and material as the scene file
// spells them, empty where none; quoted as RFC 4180 says when they hold a comma, quote or line break), then each
// extra field (a 1-component field is one column NAME, a 3-component field is
// NAME_r,NAME_g,NAME_b). In a scene with two-sided faces (PatchSet::side not empty) a column side (0 front, 1 back)
// follows face. Numbers are printed with 12 significant digits ("nan" never appears: non-finite values
// are written as empty cells). Written atomically, or to
// standard output when the path is "-" (core/standard_output.h).
// run_id: when not empty, a last column `run_id` holding it on every row (the run that wrote the file,
// apps/run_metadata.h; a constant column keeps the file one plain table for every CSV reader).
#include <string>
#include <vector>

#include "io/cell_field.h"

namespace radwalk {

void write_patch_csv(const std::string& path, const PatchSet& patches, const std::vector<CellField>& extra,
                     const std::string& run_id = "");

// Writes a generic table (header + rows of already formatted cells), atomically or to standard output ("-"); run_id
// as for write_patch_csv.
void write_csv_table(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::vector<std::string>>& rows, const std::string& run_id = "");

// A text cell: as it is, or in double quotes (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_text(const std::string& text);

// Formats a number for CSV: 12 significant digits, empty for NaN or infinity.
std::string csv_number(double v);

}  // namespace radwalk
