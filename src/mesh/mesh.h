#pragma once
// The scene as the user gave it: vertices, faces (triangles or quads) and materials, before patching.
// Messages and the CSV `face` column name input faces (face_source): face f is input face f unless a repair
// (triangulating an n-gon, splitting a bent quad, dropping a zero-area face) changed the face list.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/finding.h"
#include "mesh/material.h"

namespace radwalk {

// How readers treat what they can repair (polygons of more than 4 corners, ...): repair with a warning, or with
// strict refuse.
struct ReadOptions {
  bool strict = false;
};

struct Mesh {
  std::string path;                              // file it came from (for messages)
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int32_t, 4>> faces;  // vertex indices; [3] == -1 for a triangle
  std::vector<std::int32_t> face_material;       // index into materials
  std::vector<long> face_line;                   // source line of the face (OBJ), 0 if unknown
  std::vector<std::int32_t> face_source;         // the input face (f-th face of the file) face f comes from: f itself
                                                 // unless a repair split or dropped faces (pieces share it)
  std::vector<std::int32_t> face_group;          // index into groups, -1 outside any (OBJ `o` and `g`)
  std::vector<std::string> groups;               // "object 'chair', group 'seat'" as the file names them
  std::vector<std::string> group_object;         // the object name of groups[i] ("" if none)
  std::vector<std::string> group_name;           // the group name of groups[i] ("" if none)
  std::vector<Material> materials;
  std::vector<std::string> warnings;             // one line per repair or notice, naming the face (after
                                                 // validate_mesh: the non-error findings, grouped by kind)
  std::vector<Finding> findings;                 // what the reader and validation found (finding.h)
  // Contact pairs the file declares (radwalk's own .vtp: its cell field contact_pair, mesh/read_vtk.h; radwalk's own
  // .obj: its "# radwalk_contact_pair" lines, mesh/read_obj.h): the pair
  // id of input face s (Mesh::source_face), -1 for none; empty for other files. Two faces of one pair that lie
  // back to back on the same corners stay two one-sided faces (a floor piece cut along a footprint and the bottom
  // lying on it, patch/contact_pairs.h) instead of becoming one two-sided face (mesh/validate.h).
  std::vector<std::int32_t> source_contact_pair;
  // The faces are a run's patches as radwalk wrote them (its own .vtp, mesh/read_vtk.h, or .obj, mesh/read_obj.h):
  // that run oriented them and gave them their sides (the .vtp's side field, the .obj's two-sided materials), so
  // validation keeps both (mesh/validate.h, orient_faces).
  bool as_written = false;

  std::size_t face_count() const { return faces.size(); }
  bool is_quad(std::size_t f) const { return faces[f][3] >= 0; }
  int corner_count(std::size_t f) const { return is_quad(f) ? 4 : 3; }
  // The input face of face f (f when face_source is not filled).
  long source_face(std::size_t f) const { return f < face_source.size() ? face_source[f] : static_cast<long>(f); }
  // The contact pair face f belongs to (source_contact_pair of its input face), -1 for none.
  std::int32_t contact_pair(std::size_t f) const {
    const long s = source_face(f);
    return s >= 0 && static_cast<std::size_t>(s) < source_contact_pair.size()
               ? source_contact_pair[static_cast<std::size_t>(s)]
               : -1;
  }
  // " (object 'chair', group 'seat', material 'red')": where face f is in the file, as far as known ("" if
  // nothing is).
  std::string context(std::size_t f) const;
  // The same for a face with this material and group (indices, -1 for none), e.g. one not yet added.
  std::string context_of(std::int32_t material, std::int32_t group) const;
  // A finding about face f: its input face, line, object, group and material filled in.
  Finding finding(std::size_t f, std::string kind, Severity severity, std::string message) const;
  // The same for input face `source` at `line` with this material and group (indices, -1 for none), e.g. one
  // not yet added; source -1 and line 0 for a scene-wide finding.
  Finding finding_of(long source, long line, std::int32_t material, std::int32_t group, std::string kind,
                     Severity severity, std::string message) const;
};

}  // namespace radwalk
