#pragma once
// The former per-patch CSV writer (printf's %.12g per number, every cell inserted into the stream), kept as a
// reference: the tests check that io/csv_writer.h writes the same bytes, and bench_csv times it beside the
// current one.
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "io/cell_field.h"
#include "io/csv_writer.h"
#include "patch/patch_set.h"

namespace radwalk::test {

inline std::string printf_csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

// The rows of write_patch_csv (header excluded) as the former writer formatted them.
inline void former_patch_csv_rows(std::ostream& out, const PatchSet& patches, const std::vector<CellField>& extra,
                                  const std::string& run_id = "") {
  const std::string last = run_id.empty() ? "" : "," + run_id;
  const bool sides = !patches.side.empty();
  for (std::size_t i = 0; i < patches.size(); ++i) {
    out << i << ',' << patches.face[i];
    if (sides) out << ',' << (patches.is_back(i) ? 1 : 0);
    out << ',' << printf_csv_number(patches.area[i]);
    for (int c = 0; c < 3; ++c) out << ',' << printf_csv_number(patches.centroid[i][c]);
    for (int c = 0; c < 3; ++c) out << ',' << printf_csv_number(patches.normal[i][c]);
    for (int c = 0; c < 3; ++c) out << ',' << printf_csv_number(patches.rho[i][c]);
    for (int c = 0; c < 3; ++c) out << ',' << printf_csv_number(patches.E[i][c]);
    out << ',' << csv_text(patches.object_of(i)) << ',' << csv_text(patches.group_of(i)) << ','
        << csv_text(patches.material_of(i));
    for (const CellField& f : extra)
      for (int c = 0; c < f.components; ++c) out << ',' << printf_csv_number(f.values[i * f.components + c]);
    out << last << '\n';
  }
}

}  // namespace radwalk::test
