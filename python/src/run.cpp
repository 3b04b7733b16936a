#include "run.hpp"

#include <pybind11/stl.h>

#include <algorithm>

#include "arrays.hpp"

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
