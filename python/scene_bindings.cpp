// radwalk.load and the Scene type: the PatchSet of a validated, patched scene, with numpy views of its arrays.
#include <filesystem>

#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "core/error.h"
#include "mesh/read_scene.h"
#include "patch/patch_scene.h"
#include "solve/response_spec.h"

namespace radwalk::python {
namespace {

// A numpy view of n rows of `columns` values of type T starting at data, owned by base; read-only unless writable.
template <class T>
py::array_t<T> view(const T* data, std::size_t n, std::size_t columns, std::size_t row_stride, py::handle base,
                    bool writable) {
  std::vector<py::ssize_t> shape = {static_cast<py::ssize_t>(n)}, strides = {static_cast<py::ssize_t>(row_stride)};
  if (columns > 1) {
    shape.push_back(static_cast<py::ssize_t>(columns));
    strides.push_back(sizeof(T));
  }
  py::array_t<T> a(shape, strides, data, base);
  if (!writable) py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// target[...] = values (numpy broadcasting), for `scene.rho = values`.
void assign(py::object target, py::object values) { py::module_::import("numpy").attr("copyto")(target, values); }

// Reads, validates and patches the scene as every CLI command does (load_scene, then patch_scene: the CLI's
// load_patches without its notes).
Scene load(const std::filesystem::path& file, double max_edge, double max_area, bool strict, bool two_sided,
           bool contact_cut) {
  const std::string path = file.string();
  Scene scene;
  {
    py::gil_scoped_release release;
    ReadOptions read;
    read.strict = strict;
    ScenePatchingOptions patching;
    patching.split.max_edge = max_edge;
    patching.split.max_area = max_area;
    patching.contact_cut = contact_cut;
    patching.two_sided = two_sided;
    PatchedScene patched = patch_scene(load_scene(path, read), patching);
    scene.patches = std::move(patched.patches);
    scene.group = patch_groups(patched.mesh, scene.patches);  // through the input face of every (repaired) face
    scene.groups = patched.mesh.groups;
    scene.warnings = patched.mesh.warnings;
  }
  scene.path = path;
  scene.max_edge = max_edge;
  scene.max_area = max_area;
  scene.strict = strict;
  scene.two_sided = two_sided;
  scene.contact_cut = contact_cut;
  for (const std::string& w : scene.warnings) PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1);
  return scene;
}

std::size_t material_index(const Scene& scene, const py::object& material) {
  const auto& materials = scene.patches.materials;
  if (py::isinstance<py::str>(material)) {
    const std::string name = material.cast<std::string>();
    for (std::size_t k = 0; k < materials.size(); ++k)
      if (materials[k].name == name) return k;
    throw InputError("unknown material '" + name + "' (the scene's materials are listed in Scene.materials)");
  }
  const long k = material.cast<long>();
  if (k < 0 || static_cast<std::size_t>(k) >= materials.size())
    throw InputError("material index " + std::to_string(k) + " is outside [0, " + std::to_string(materials.size()) +
                     ")");
  return static_cast<std::size_t>(k);
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Material>(m, "Material", "A material of the scene, as read from its MTL (or PLY colours).")
      .def_readonly("name", &Material::name)
      .def_property_readonly("Kd", [](const Material& x) { return std::vector<double>(x.Kd.begin(), x.Kd.end()); },
                             "Diffuse reflectance rho (r, g, b).")
      .def_property_readonly("Ke", [](const Material& x) { return std::vector<double>(x.Ke.begin(), x.Ke.end()); },
                             "Emitted radiance L_e (r, g, b); E = pi * Ke.")
      .def_readonly("file", &Material::file, "The MTL file that defines it (empty if none).")
      .def_readonly("line", &Material::line, "Its line in that file (0 if none).")
      .def("__repr__", [](const Material& x) { return "<radwalk.Material '" + x.name + "'>"; });

  py::class_<Scene>(m, "Scene", R"doc(A validated, patched scene (radwalk.load).

Per-patch numpy arrays are views of the C++ arrays (no copy; they keep the Scene alive):
  areas (N,), centroids (N, 3), normals (N, 3), face (N,) input face, material (N,) index into materials,
  group (N,) index into groups (-1 outside any), points (P, 3) and corners (N, 4) (-1 in [3] for a triangle):
  read-only;
  rho (N, 3) and E (N, 3): WRITABLE in place. Every later computation (form_factors excepted: F does not depend on
  them) uses the values as they are then, e.g. scene.rho[scene.material == 2] = 0.5. Values outside what an MTL
  may hold (rho outside [0, 1), E < 0) are not refused here; the solvers report what they do (negative or
  non-finite values raise InputError).
Per material: set_material(name, rho=..., Ke=...), which acts as the same scene with an edited MTL.)doc")
      .def_readonly("path", &Scene::path)
      .def_readonly("max_edge", &Scene::max_edge)
      .def_readonly("max_area", &Scene::max_area)
      .def_readonly("strict", &Scene::strict)
      .def_readonly("two_sided", &Scene::two_sided)
      .def_readonly("contact_cut", &Scene::contact_cut)
      .def_readonly("warnings", &Scene::warnings, "Validation's repairs and notices, one line each (as the CLI's).")
      .def_readonly("groups", &Scene::groups, "Group names, indexed by Scene.group.")
      .def_property_readonly("materials", [](const Scene& s) { return s.patches.materials; },
                             "The materials (copies), indexed by Scene.material.")
      .def("__len__", [](const Scene& s) { return s.patches.size(); }, "The number of patches N.")
      .def_property_readonly("total_area", [](const Scene& s) { return s.patches.total_area(); })
      .def_property_readonly(
          "areas", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.area.data(), s.patches.size(), 1, sizeof(double), self, false);
          }, "Patch areas (N,), in the mesh's unit squared.")
      .def_property_readonly(
          "centroids", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.centroid.data()->data(), s.patches.size(), 3, sizeof(Vec3), self, false);
          }, "Area centroids (N, 3).")
      .def_property_readonly(
          "normals", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.normal.data()->data(), s.patches.size(), 3, sizeof(Vec3), self, false);
          }, "Unit normals (N, 3), from the corner order (counter-clockwise seen from the front).")
      .def_property_readonly(
          "points", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.points.data()->data(), s.patches.points.size(), 3, sizeof(Vec3), self, false);
          }, "Corner points (P, 3), shared between patches.")
      .def_property_readonly(
          "corners", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.corners.data()->data(), s.patches.size(), 4, 4 * sizeof(std::int32_t), self,
                        false);
          }, "Corner indices into points (N, 4); corners[i, 3] == -1 for a triangle.")
      .def_property_readonly(
          "face", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.face.data(), s.patches.size(), 1, sizeof(std::int32_t), self, false);
          }, "Input face of every patch (N,), counted from 0 in file order.")
      .def_property_readonly(
          "material", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.patches.material.data(), s.patches.size(), 1, sizeof(std::int32_t), self, false);
          }, "Material index of every patch (N,), into Scene.materials.")
      .def_property_readonly(
          "group", [](py::object self) {
            const Scene& s = self.cast<const Scene&>();
            return view(s.group.data(), s.patches.size(), 1, sizeof(std::int32_t), self, false);
          }, "Group index of every patch (N,), into Scene.groups; -1 outside any group.")
      .def_property(
          "rho", [](py::object self) {
            Scene& s = self.cast<Scene&>();
            return view(s.patches.rho.data()->data(), s.patches.size(), 3, sizeof(Rgb), self, true);
          },
          [](py::object self, py::object values) { assign(self.attr("rho"), values); },
          "Diffuse reflectance (N, 3), writable in place: scene.rho[i] = (r, g, b), scene.rho[:] *= 0.9.")
      .def_property(
          "E", [](py::object self) {
            Scene& s = self.cast<Scene&>();
            return view(s.patches.E.data()->data(), s.patches.size(), 3, sizeof(Rgb), self, true);
          },
          [](py::object self, py::object values) { assign(self.attr("E"), values); },
          "Emitted radiosity E = pi * Ke (N, 3), W per unit length squared, writable in place.")
      .def(
          "set_material",
          [](Scene& s, const py::object& material, std::optional<std::array<double, 3>> rho,
             std::optional<std::array<double, 3>> Ke) {
            Material& mat = s.patches.materials[material_index(s, material)];
            if (rho) mat.Kd = Rgb((*rho)[0], (*rho)[1], (*rho)[2]);
            if (Ke) mat.Ke = Rgb((*Ke)[0], (*Ke)[1], (*Ke)[2]);
            set_radiometry_from_materials(s.patches);
          },
          py::arg("material"), py::arg("rho") = py::none(), py::arg("Ke") = py::none(),
          R"doc(Sets a material's Kd (rho) and/or Ke (emitted radiance), by name or index, as an edited MTL would.

Then every patch's rho and E are derived again from its material (rho = Kd, E = pi * Ke: the library's
set_radiometry_from_materials), so per-patch edits of rho or E made before are replaced.)doc")
      .def("__repr__", [](const Scene& s) {
        return "<radwalk.Scene '" + s.path + "': " + std::to_string(s.patches.size()) + " patches, " +
               std::to_string(s.patches.materials.size()) + " materials>";
      });

  m.def("load", &load, py::arg("path"), py::arg("max_edge") = 0.0, py::arg("max_area") = 0.0,
        py::arg("strict") = false, py::arg("two_sided") = false, py::arg("contact_cut") = false,
        R"doc(Reads, validates and patches a scene (OBJ with MTL, or PLY): a Scene.

max_edge: split faces until no patch edge is longer than this (mesh units); 0 keeps the input faces (patch i is
  input face i), as the CLI's --max-edge.
max_area: also split faces until no patch is larger than this (mesh units squared), as --max-area.
strict: refuse what validation would repair (the CLI's --strict).
two_sided: every material two-sided (a front and a back patch per face), as --two-sided; materials with
  `radwalk_two_sided 1` in their MTL block are two-sided either way.
contact_cut: cut the faces that objects stand on along their footprints before splitting (only when max_edge or
  max_area splits faces), as --contact-cut.
Repairs are reported as UserWarnings and kept in Scene.warnings; refusals raise radwalk.InputError (a
ValueError) with the CLI's one-line message ("FILE:LINE: face F: what is wrong").)doc");
}

}  // namespace radwalk::python
