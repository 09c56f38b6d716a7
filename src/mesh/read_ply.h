#pragma once
// Stanford PLY input (ascii, binary_little_endian, binary_big_endian), read once and parsed by radwalk itself.
//
// Header: `ply`, `format`, `comment`/`obj_info`, `element NAME COUNT`, `property TYPE NAME` and
// `property list COUNT_TYPE ITEM_TYPE NAME`, `end_header` (lines end at LF or CRLF). TYPE is one of char, uchar,
// short, ushort, int, uint, float, double or their sized names (int8 ... float64).
// What radwalk reads:
//   - element `vertex`: properties x, y, z (any numeric type; doubles stay doubles, so UTM-sized coordinates keep
//     their centimetres);
//   - element `face`: the list `vertex_indices` (or `vertex_index`), 3 or more indices (polygons of more than 4
//     corners are triangulated as in OBJ, polygon_faces.h), and optional colours red, green, blue used as the diffuse reflectance rho: integer types as
//     colour / 255 with colour in 0..255, float types as given in [0, 1]; one material per distinct colour, named
//     "ply_R_G_B" (integers) or "ply_colour_K" (floats). Without face colours every face gets rho 0.5, with a
//     warning. PLY carries no emission: a PLY scene has no emitter unless one is added later.
//   - every other element and property is read past and ignored.
// Face f is the f-th face of the file (none is dropped: repeated indices are validate_mesh's to report). For
// ascii files face_line holds the line where face f starts; for binary files it is 0.
// Bounded: an element count must fit the bytes that follow the header (each element takes at least its fixed-size
// properties in binary, at least one character per value in ascii), so a 200-byte file that declares 4e9 vertices
// is refused before anything is allocated. Every refusal is one InputError naming the file (and line or element).
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_ply(const std::string& path, const ReadOptions& options = {});

// The same for the bytes of a PLY file already read (path names it in messages).
Mesh read_ply_bytes(const std::string& path, std::string_view bytes, const ReadOptions& options = {});

}  // namespace radwalk
