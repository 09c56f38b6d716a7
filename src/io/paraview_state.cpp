#include "io/paraview_state.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <ostream>

#include "core/atomic_write.h"
#include "core/format_number.h"

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

std::string python_number(double x) {
  return format_number(x, 17);
}

std::string python_list(const Vec3& v) {
  return '[' + python_number(v.x()) + ", " + python_number(v.y()) + ", " + python_number(v.z()) + ']';
}

}  // namespace

StateColouring radiosity_colouring(const PatchSet& patches, const std::vector<double>& B_rgb) {
  StateColouring colouring{"B", "B [W/unit^2]", 0.0, 1.0};
  const std::size_t n = std::min(patches.size(), B_rgb.size() / 3);
  // The range of the channel mean over the non-emitting patches (all patches if every one emits).
  for (const bool skip_emitters : {true, false}) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < n; ++i) {
      if (skip_emitters && (patches.E[i] > 0).any()) continue;
      const double mean = (B_rgb[3 * i] + B_rgb[3 * i + 1] + B_rgb[3 * i + 2]) / 3.0;
      if (!std::isfinite(mean)) continue;
      lo = std::min(lo, mean);
      hi = std::max(hi, mean);
    }
    if (lo <= hi) {
      colouring.lo = lo;
      colouring.hi = hi > lo ? hi : lo + std::max(1e-6 * std::abs(lo), 1e-12);
      return colouring;
    }
  }
  return colouring;  // no finite value: 0..1
}

StateColouring heat_flux_colouring(const std::vector<double>& q) {
  StateColouring colouring{"q", "q [W/m^2] (net leaving)", -1.0, 1.0, "Cool to Warm",
                           "symmetric about 0: blue gains heat, red loses it"};
  double largest = 0;
  for (double v : q)
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  if (largest > 0) colouring.lo = -largest, colouring.hi = largest;
  return colouring;
}

void write_paraview_state(const std::string& path, const std::string& vtp, const ViewPoint& view,
                          const StateColouring& colouring, const std::string& run_id) {
  const std::filesystem::path data(vtp);
  const std::string absolute = std::filesystem::absolute(data).lexically_normal().string();
  const std::string angle = python_number(view.view_angle_deg);
  write_atomically(path, [&](std::ostream& out) {
    out << "# ParaView state written by radwalk: File > Load State, `paraview --state=THIS.py` or `pvpython "
           "THIS.py`.\n"
           "# Shows " << data.filename().string() << (colouring.field.empty() ? std::string() :
           " coloured by " + colouring.field + " (" + colouring.preset + ", " + colouring.range_rule +
           ", colour bar, smooth)") <<
           ", unlit, from the camera of the one camera rule (scripts/camera_rule.py).\n";
    if (!run_id.empty()) out << "# run_id " << run_id << "\n";
    out <<
           "import os\n"
           "from paraview import simple\n\n"
           "name = " << python_string(data.filename().string()) << "\n"
           "here = os.path.dirname(os.path.abspath(__file__)) if '__file__' in globals() else os.getcwd()\n"
           "path = os.path.join(here, name)\n"
           "if not os.path.exists(path):\n"
           "    path = " << python_string(absolute) << "\n"
           "field = " << python_string(colouring.field) << "\n"
           "title = " << python_string(colouring.title) << "\n"
           "value_range = [" << python_number(colouring.lo) << ", " << python_number(colouring.hi) << "]"
           "  # the colour map's range: " << colouring.range_rule << "\n"
           "reader = simple.XMLPolyDataReader(registrationName=name, FileName=[path])\n"
           "view = simple.GetActiveViewOrCreate('RenderView')\n"
           "display = simple.Show(reader, view)\n"
           "if field and field in reader.CellData.keys():\n"
           "    smooth = field in reader.PointData.keys()  # the point field: smooth shading\n"
           "    simple.ColorBy(display, ('POINTS' if smooth else 'CELLS', field))\n"
           "    if smooth:\n"
           "        display.Interpolation = 'Gouraud'\n"
           "    display.Ambient = 1.0\n"
           "    display.Diffuse = 0.0\n"
           "    lut = simple.GetColorTransferFunction(field)\n"
           "    lut.ApplyPreset(" << python_string(colouring.preset) << ", True)\n"
           "    lut.AutomaticRescaleRangeMode = 'Never'\n"
           "    lut.RescaleTransferFunction(value_range[0], value_range[1])\n"
           "    simple.GetOpacityTransferFunction(field).RescaleTransferFunction(value_range[0], value_range[1])\n"
           "    display.SetScalarBarVisibility(view, True)\n"
           "    bar = simple.GetScalarBar(lut, view)\n"
           "    bar.Title = title\n"
           "    bar.ComponentTitle = ''\n"
           "    bar.RangeLabelFormat = '%-#.3g'\n"
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
