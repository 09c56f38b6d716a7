#include "io/obj_writer.h"

#include <cmath>
#include <filesystem>
#include <ostream>
#include <set>
#include <vector>

#include "core/atomic_write.h"
#include "core/format_number.h"
#include "mesh/read_obj.h"
#include "patch/contact_pairs.h"

namespace radwalk {
namespace {

std::string num(double v) {
  return format_number(v, 17);
}

std::string rgb(const Rgb& c) { return num(c[0]) + " " + num(c[1]) + " " + num(c[2]); }

// A name as one OBJ/MTL statement reads it back (text_scan.h name rule): control characters and '#' (a comment)
// become '_', leading and trailing blanks are dropped.
std::string statement_name(const std::string& name) {
  std::string out;
  for (const char c : name) out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7F || c == '#') ? '_' : c;
  const std::size_t first = out.find_first_not_of(" \t"), last = out.find_last_not_of(" \t");
  return first == std::string::npos ? std::string() : out.substr(first, last - first + 1);
}

}  // namespace

void write_obj(const std::string& path, const PatchSet& patches, const std::string& run_id) {
  const std::string id_line = run_id.empty() ? "" : "# run_id " + run_id + "\n";
  const std::filesystem::path obj(path);
  const std::filesystem::path mtl = std::filesystem::path(obj).replace_extension(".mtl");

  // Materials of two-sided faces: the file gets their front patches only, and the statement radwalk_two_sided 1
  // makes the reader add the back patches again.
  std::vector<bool> two_sided(patches.materials.size(), false);
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (patches.two_sided(i)) two_sided[static_cast<std::size_t>(patches.material[i])] = true;

  // The materials the patches use, each under a name of its own: validation's two-sided copy of a material keeps
  // its name, and an OBJ reader takes the first definition of a name, so a later material of a name already
  // written becomes NAME_2, NAME_3, ... (as the .vtp reader names materials that share a name); unused ones are
  // left out.
  std::vector<bool> used(patches.materials.size(), false);
  for (std::size_t i = 0; i < patches.size(); ++i) used[static_cast<std::size_t>(patches.material[i])] = true;
  std::vector<std::string> name_of(patches.materials.size());
  std::set<std::string> taken;
  for (std::size_t k = 0; k < patches.materials.size(); ++k) {
    if (!used[k]) continue;
    const std::string name = statement_name(patches.materials[k].name);
    name_of[k] = name;
    for (int n = 2; !taken.insert(name_of[k]).second; ++n) name_of[k] = name + "_" + std::to_string(n);
  }

  // Both files are written completely before either replaces an old one (commit_together): a full disk leaves
  // the old pair, never a new .mtl beside an old .obj.
  PendingFile mtl_file(mtl.string()), obj_file(path);
  mtl_file.write([&](std::ostream& out) {
    out << "# radwalk patches of " << patches.source << "\n" << id_line
        << "# Kd = diffuse reflectance, Ke = emitted radiance\n";
    for (std::size_t k = 0; k < patches.materials.size(); ++k) {
      if (!used[k]) continue;
      const Material& m = patches.materials[k];
      out << "\nnewmtl " << name_of[k] << "\nKd " << rgb(m.Kd) << "\nKe " << rgb(m.Ke) << "\n";
      if (two_sided[k]) out << "radwalk_two_sided 1\n";
      if (m.illum >= 0) out << "illum " << m.illum << "\n";
      if (m.kind != BsdfKind::diffuse) {
        out << "Ks " << rgb(m.Ks) << "\nNi " << num(m.Ni) << "\n";
        // The reader takes Pr as perceptual roughness (GGX alpha = Pr^2): write Pr = sqrt(alpha), not alpha.
        if (m.roughness > 0) out << "Pr " << num(std::sqrt(m.roughness)) << "\n";
        if (m.metallic > 0) out << "Pm " << num(m.metallic) << "\n";
      }
    }
  });
  obj_file.write([&](std::ostream& out) {
    out << kObjRadwalkHeader << patches.source << ": " << patches.size() << " patches\n" << id_line;
    // The faces are this run's patches, oriented and sided as it made them: radwalk's reader keeps them so.
    out << kObjAsWrittenComment << ": faces oriented and sided as this run made them\n";
    out << "mtllib " << mtl.filename().string() << "\n";
    for (const Vec3& p : patches.points) out << "v " << num(p.x()) << ' ' << num(p.y()) << ' ' << num(p.z()) << '\n';
    int current = -1;
    std::string object, group;  // the statements in force: none at the start
    std::vector<long> face_of(patches.size(), 0);  // the file's face number (1-based) of each written patch
    long faces = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      if (patches.is_back(i)) continue;  // written by its front (radwalk_two_sided above)
      face_of[i] = ++faces;
      // o starts an object and leaves its group, so each change writes o, then g when there is a group.
      if (object != patches.object_of(i) || group != patches.group_of(i)) {
        object = patches.object_of(i);
        group = patches.group_of(i);
        out << "o";
        if (!object.empty()) out << ' ' << statement_name(object);
        out << '\n';
        if (!group.empty()) out << "g " << statement_name(group) << '\n';
      }
      if (patches.material[i] != current) {
        current = patches.material[i];
        out << "usemtl " << name_of[static_cast<std::size_t>(current)] << '\n';
      }
      out << 'f';
      for (int k = 0; k < patches.corner_count(i); ++k) out << ' ' << patches.corners[i][k] + 1;
      out << '\n';
    }
    // The contact pairs, as comments other readers skip (docs/units-and-formats.md, "OBJ radwalk wrote").
    const std::vector<std::int32_t> pair = contact_pair_ids(patches);
    std::vector<long> first(patches.size(), 0);  // pair id -> its lower patch's face number
    for (std::size_t i = 0; i < patches.size(); ++i) {
      if (pair[i] < 0) continue;
      long& lower = first[static_cast<std::size_t>(pair[i])];
      if (lower == 0)
        lower = face_of[i];
      else
        out << kObjContactPairComment << ' ' << lower << ' ' << face_of[i] << '\n';
    }
  });
  commit_together({&mtl_file, &obj_file});
}

}  // namespace radwalk
