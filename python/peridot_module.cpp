// The Python module `peridot` (pybind11): build a problem from a deck file, YAML text or a dict, with
// parameters set by key path; run it in pieces (steps, to a time, to the end); read fields as numpy views of the
// solver's own arrays and the history as numpy arrays; change a boundary condition between pieces. Deck errors
// arrive as peridot.InputError carrying every file:line:col. docs/python.md is the user's page.
//
// Serial only: the module never starts MPI (one rank, OpenMP threads inside it).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <yaml-cpp/yaml.h>

#include "peridot/core/error.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/solvers/runner.hpp"
#include "peridot/solvers/simulation.hpp"
#include "peridot/state/point_fields.hpp"
#include "peridot/version.hpp"

namespace py = pybind11;

namespace {

using peridot::DeckOverride;
using peridot::Problem;
using peridot::Run;
using peridot::Simulation;

// -- Python values → YAML -------------------------------------------------------------------------------------

/// A Python value as a YAML node: dict → map, list/tuple → sequence, bool, int, float (shortest round-trip
/// text), str, None. Anything else is a TypeError naming where it is.
YAML::Node to_yaml(const py::handle& value, const std::string& where) {
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
    return YAML::Node(py::repr(value).cast<std::string>());  // repr(float) reads back to the same double
  if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [key, item] : value.cast<py::dict>()) {
      const std::string name = py::str(key).cast<std::string>();
      map[name] = to_yaml(item, where.empty() ? name : where + "." + name);
    }
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node list(YAML::NodeType::Sequence);
    std::size_t k = 0;
    for (const py::handle item : value) list.push_back(to_yaml(item, fmt::format("{}.{}", where, k++)));
    return list;
  }
  // numpy scalars and the like: their float value if they have one.
  if (py::hasattr(value, "__float__")) return YAML::Node(py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>());
  throw py::type_error(fmt::format("deck value at '{}': a {} is not a YAML value", where,
                                   py::str(value.get_type().attr("__name__")).cast<std::string>()));
}

std::string yaml_text(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << node;
  return out.c_str();
}

/// parameters={"materials.steel.yield_stress": 3.5e8, …} as DeckOverrides.
std::vector<DeckOverride> overrides_of(const std::optional<py::dict>& parameters) {
  std::vector<DeckOverride> sets;
  if (!parameters) return sets;
  for (const auto& [key, value] : *parameters) {
    const std::string path = py::str(key).cast<std::string>();
    sets.push_back({path, yaml_text(to_yaml(value, path))});
  }
  return sets;
}

// -- the classes -----------------------------------------------------------------------------------------------

/// A running problem: Run plus what Python needs (the problem it was built from stays alive with it).
struct PyRun {
  Problem problem;
  std::unique_ptr<Run> run;

  Simulation& sim() { return run->simulation(); }
  std::int64_t step() { return sim().state().step; }

  /// Steps one at a time to `last_step`, without the GIL, looking for Ctrl-C between steps.
  void advance_to(std::int64_t last_step) {
    if (run->finished()) throw std::logic_error("this run has finished");
    if (last_step > sim().total_steps())
      throw py::value_error(fmt::format("step {} is after the run's end (step {}, t = {:g} s)", last_step,
                                        sim().total_steps(), end_time()));
    while (step() < last_step) {
      {
        py::gil_scoped_release unlocked;
        run->advance(step() + 1);
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }
  double end_time() { return sim().state().time + static_cast<double>(sim().total_steps() - step()) * sim().time_step(); }
};

/// A numpy view of n×3 (or n) doubles owned by `owner`, read-only: the solver's own array, no copy.
py::array view(const double* data, std::size_t n, bool vector, const py::object& owner) {
  py::array a = vector ? py::array(py::dtype::of<double>(), {n, std::size_t{3}}, {3 * sizeof(double), sizeof(double)}, data, owner)
                       : py::array(py::dtype::of<double>(), {n}, {sizeof(double)}, data, owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

py::array field(const py::object& self, const std::string& name) {
  PyRun& r = self.cast<PyRun&>();
  Simulation& sim = r.sim();
  const std::size_t n = sim.num_owned();
  if (name == "position" || name == "reference_position") return view(sim.discretization().x.data(), n, true, self);
  const peridot::PointField* entry = nullptr;
  for (const peridot::PointField& f : peridot::point_fields())
    if (f.name == name) entry = &f;
  const std::vector<std::string> optional = peridot::optional_exodus_fields(sim);
  const bool present = entry && (entry->scope == peridot::FieldScope::always ||
                                 std::find(optional.begin(), optional.end(), name) != optional.end());
  if (!present) {
    std::vector<std::string> names = {"position"};
    for (const peridot::PointField& f : peridot::point_fields())
      if (f.scope == peridot::FieldScope::always) names.emplace_back(f.name);
    names.insert(names.end(), optional.begin(), optional.end());
    throw py::key_error(fmt::format("'{}' is not a field of this problem; it has: {}", name, fmt::join(names, ", ")));
  }
  if (name == "volume") return view(sim.discretization().volume.data(), n, false, self);
  const peridot::FieldStorage where = entry->in(sim.state());
  if (where.vector) return view(where.vector->data(), n, true, self);
  if (where.scalar && where.scalar->size() >= n) return view(where.scalar->data(), n, false, self);
  // Not stored (a model without this array), or filled only when output is gathered (correspondence fields,
  // temperature): a copy.
  py::array_t<double> copy(static_cast<py::ssize_t>(n));
  double* out = copy.mutable_data();
  std::fill(out, out + n, 0.0);
  if (!where.scalar) {
    sim.prepare_outputs(true, false);
    const auto& outputs = sim.state().point_outputs;
    if (auto it = outputs.find(name); it != outputs.end() && it->second.size() >= n)
      std::copy(it->second.begin(), it->second.begin() + static_cast<std::ptrdiff_t>(n), out);
  }
  return copy;
}

py::dict history(PyRun& r) {
  const peridot::HistoryRows& rows = r.run->history();
  py::dict out;
  const std::size_t columns = rows.columns.size();
  const std::size_t count = columns ? rows.values.size() / columns : 0;
  for (std::size_t c = 0; c < columns; ++c) {
    py::array_t<double> column(static_cast<py::ssize_t>(count));
    double* data = column.mutable_data();
    for (std::size_t k = 0; k < count; ++k) data[k] = rows.values[k * columns + c];
    out[py::str(rows.columns[c])] = column;
  }
  return out;
}

Problem make_problem(const std::optional<std::string>& path, const std::optional<std::string>& yaml,
                     const std::optional<py::dict>& deck, const std::string& base_dir,
                     const std::optional<py::dict>& parameters) {
  const int given = path.has_value() + yaml.has_value() + deck.has_value();
  if (given != 1) throw py::value_error("give exactly one of: a deck file, yaml= text or deck= dict");
  const std::vector<DeckOverride> sets = overrides_of(parameters);
  if (path) return peridot::load_deck(*path, sets);
  if (yaml) return peridot::parse_deck(*yaml, "<yaml>", base_dir, sets);
  return peridot::parse_deck(yaml_text(to_yaml(*deck, "")), "<dict>", base_dir, sets);
}

}  // namespace

PYBIND11_MODULE(peridot, m) {
  m.doc() = "Peridot: peridynamic solid mechanics and fracture (docs/python.md)";
  m.attr("__version__") = PERIDOT_VERSION;

  // Exceptions: InputError carries every deck problem as (file, line, column, message) tuples.
  static py::exception<peridot::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<peridot::NumericalError> numerical_error(m, "NumericalError", PyExc_RuntimeError);
  static py::exception<peridot::OutputError> output_error(m, "OutputError", PyExc_OSError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const peridot::InputError& e) {
      std::string text;
      py::list diagnostics;
      for (const peridot::Diagnostic& d : e.diagnostics()) {
        text += (text.empty() ? "" : "\n") + d.str();
        diagnostics.append(py::make_tuple(d.pos.file, d.pos.line, d.pos.column, d.message));
      }
      py::object error = py::reinterpret_borrow<py::object>(input_error.ptr())(text);
      error.attr("diagnostics") = diagnostics;
      PyErr_SetObject(input_error.ptr(), error.ptr());
    } catch (const peridot::NumericalError& e) {
      numerical_error(e.what());
    } catch (const peridot::OutputError& e) {
      output_error(e.what());
    }
  });

  m.def("set_threads", [](int n) {
    if (n < 1) throw py::value_error("threads must be at least 1");
    omp_set_num_threads(n);
  }, py::arg("n"), "OpenMP threads for the runs that follow (results do not depend on it)");
  m.def("threads", [] { return omp_get_max_threads(); });

  py::class_<Problem>(m, "Problem", "A validated deck: every default filled in, every number in SI")
      .def(py::init([](std::optional<std::string> path, std::optional<std::string> yaml, std::optional<py::dict> deck,
                       std::string base_dir, std::optional<py::dict> parameters) {
             return make_problem(path, yaml, deck, base_dir, parameters);
           }),
           py::arg("path") = py::none(), py::kw_only(), py::arg("yaml") = py::none(), py::arg("deck") = py::none(),
           py::arg("base_dir") = ".", py::arg("parameters") = py::none(),
           "Problem('deck.yaml'), Problem(yaml=text), or Problem(deck=dict); parameters={'materials.steel."
           "yield_stress': 3.5e8, 'boundary_conditions.0.value': '1e-3*t'} sets deck values by key path first. "
           "Relative file names in yaml= and deck= are taken from base_dir. Raises InputError.")
      .def_property_readonly("deck_path", [](const Problem& p) { return p.deck_path; })
      .def_property_readonly("warnings", [](const Problem& p) {
        std::vector<std::string> out;
        for (const peridot::Diagnostic& w : p.warnings) out.push_back(w.str());
        return out;
      })
      .def_property_readonly("output_directory", [](const Problem& p) { return p.output.directory; })
      .def("resolved_yaml", [](const Problem& p) { return peridot::resolved_deck_yaml(p); },
           "the deck as the run understands it (what resolved_deck.yaml holds)")
      .def("start", [](const Problem& p, std::optional<std::string> output_dir, bool write_files, bool progress) {
             auto r = std::make_unique<PyRun>();
             r->problem = p;
             if (output_dir) r->problem.output.directory = std::filesystem::absolute(*output_dir).string();
             peridot::RunOptions options;
             options.progress = progress;
             options.write_files = write_files;
             options.catch_signals = false;
             r->run = std::make_unique<Run>(r->problem, options);
             return r;
           },
           py::kw_only(), py::arg("output_dir") = py::none(), py::arg("write_files") = true, py::arg("progress") = false,
           "Sets the problem up and returns its Run at step 0. write_files=False writes nothing (the history is still "
           "kept in memory); output_dir replaces the deck's output.directory.");

  py::class_<PyRun>(m, "Run", "A problem being run; its outputs are those of `peridot run`, however it is stepped")
      .def_property_readonly("step", &PyRun::step)
      .def_property_readonly("time", [](PyRun& r) { return r.sim().state().time; })
      .def_property_readonly("time_step", [](PyRun& r) { return r.sim().time_step(); })
      .def_property_readonly("total_steps", [](PyRun& r) { return r.sim().total_steps(); })
      .def_property_readonly("end_time", &PyRun::end_time)
      .def_property_readonly("num_points", [](PyRun& r) { return r.sim().num_owned(); })
      .def_property_readonly("finished", [](PyRun& r) { return r.run->finished(); })
      .def("advance", [](PyRun& r, std::optional<std::int64_t> steps, std::optional<double> to_time,
                         std::optional<std::int64_t> to_step) {
             if (steps.has_value() + to_time.has_value() + to_step.has_value() > 1)
               throw py::value_error("give one of steps=, to_time= or to_step=");
             std::int64_t target = r.sim().total_steps();
             if (steps) {
               if (*steps < 0) throw py::value_error("steps must not be negative");
               target = r.step() + *steps;
             } else if (to_step) {
               target = *to_step;
             } else if (to_time) {
               // The first step at or after the time (steps are of equal length, so this is exact up to round-off).
               const double steps_left = (*to_time - r.sim().state().time) / r.sim().time_step();
               target = r.step() + std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(steps_left - 1e-9)));
             }
             if (target < r.step())
               throw py::value_error(fmt::format("step {} is before the current step {}", target, r.step()));
             r.advance_to(target);
           },
           py::arg("steps") = py::none(), py::kw_only(), py::arg("to_time") = py::none(), py::arg("to_step") = py::none(),
           "Steps on: advance(10), advance(to_time=1e-5) (the first step at or after it), advance(to_step=k), or "
           "advance() to the end. Ctrl-C stops between steps (KeyboardInterrupt). Raises NumericalError.")
      .def("finish", [](PyRun& r) { r.run->finish(); },
           "Writes this step's frame and history row if not yet written and moves the results into place.")
      .def("field", &field, py::arg("name"),
           "A point field as a read-only numpy array: vectors n×3 (displacement, velocity, force_density, position), "
           "scalars n (damage, dilatation, volume, …). Views of the solver's arrays where it keeps them (they change "
           "as the run advances), copies otherwise.")
      .def_property_readonly("fields", [](PyRun& r) {
        std::vector<std::string> names = {"position"};
        for (const peridot::PointField& f : peridot::point_fields())
          if (f.scope == peridot::FieldScope::always) names.emplace_back(f.name);
        for (const std::string& name : peridot::optional_exodus_fields(r.sim())) names.push_back(name);
        return names;
      })
      .def("node_set", [](PyRun& r, const std::string& name) {
             for (const peridot::NodeSet& set : r.sim().node_sets())
               if (set.name == name) return py::array_t<std::uint32_t>(static_cast<py::ssize_t>(set.points.size()), set.points.data());
             throw py::key_error(fmt::format("no node set '{}'", name));
           },
           py::arg("name"), "the point indices of a node set (a copy)")
      .def("history", &history, "the history rows written so far, {column: numpy array} (a copy)")
      .def("reaction", [](PyRun& r, const std::string& name) {
             for (const peridot::NodeSet& set : r.sim().node_sets())
               if (set.name == name) {
                 const peridot::Vec3 f = r.sim().reaction(set.name);
                 return py::make_tuple(f.x, f.y, f.z);
               }
             throw py::key_error(fmt::format("no node set '{}'", name));
           },
           py::arg("node_set"), "the reaction force (N) on a node set at the current step")
      .def("set_boundary_condition", [](PyRun& r, const std::string& node_set, const std::string& component,
                                        const std::string& value) {
             const auto& conditions = r.problem.boundary_conditions;
             const int axis = component.size() == 1 && component[0] >= 'x' && component[0] <= 'z' ? component[0] - 'x' : -1;
             if (axis < 0) throw py::value_error(fmt::format("component '{}': give x, y or z", component));
             const std::string where = fmt::format("boundary condition on {}, {}", node_set, component);
             const peridot::Expression e{value, peridot::SourcePos{where, 0, 0}, false};
             bool found = false;
             for (std::size_t k = 0; k < conditions.size(); ++k)
               if (conditions[k].node_set == node_set && conditions[k].component == axis) {
                 r.sim().loads().set_boundary_value(k, e, r.sim().state().time);
                 found = true;
               }
             if (found) return;
             std::vector<std::string> known;
             for (const peridot::BoundaryConditionSpec& bc : conditions)
               known.push_back(fmt::format("({}, {})", bc.node_set, static_cast<char>('x' + bc.component)));
             throw py::key_error(fmt::format("no boundary condition on node set '{}', component {}; the deck has: {}",
                                             node_set, component, known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
           },
           py::arg("node_set"), py::arg("component"), py::arg("value"),
           "Replaces the value (an expression of x, y, z, t; m or m/s) of the deck's boundary condition on this node "
           "set and component ('x', 'y', 'z') from the next step on; its kind (displacement or velocity) stays. Not "
           "recorded in checkpoints. Raises InputError for a malformed expression.");
}
