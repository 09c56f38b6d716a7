#pragma once
// STL input (ascii and binary), read once and parsed by radwalk itself.
//
// Which form: a file whose size is exactly 84 + 50 n bytes, n the little-endian count at byte 80, is binary
// (whatever its first bytes say: binary headers often start with "solid"); otherwise a file whose first word is
// `solid` and that is text (no NUL byte, bytes 80 to 83 printable ASCII or blanks) is ascii; anything else is refused, a binary file whose size does not match its
// count by naming both.
// Ascii: `solid [NAME]`, then facets `facet normal nx ny nz` / `outer loop` / `vertex x y z` (3 or more) /
// `endloop` / `endfacet`, then `endsolid [NAME]`; several solids may follow one another. Numbers are exact
// doubles (text_scan.h); keywords are lower case as the format writes them. Binary: an 80-byte header, the count,
// then per triangle 12 little-endian floats (normal, three corners) and a 2-byte attribute (ignored).
// The facet normal is read and ignored: the corner order (counter-clockwise seen from the front) defines the
// front, as in every other format radwalk reads.
// Names: each ascii solid is a group named by its NAME (Mesh::group_name; an unnamed solid, and the one solid of a
// binary file, is named by the file's stem, with "_K" appended for the K-th unnamed solid from the second on).
// STL carries no materials: each group's faces get a material of the group's name that has no reflectance
// (Material::reflectance_missing), so validate_mesh refuses them until `--set NAME.Kd=r,g,b` gives one
// (`--set NAME.Ke=r,g,b` makes it an emitter).
// Corners at bit-identical positions are one vertex (exact_vertices.h). Face f is the f-th facet of the file;
// face_line is the line of its `facet` (0 for binary).
// Bounded: a binary count must match the file size before anything is allocated; an ascii file allocates in
// proportion to its facets. Every refusal is one InputError naming the file (and line).
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_stl(const std::string& path, const ReadOptions& options = {});

// The same for the bytes of an STL file already read (path names it in messages and gives the stem).
Mesh read_stl_bytes(const std::string& path, std::string_view bytes, const ReadOptions& options = {});

}  // namespace radwalk
