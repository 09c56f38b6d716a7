// radwalk.load and the Scene type: the PatchSet of a validated, patched scene, with numpy views of its arrays.
#include <filesystem>

#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "core/error.h"
#include "interruptible.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"
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
  interruptible([&] {
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
  });
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
  if (!py::isinstance<py::int_>(material) || py::isinstance<py::bool_>(material))
    throw InputError("a material is named by its name (str) or its index (int) into Scene.materials");
  int overflow = 0;
  const long long k = PyLong_AsLongLongAndOverflow(material.ptr(), &overflow);
  if (overflow != 0)
    throw InputError("material index " + py::str(material).cast<std::string>() + " is outside [0, " +
                     std::to_string(materials.size()) + ")");
  if (k < 0 || static_cast<std::size_t>(k) >= materials.size())
    throw InputError("material index " + std::to_string(k) + " is outside [0, " + std::to_string(materials.size()) +
                     ")");
  return static_cast<std::size_t>(k);
}

// An RGB argument of set_material: a number (the same in every channel) or 3 numbers; None: not given.
std::optional<Rgb> rgb_argument(const py::object& value, const char* name) {
  if (value.is_none()) return std::nullopt;
  const py::module_ np = py::module_::import("numpy");
  py::object a;
  try {
    a = np.attr("asarray")(value, py::arg("dtype") = np.attr("float64"));
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError)) throw;
    throw InputError(std::string(name) + " must be a number or 3 numbers (r, g, b)");
  }
  const auto v = a.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  if (v.ndim() == 0) return Rgb::Constant(v.data()[0]);
  if (v.ndim() == 1 && v.shape(0) == 3) return Rgb(v.data()[0], v.data()[1], v.data()[2]);
  throw InputError(std::string(name) + " must be a number or 3 numbers (r, g, b), got " + std::to_string(v.size()) +
                   " numbers");
}

// Sets Kd and/or Ke of a material after checking them as validate_mesh checks an MTL's (rho in [0, 1), Ke finite,
// >= 0 and at most kMaxKe), then derives every patch's rho and E again.
void set_material(Scene& s, const py::object& material, const py::object& rho_value, const py::object& Ke_value) {
  Material& mat = s.patches.materials[material_index(s, material)];
  const std::optional<Rgb> rho = rgb_argument(rho_value, "rho"), Ke = rgb_argument(Ke_value, "Ke");
  const std::string at = "material '" + printable(mat.name) + "': ";
  if (rho)
    for (int c = 0; c < 3; ++c)
      if (!((*rho)[c] >= 0 && (*rho)[c] < 1))
        throw InputError(at + "rho = " + number_text((*rho)[c]) + " in channel " + std::to_string(c) +
                         " is outside [0, 1) (Kd)");
  if (Ke)
    for (int c = 0; c < 3; ++c)
      if (!((*Ke)[c] >= 0 && (*Ke)[c] <= kMaxKe))
        throw InputError(at + "Ke = " + number_text((*Ke)[c]) + " in channel " + std::to_string(c) +
                         " must be finite, >= 0 and at most " + number_text(kMaxKe));
  if (rho) mat.Kd = *rho;
  if (Ke) mat.Ke = *Ke;
  set_radiometry_from_materials(s.patches);
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
  may hold are not refused when written but by every computation before it starts (InputError naming the patch,
  channel and value): rho in [0, 1), E = pi Ke finite, >= 0 and at most pi x 1e300.
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
          "set_material", &set_material,
          py::arg("material"), py::arg("rho") = py::none(), py::arg("Ke") = py::none(),
          R"doc(Sets a material's Kd (rho) and/or Ke (emitted radiance), by name or index, as an edited MTL would.

rho and Ke: a number (all three channels) or (r, g, b); refused (InputError) outside what an MTL may hold:
rho in [0, 1), Ke finite, >= 0 and at most 1e300.
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
