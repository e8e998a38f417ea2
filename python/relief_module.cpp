// The Python module `relief` (pybind11): the road surface a relief build shipped, asked where a
// vehicle stands (z, pitch, roll on its four wheel contacts), and the co-simulation loop.
//   import relief
//   surface = relief.Surface("out/NAME.glb")
//   pose = surface.place(x, y, heading, length=4.5, width=1.8, z_hint=z)
//   figures = relief.run_cosim("out/NAME.sumocfg", "out/cosim", end=60.0, ego_count=2)
//   figures = relief.run_cosim("out/NAME.sumocfg", "out/cosim", sumo="sumo-gui")  # to watch it
// Coordinates are the build's local frame (SUMO's net coordinates), angles in radians.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>

#include "relief/core/errors.h"
#include "relief/cosim/cosim.h"
#include "relief/cosim/vehicle_pose.h"
#include "relief/export/mesh_writer.h"
#include "relief/scene/surface_query.h"

namespace py = pybind11;

namespace {

using namespace relief;

// A scene and its query, kept together (the query refers to the scene).
class Surface {
 public:
  explicit Surface(const std::filesystem::path& mesh_file)
      : scene_(std::make_unique<MeshScene>(read_mesh_file(mesh_file))), query_(*scene_) {}

  [[nodiscard]] std::optional<double> height(double x, double y) const {
    const auto hit = query_.highest(x, y);
    return hit ? std::optional<double>(hit->z_m) : std::nullopt;
  }
  [[nodiscard]] std::optional<double> nearest(double x, double y, double z) const {
    const auto hit = query_.nearest(x, y, z);
    return hit ? std::optional<double>(hit->z_m) : std::nullopt;
  }
  [[nodiscard]] std::optional<SurfacePose> place(double x, double y, double heading, double length,
                                                 double width, double z_hint, double pitch_hint,
                                                 double max_gap) const {
    return place_on_surface(query_, Vec2(x, y), heading, wheel_base_of(length, width), z_hint, pitch_hint,
                            max_gap);
  }
  [[nodiscard]] std::size_t triangles() const { return query_.triangles_indexed(); }

 private:
  std::unique_ptr<MeshScene> scene_;
  SurfaceQuery query_;
};

}  // namespace

PYBIND11_MODULE(relief, m) {
  m.doc() = "relief: elevation-aware 3D road networks; the road surface and the co-simulation";
  // relief's exceptions as Python's: bad input as ValueError, unreadable files as OSError.
  py::register_exception_translator(
      [](std::exception_ptr p)  // NOLINT(performance-unnecessary-value-param): pybind11 fixes the signature
      {
        try {
          if (p) std::rethrow_exception(p);
        } catch (const InvalidInput& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const IoError& e) {
          PyErr_SetString(PyExc_OSError, e.what());
        }
      });

  py::class_<SurfacePose>(m, "Pose", "A vehicle set on the surface on its four wheel contacts")
      .def_readonly("z", &SurfacePose::z_m, "height of the body plane under the centre (m)")
      .def_readonly("pitch", &SurfacePose::pitch_rad, "nose up positive (rad)")
      .def_readonly("roll", &SurfacePose::roll_rad, "right side down positive (rad)")
      .def_readonly("wheel_z", &SurfacePose::wheel_z_m,
                    "surface under front left, front right, rear left, rear right")
      .def_readonly("wheel_under", &SurfacePose::wheel_under_m,
                    "how far each contact's surface lies above the body")
      .def_readonly("contacts_missing", &SurfacePose::contacts_missing)
      .def("__repr__", [](const SurfacePose& p) {
        std::ostringstream s;
        s << "Pose(z=" << p.z_m << ", pitch=" << p.pitch_rad << ", roll=" << p.roll_rad << ")";
        return s.str();
      });

  py::class_<Surface>(m, "Surface", "The surfaces of a scene file (.glb, .obj, .fbx a relief build wrote)")
      .def(py::init<const std::filesystem::path&>(), py::arg("mesh_file"))
      .def("height", &Surface::height, py::arg("x"), py::arg("y"),
           "the top surface's height at (x, y), or None")
      .def("nearest", &Surface::nearest, py::arg("x"), py::arg("y"), py::arg("z"),
           "the height of the surface nearest z at (x, y), or None")
      .def("place", &Surface::place, py::arg("x"), py::arg("y"), py::arg("heading"), py::arg("length") = 4.5,
           py::arg("width") = 1.8, py::arg("z_hint") = 0.0, py::arg("pitch_hint") = 0.0,
           py::arg("max_gap") = 1.0,
           "the pose of a vehicle centred at (x, y) with this heading (rad, counter-clockwise from east), or "
           "None "
           "when two wheels have no surface within max_gap of the hinted height")
      .def_property_readonly("triangles", &Surface::triangles);

  m.def(
      "wheel_base",
      [](double length, double width) {
        const WheelBase w = wheel_base_of(length, width);
        return py::make_tuple(w.wheelbase_m, w.track_m);
      },
      py::arg("length"), py::arg("width"), "(wheelbase, track) of a vehicle of this size");

  m.def(
      "run_cosim",
      [](const std::filesystem::path& sumocfg, const std::filesystem::path& out, std::optional<double> end,
         double step, double replay_period, const std::vector<std::string>& egos, std::size_t ego_count,
         double resync, const std::string& sumo, int sumo_port, const std::string& sumo_host) {
        CosimOptions options;
        if (sumo_port != 0) {
          options.sumo.mode = SumoEndpoint::Mode::attach;
          options.sumo.port = sumo_port;
          options.sumo.host = sumo_host;
        } else if (!sumo.empty()) {
          options.sumo.mode = SumoEndpoint::Mode::launch;
          options.sumo.program = sumo;
        }
        options.end_s = end;
        options.step_s = step;
        options.replay_period_s = replay_period;
        options.egos = egos;
        options.ego_count = ego_count;
        options.resync_m = resync;
        Diagnostics diagnostics;
        {
          py::gil_scoped_release release;
          (void)run_cosim(find_cosim_inputs(sumocfg), options, out, diagnostics);
        }
        // The figures as cosim.json has them: one list of keys, the library's.
        std::ifstream in(out / kCosimReportFile);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        return py::module_::import("json").attr("loads")(text);
      },
      py::arg("sumocfg"), py::arg("out"), py::arg("end") = py::none(), py::arg("step") = 0.05,
      py::arg("replay_period") = 0.5, py::arg("egos") = std::vector<std::string>{}, py::arg("ego_count") = 0,
      py::arg("resync") = 0.5, py::arg("sumo") = std::string(), py::arg("sumo_port") = 0,
      py::arg("sumo_host") = std::string("localhost"),
      "runs SUMO on a relief build's configuration with every vehicle set on the surface (relief cosim), "
      "the vehicles named in `egos` and the first `ego_count` to depart driven by the physics; SUMO in "
      "this process, or `sumo` ('sumo', 'sumo-gui') launched over TraCI, or the SUMO already running "
      "with --remote-port `sumo_port` on `sumo_host`; "
      "writes cosim.json, the trajectories and cosim.glb in `out` and returns cosim.json's figures as a "
      "dict");
}
