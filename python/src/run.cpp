#include "run.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "arrays.hpp"
#include "cli/report_command.hpp"

namespace py = pybind11;

namespace lagrange::python {

namespace {

// The named column as a view into the trajectory (KeyError for an unknown name).
py::array column(py::object self, const std::string& name) {
  const Trajectory& traj = self.cast<const Run&>().trajectory;
  size_t c = 0;
  try {
    c = traj.column_index(name);
  } catch (const std::out_of_range&) {
    throw py::key_error("no column '" + name + "' in the run (see run.columns)");
  }
  const size_t n = traj.columns.size();
  return column_view(traj.data.data() + c, traj.rows(), n, self);
}

py::dict stats(const Trajectory& traj) {
  return py::dict(py::arg("steps") = traj.stats.steps, py::arg("rhs_evals") = traj.stats.rhs_evals,
                  py::arg("failed_steps") = traj.stats.failed_steps,
                  py::arg("method") = traj.stats.method,
                  py::arg("rotation_drift") = traj.rotation_drift);
}

// The HTML report of the run (README.md, "Watching a model move"), as `simulate --report` writes
// it; ValueError for a name that does not end in .html or a run without samples.
void report(const Run& r, const std::string& path) {
  if (r.trajectory.rows() == 0) throw py::value_error("the run has no samples to report");
  cli::check_report(path, *r.prepared->model);
  const ReportNotes notes =
      cli::write_run_report(*r.prepared, r.trajectory, r.integrator, r.wall_seconds, path);
  for (const std::string& n : notes.notes)
    if (PyErr_WarnEx(PyExc_UserWarning, n.c_str(), 1) != 0) throw py::error_already_set();
}

// The report inline in a notebook: the self-contained page in an iframe's srcdoc.
std::string report_iframe(const Run& r) {
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                     ("lagrange-report-" + std::to_string(stamp) + ".html");
  report(r, file.string());
  std::ifstream in(file, std::ios::binary);
  std::ostringstream html;
  html << in.rdbuf();
  in.close();
  std::filesystem::remove(file);
  std::string escaped;
  for (const char c : html.str())
    escaped += c == '&'   ? std::string("&amp;")
               : c == '"' ? std::string("&quot;")
                          : std::string(1, c);
  return "<iframe style=\"width: 100%; height: 640px; border: 0\" srcdoc=\"" + escaped +
         "\"></iframe>";
}

}  // namespace

void bind_run(py::module_& m) {
  py::class_<Run>(m, "Run",
                  "A simulated trajectory on the output grid. Columns are read-only numpy views "
                  "of the engine's buffer (no copies); the Run keeps the buffer alive.")
      .def_property_readonly(
          "columns", [](const Run& r) { return r.trajectory.columns; },
          "Column names: t, coordinates, velocities (NAME_dot), kinetic, potential, energy, "
          "outputs, multipliers, residuals.")
      .def_property_readonly(
          "t", [](py::object self) { return column(self, "t"); }, "Sample times (a view).")
      .def("__getitem__", &column, py::arg("column"), "The named column as a view.")
      .def("__contains__",
           [](const Run& r, const std::string& name) {
             const auto& c = r.trajectory.columns;
             return std::find(c.begin(), c.end(), name) != c.end();
           })
      .def("__len__", [](const Run& r) { return r.trajectory.rows(); })
      .def_property_readonly(
          "array",
          [](py::object self) {
            const Trajectory& traj = self.cast<const Run&>().trajectory;
            return matrix_view(traj.data.data(), traj.rows(), traj.columns.size(), self);
          },
          "All samples as a rows × columns view (row-major, as in the CSV).")
      .def_property_readonly(
          "status", [](const Run& r) { return std::string(r.trajectory.status_name()); },
          "'complete', 'failed' or 'interrupted'.")
      .def_property_readonly(
          "message", [](const Run& r) { return r.trajectory.message; },
          "Why the run failed ('' when complete).")
      .def_property_readonly(
          "failure_time", [](const Run& r) { return r.trajectory.failure_time; },
          "Where a failed run stopped.")
      .def_property_readonly(
          "notes", [](const Run& r) { return r.trajectory.notes; },
          "What the engine noted, e.g. how it projected the initial state.")
      .def_property_readonly(
          "warnings", [](const Run& r) { return r.trajectory.warnings; },
          "Results that may not mean what they seem, e.g. a kite below the ground of its wind.")
      .def_property_readonly(
          "stats", [](const Run& r) { return stats(r.trajectory); },
          "Integrator statistics: steps, rhs_evals, failed_steps, method, rotation_drift.")
      .def(
          "to_pandas",
          [](py::object self) {
            const Run& r = self.cast<const Run&>();
            py::module_ pandas = py::module_::import("pandas");
            return pandas.attr("DataFrame")(self.attr("array"),
                                            py::arg("columns") = r.trajectory.columns);
          },
          "A pandas.DataFrame over the samples (pandas is imported only here).")
      .def("report", &report, py::arg("path"),
           "Write the HTML report (3-D animation, plots, equations, statistics) to path "
           "(.html), as `lagrange simulate --report`.")
      .def("_repr_html_", &report_iframe)
      .def("__repr__", [](const Run& r) {
        const Trajectory& traj = r.trajectory;
        const size_t rows = traj.rows();
        const double t1 = rows ? traj.data[(rows - 1) * traj.columns.size()] : 0.0;
        return "<lagrange.Run " + std::string(traj.status_name()) + ": " + std::to_string(rows) +
               " samples to t = " + py::repr(py::float_(t1)).cast<std::string>() + ", " +
               std::to_string(traj.columns.size()) + " columns>";
      });
}

}  // namespace lagrange::python
