#pragma once
// Writes patches as OBJ + MTL so that they load back as the same scene: one material per material the patches use
// (Kd = rho, Ke = E / pi, plus the non-diffuse parameters; a later material of a name already written, such as
// validation's two-sided copy of a material beside the one-sided original, is written as NAME_2, NAME_3, ...), faces in patch order (patch i = face i of the output),
// each patch's object and group as `o` and `g` statements. Two-sided faces: only the front patches are written
// (so the file has no duplicate faces) and their materials get `radwalk_two_sided 1`, so that reading the file adds
// the back patches again (front patch i is face i; the back patches follow, as add_back_sides makes them). Names
// are written as the OBJ name rule reads them back: control characters and '#' become '_'.
// The MTL file is PATH with its extension replaced by .mtl. Both files are written atomically.
// run_id: when not empty, both files' second line is the comment "# run_id RUN_ID" (apps/run_metadata.h).
// Contact pairs (patch/contact_pairs.h: a floor piece cut along a footprint and the bottom lying on it, two front
// patches on the same corners back to back) are named after the faces, one comment line per pair,
// "# radwalk_contact_pair A B" with A < B the pair's face numbers in the file (1-based, as `f` statements count),
// in the order of their lower patch: radwalk's OBJ reader honours them in a file whose first line is this writer's
// "# radwalk patches of ..." (mesh/read_obj.h), so that the pair reads back as two one-sided faces instead of one
// two-sided face; other readers skip them as comments.
// Orientation and sides: after the first line (and the run id), the comment line kObjAsWrittenComment says that
// the faces are this run's patches, oriented and sided as the run made them (the front patches' corner order, the
// two-sided materials), so that radwalk's reader keeps their orientation instead of deriving it again
// (Mesh::as_written, mesh/validate.h): the file reads back as the same patches facing the same way, as the .vtp
// does. Without it the cut floor piece under a bottomless block would close the block's shell and be turned.
#include <string>

#include "patch/patch_set.h"

namespace radwalk {

void write_obj(const std::string& path, const PatchSet& patches, const std::string& run_id = "");

}  // namespace radwalk
