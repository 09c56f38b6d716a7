#pragma once
// Wavefront OBJ + MTL input.
//
// Face f of the Mesh is the f-th `f` statement of the file (0-based, across groups and objects); face_line[f] is
// its line. Vertices keep file order (vertex i = i-th `v` statement). Materials come from the `mtllib` files in
// statement order, newmtl blocks in file order (see mtl.h for the statements and the BsdfKind mapping); a face
// before any `usemtl` gets material -1 (validate_mesh gives it a default with a warning).
//
// The file is read once and parsed from those bytes by one scanner (text_scan.h: one line rule, one name rule for
// OBJ and MTL alike). What it reads: `v` (exact, correctly rounded coordinates), `f` (the vertex index of each
// corner; texture and normal indices are ignored), `usemtl NAME` and `newmtl NAME` (a name is the rest of the
// statement, spaces included), `mtllib` (the rest of the statement names one file if such a file exists, else a
// list of files separated by spaces; "\ " escapes a space; absolute paths are used as given). Other statements
// (vn, vt, s, ...) are ignored; `l` and `p` are ignored with a warning.
// Faces of more than 4 corners are triangulated (polygon_faces.h; a repair, reported) unless options.strict; `o`
// and `g` name the face's object and group in messages (Mesh::groups).
// Refused at once with an InputError naming file and line: a missing mtllib file, an MTL statement radwalk cannot
// read. Everything else is collected, so that one run reports every finding: as error findings naming file, line
// and face (mesh.findings; the face is left out and validate_mesh refuses the scene with every other finding): a
// vertex without three numbers (kept as a NaN vertex so that the numbering holds), a corner that is not an index,
// index 0, a relative index before the first vertex, an index too large, and with options.strict an unknown
// usemtl name (per face that uses it); as repairs (refusals with options.strict): a face of fewer than 3 corners,
// repeated corners (polygon_faces.h), and an unknown usemtl name, whose faces get the default material (Kd 0.5, no
// emission, as validate_mesh gives a face without material) under that name, one repair per name naming its first
// usemtl line, the libraries searched and the count of faces. Non-finite coordinates are kept (validate_mesh refuses the faces that use them).
// tinyobjloader is the independent reference parse of the same bytes in the tests (tests/mesh), not a second
// reader here.
// Out-of-range vertex indices are kept and reported by validate_mesh.
// Contact pairs of an OBJ radwalk wrote (io/obj_writer.h; docs/units-and-formats.md): in a file whose first line
// starts with kObjRadwalkHeader, a comment line "# radwalk_contact_pair A B" (kObjContactPairComment, then two face
// numbers counted as `f` statements are, from 1) declares faces A and B a contact pair (Mesh::source_contact_pair,
// numbered in the order of the lines), which validation keeps as two one-sided faces when they lie on the same
// corners back to back (mesh/validate.h) instead of making them one two-sided face. A declaration that is not two
// different face numbers of the file, or names a face another declaration named, is not used (a warning finding
// naming its line). In other files these lines are comments like any other.
// Faces as written: in a file whose first line starts with kObjRadwalkHeader, a comment line that starts with
// kObjAsWrittenComment (the writer puts it after its header) sets Mesh::as_written: the faces are a run's patches,
// oriented and given their sides (`radwalk_two_sided 1` materials) by that run, so validation keeps both
// (mesh/validate.h) and the file reads back face for face, facing as written. Elsewhere it is a comment.
#include <functional>
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace radwalk {

// The first line of an OBJ radwalk wrote starts with this; its contact-pair lines with kObjContactPairComment.
inline constexpr std::string_view kObjRadwalkHeader = "# radwalk patches of ";
inline constexpr std::string_view kObjContactPairComment = "# radwalk_contact_pair";
// The line that says the faces are oriented and sided as written (above).
inline constexpr std::string_view kObjAsWrittenComment = "# radwalk_as_written";

// Where the material libraries of an OBJ come from. exists(path) says whether a library of that (resolved)
// path can be read: it decides how an mtllib statement is split (see above) and whether a library is "not
// found"; read(path) gives a library's bytes, once per library, after exists(path) said yes.
struct MtlSource {
  std::function<bool(const std::string& path)> exists;
  std::function<std::string(const std::string& path)> read;
};

// Libraries as regular files on disk, each read once with read_input_file (what read_obj uses).
MtlSource mtl_files_on_disk();

// read_obj_text(path, read_input_file(path), mtl_files_on_disk(), options).
Mesh read_obj(const std::string& path, const ReadOptions& options = {});

// The bytes of an OBJ file already read: `path` names it in messages and is the base of relative mtllib
// names; the libraries come from `libraries`. Gives exactly what read_obj gives for a file with these bytes.
Mesh read_obj_text(const std::string& path, std::string_view text, const MtlSource& libraries,
                   const ReadOptions& options = {});

}  // namespace radwalk
