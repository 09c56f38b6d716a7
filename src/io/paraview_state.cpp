#include "io/paraview_state.h"

#include <cstdio>
#include <filesystem>
#include <ostream>

#include "core/atomic_write.h"

namespace radwalk {
namespace {

std::string python_string(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    if (c == '\\' || c == '\'') out += '\\';
    out += c;
  }
  return out + "'";
}

std::string python_list(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z());
  return buf;
}

}  // namespace

void write_paraview_state(const std::string& path, const std::string& vtp, const ViewPoint& view,
                          const std::string& run_id) {
  const std::filesystem::path data(vtp);
  const std::string absolute = std::filesystem::absolute(data).lexically_normal().string();
  char angle[32];
  std::snprintf(angle, sizeof angle, "%.17g", view.view_angle_deg);
  write_atomically(path, [&](std::ostream& out) {
    out << "# ParaView state written by radwalk: File > Load State, `paraview --state=THIS.py` or `pvpython "
           "THIS.py`.\n"
           "# Shows " << data.filename().string() << " coloured by B_srgb (sRGB of the radiance B/pi, exposure 1) "
           "with Map Scalars off, unlit, from the scene's camera.\n";
    if (!run_id.empty()) out << "# run_id " << run_id << "\n";
    out <<
           "import os\n"
           "from paraview import simple\n\n"
           "name = " << python_string(data.filename().string()) << "\n"
           "here = os.path.dirname(os.path.abspath(__file__)) if '__file__' in globals() else os.getcwd()\n"
           "path = os.path.join(here, name)\n"
           "if not os.path.exists(path):\n"
           "    path = " << python_string(absolute) << "\n"
           "reader = simple.XMLPolyDataReader(registrationName=name, FileName=[path])\n"
           "view = simple.GetActiveViewOrCreate('RenderView')\n"
           "display = simple.Show(reader, view)\n"
           "if 'B_srgb' in reader.CellData.keys():\n"
           "    simple.ColorBy(display, ('CELLS', 'B_srgb'))\n"
           "    display.MapScalars = 0\n"
           "    display.Ambient = 1.0\n"
           "    display.Diffuse = 0.0\n"
           "    display.SetScalarBarVisibility(view, False)\n"
           "view.OrientationAxesVisibility = 0\n"
           "view.UseColorPaletteForBackground = 0\n"
           "view.Background = [0.0, 0.0, 0.0]\n"
           "simple.Render(view)  # the first render resets the camera: set it afterwards\n"
           "view.CameraPosition = " << python_list(view.position) << "\n"
           "view.CameraFocalPoint = " << python_list(view.focal_point) << "\n"
           "view.CameraViewUp = " << python_list(view.up) << "\n"
           "view.CameraViewAngle = " << angle << "\n"
           "view.CameraParallelProjection = 0\n"
           "simple.Render(view)\n";
  });
}

}  // namespace radwalk
