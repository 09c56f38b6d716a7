// Scene.from_meshio and Result.to_meshio: scenes from and results to meshio.Mesh objects (Debian's python3-meshio,
// 7.0), so that any format meshio reads (VTU, Gmsh, Exodus, ...) can be solved and any it writes receives B. meshio
// is imported when one of the two is called, so the module works without it.
#include <string>
#include <vector>

#include "bindings.h"
#include "core/error.h"

namespace radwalk::python {
namespace {

// The meshio module; ImportError naming the Debian package when it is not installed.
py::module_ meshio_module() {
  try {
    return py::module_::import("meshio");
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_ImportError)) throw;
    PyErr_SetString(PyExc_ImportError,
                    "radwalk's meshio support needs the meshio module: apt install python3-meshio (Debian 12)");
    throw py::error_already_set();
  }
}

// The cell types that are surface polygons, as meshio names them.
bool surface_cell_type(const std::string& type) {
  return type == "triangle" || type == "quad" || type == "polygon";
}

// A per-cell value of the mesh: `value` itself when it is not a str (a number or an array, one row per cell in the
// order of mesh.cells), or, for a str, the cell_data of that name, its blocks concatenated in that order.
py::object per_cell(const py::object& mesh, const py::object& value, const char* argument) {
  if (!py::isinstance<py::str>(value)) return value;
  const std::string key = value.cast<std::string>();
  const py::dict cell_data = mesh.attr("cell_data");
  if (!cell_data.contains(key)) {
    std::string keys;
    for (const auto& item : cell_data) keys += (keys.empty() ? "" : ", ") + py::str(item.first).cast<std::string>();
    throw InputError(std::string(argument) + "='" + key + "': the mesh has no cell_data '" + key +
                     "' (it has: " + (keys.empty() ? "none" : keys) + ")");
  }
  const py::module_ np = py::module_::import("numpy");
  return np.attr("concatenate")(cell_data[key.c_str()]);
}

// Scene.from_meshio: the mesh's surface cells as the faces of scene_from_arrays, in the order of mesh.cells.
Scene from_meshio(const py::object& mesh, const py::object& rho, const py::object& emission, const py::object& groups,
                  bool two_sided, double max_edge, double max_area, bool strict, bool contact_cut) {
  meshio_module();
  if (!py::hasattr(mesh, "points") || !py::hasattr(mesh, "cells") || !py::hasattr(mesh, "cell_data"))
    throw InputError("from_meshio takes a meshio.Mesh (points, cells, cell_data)");
  const py::module_ np = py::module_::import("numpy");
  py::list faces;
  std::size_t block = 0;
  for (const py::handle cells : py::iter(mesh.attr("cells"))) {
    const std::string type = py::str(cells.attr("type")).cast<std::string>();
    if (!surface_cell_type(type))
      throw InputError("mesh.cells[" + std::to_string(block) + "]: cells of type '" + type +
                       "' are not surface polygons; radwalk takes triangle, quad and polygon cells (drop the "
                       "others, and their cell_data, before from_meshio)");
    for (const py::handle row : py::iter(np.attr("asarray")(cells.attr("data")))) faces.append(row);
    ++block;
  }
  py::object names = py::none();
  if (!groups.is_none()) {
    names = py::list();
    for (const py::handle g : py::iter(per_cell(mesh, groups, "groups"))) {
      py::object v = py::reinterpret_borrow<py::object>(g);
      if (py::hasattr(v, "item")) v = v.attr("item")();  // a numpy scalar: 1, not "np.int64(1)"
      names.cast<py::list>().append(py::str(v));
    }
  }
  return scene_from_arrays(mesh.attr("points"), faces, per_cell(mesh, rho, "rho"),
                           emission.is_none() ? emission : per_cell(mesh, emission, "emission"), names, two_sided,
                           max_edge, max_area, strict, contact_cut, "<meshio>");
}

// Result.to_meshio: the patches of `scene` as cells (consecutive triangles one "triangle" block, consecutive quads
// one "quad" block, so that the blocks in order are the patches in order) and the result's fields as cell_data.
py::object to_meshio(const py::object& self, const Scene& scene) {
  const py::module_ meshio = meshio_module();
  const py::module_ np = py::module_::import("numpy");
  const Result& r = self.cast<const Result&>();
  const PatchSet& p = scene.patches;
  const std::size_t n = p.size();
  if (static_cast<std::size_t>(r.solution.B.rows()) != n)
    throw InputError("to_meshio: the result has " + std::to_string(r.solution.B.rows()) + " patches, the scene " +
                     std::to_string(n) + " (pass the scene the result was computed on)");
  if (n == 0) throw InputError("to_meshio: the scene has no patches");
  // Per patch: B (the channel mean, as the .vtp's active scalar), B_rgb, the Monte Carlo fields where computed,
  // and the patch description.
  std::vector<std::pair<std::string, py::object>> fields;
  const py::object B_rgb = np.attr("array")(rgb_view(r.solution.B, self));
  fields.emplace_back("B", B_rgb.attr("mean")(py::arg("axis") = 1));
  fields.emplace_back("B_rgb", B_rgb);
  if (r.solution.B_se.size()) fields.emplace_back("B_se", np.attr("array")(rgb_view(r.solution.B_se, self)));
  if (r.solution.var.size()) fields.emplace_back("B_var", np.attr("array")(rgb_view(r.solution.var, self)));
  if (r.solution.var_theory.size())
    fields.emplace_back("B_var_theory", np.attr("array")(rgb_view(r.solution.var_theory, self)));
  if (r.solution.vov.size()) fields.emplace_back("B_vov", np.attr("array")(rgb_view(r.solution.vov, self)));
  // Copies of the scene's rho and E (the views' base is the result, so they are copied at once).
  fields.emplace_back("rho", np.attr("array")(view(p.rho.data()->data(), n, 3, self, false, sizeof(Rgb))));
  fields.emplace_back("E", np.attr("array")(view(p.E.data()->data(), n, 3, self, false, sizeof(Rgb))));
  fields.emplace_back("area", copy_array(p.area));
  std::vector<std::int64_t> index(n), face(p.face.begin(), p.face.end());
  for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<std::int64_t>(i);
  fields.emplace_back("patch", copy_array(index));
  fields.emplace_back("face", copy_array(face));

  py::list cells;
  py::dict cell_data;
  for (const auto& f : fields) cell_data[f.first.c_str()] = py::list();
  for (std::size_t begin = 0; begin < n;) {
    const bool triangle = p.corners[begin][3] < 0;
    std::size_t end = begin;
    while (end < n && (p.corners[end][3] < 0) == triangle) ++end;
    const std::size_t k = triangle ? 3 : 4;
    std::vector<std::int64_t> corners;
    corners.reserve((end - begin) * k);
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t c = 0; c < k; ++c) corners.push_back(p.corners[i][c]);
    const py::object block =
        copy_array(corners).attr("reshape")(static_cast<py::ssize_t>(end - begin), static_cast<py::ssize_t>(k));
    cells.append(py::make_tuple(triangle ? "triangle" : "quad", block));
    const py::slice rows(static_cast<py::ssize_t>(begin), static_cast<py::ssize_t>(end), 1);
    for (const auto& f : fields) cell_data[f.first.c_str()].cast<py::list>().append(f.second[rows]);
    begin = end;
  }
  const py::object points = np.attr("array")(view(p.points.data()->data(), p.points.size(), 3, self));
  return meshio.attr("Mesh")(points, cells, py::arg("cell_data") = cell_data);
}

}  // namespace

void bind_meshio(py::module_& m) {
  const py::object scene = m.attr("Scene");
  scene.attr("from_meshio") = py::staticmethod(py::cpp_function(
      &from_meshio, py::name("from_meshio"), py::scope(scene), py::arg("mesh"), py::arg("rho"),
      py::arg("emission") = py::none(), py::arg("groups") = py::none(), py::arg("two_sided") = false,
      py::arg("max_edge") = 0.0, py::arg("max_area") = 0.0, py::arg("strict") = false, py::arg("contact_cut") = true,
      R"doc(A Scene from a meshio.Mesh (Debian's python3-meshio), through Scene.from_arrays.

mesh: a meshio.Mesh whose points are (V, 3) float coordinates in the mesh's length unit and whose cells are
  blocks of type "triangle" (n, 3), "quad" (n, 4) or "polygon" (n, k) of 0-based point indices (counter-clockwise
  seen from the front); any other cell type (line, vertex, tetra, ...) raises radwalk.InputError. The faces are
  the cells of all blocks in the order of mesh.cells: face f of an error message counts from 0 over them.
rho: reflectance per face in [0, 1): the name (str) of a cell_data array, each block (n,) or (n, 3); or, as in
  from_arrays, an (F, 3) or (F,) float array over the concatenated blocks, or one number.
emission: emitted radiosity E per face in W/m^2 (exitance: Ke = E / pi), a cell_data name or an (F, 3), (F,)
  array or one number; None: 0.
groups: None, or the name of a cell_data array (e.g. "gmsh:physical") whose per-cell values become the group
  names (str(value)), or a list of F names.
two_sided, max_edge, max_area, strict, contact_cut: as radwalk.load.
The validation and its messages are those of Scene.from_arrays (the scene is named "<meshio>"). meshio is
imported when called: ImportError naming `apt install python3-meshio` without it.)doc"));
  const py::object result = m.attr("Result");
  result.attr("to_meshio") = py::cpp_function(
      &to_meshio, py::name("to_meshio"), py::is_method(result), py::arg("scene"),
      R"doc(The result on the patches of `scene` as a meshio.Mesh (Debian's python3-meshio), e.g. for meshio.write.

scene: the Scene the result was computed on (same patch count, else radwalk.InputError).
Returns a meshio.Mesh with points (P, 3) float64 (Scene.points) and cells: the patches in order, as blocks of
consecutive "triangle" (n, 3) and "quad" (n, 4) int64 corner indices, so cell i over the concatenated blocks is
patch i. cell_data (per block, float64 unless said): B (n,) the channel mean (R + G + B) / 3 of the radiosity
in W per unit length squared (the .vtp's active scalar), B_rgb (n, 3) the radiosity itself (Result.B), B_se,
B_var, B_var_theory (n, 3) where the result has them, rho (n, 3), E (n, 3) in W per unit length squared, area (n,)
in unit length squared, patch and face (n,) int64 indices. Scene.from_meshio(mesh, rho="rho", emission="E") gives
the scene back (same patches and areas).)doc");
}

}  // namespace radwalk::python
