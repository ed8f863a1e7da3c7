// python/src/module.cpp — nmesh._nmesh, the compiled half of the Python package nmesh.
//
// Thin bindings over the library's public headers. The functions here take arrays already in the
// library's layout and refuse anything else with TypeError: points and vertices float32 of shape
// (N, 3), C-contiguous and aligned (so that the buffer *is* an array of nmesh::Vec3), faces
// uint32 of shape (F, 3) likewise. nmesh/__init__.py converts what a caller passes into that
// layout, once, and not at all when it already is; so the points of reconstruct() are read in
// place, through a PointSpan over the caller's buffer.
//
// The long calls (learning, measuring, reading and writing files) run with the GIL released.
// The progress callback takes the GIL back to check for Ctrl-C and to call the Python callable.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/io.h"
#include "nmesh/metrics.h"
#include "nmesh/parameters.h"
#include "nmesh/point_span.h"
#include "nmesh/reconstruct.h"
#include "nmesh/run_report.h"
#include "nmesh/vec3.h"

namespace py = pybind11;

namespace {

static_assert(sizeof(nmesh::Vec3) == 3 * sizeof(float), "a (N, 3) float32 buffer must be an array of Vec3");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t),
              "a (F, 3) uint32 buffer must be an array of triangles");

// nmesh.InputError (a subclass of ValueError), created when the module is initialised. The
// module holds a reference and so does this pointer, which is never released: exception types
// live as long as the interpreter.
PyObject* g_input_error = nullptr;

// A Python str from bytes in the file system's encoding, as os.fsdecode makes: the library's
// messages hold paths, which need not be UTF-8.
py::str fs_str(const char* text) {
    PyObject* s = PyUnicode_DecodeFSDefault(text);
    if (!s) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(s);
}

// Whether `a` is a C-contiguous, aligned array of dtype T and shape (n, 3).
template <class T>
bool is_rows_of_three(const py::array& a) {
    return py::isinstance<py::array_t<T>>(a) && a.ndim() == 2 && a.shape(1) == 3 &&
           (a.flags() & py::array::c_style) != 0 && reinterpret_cast<std::uintptr_t>(a.data()) % alignof(T) == 0;
}

// The points of `a` as a PointSpan over its own buffer (no copy). `a` must outlive the span.
nmesh::PointSpan point_view(const py::array& a, const char* name) {
    if (!is_rows_of_three<float>(a))
        throw py::type_error(std::string(name) +
                             " must be a C-contiguous, aligned float32 array of shape (N, 3) "
                             "(the functions of the package nmesh convert any other array)");
    return {static_cast<const nmesh::Vec3*>(a.data()), static_cast<std::size_t>(a.shape(0))};
}

// A mesh copied from the arrays (IndexedMesh owns vectors; the writer and the metrics take one).
nmesh::IndexedMesh mesh_from(const py::array& vertices, const py::array& faces) {
    const nmesh::PointSpan positions = point_view(vertices, "vertices");
    if (!is_rows_of_three<std::uint32_t>(faces))
        throw py::type_error(
            "faces must be a C-contiguous, aligned uint32 array of shape (F, 3) "
            "(the functions of the package nmesh convert any other integer array)");
    nmesh::IndexedMesh mesh;
    mesh.positions.assign(positions.begin(), positions.end());
    const auto* triangles = static_cast<const std::array<std::uint32_t, 3>*>(faces.data());
    mesh.triangles.assign(triangles, triangles + faces.shape(0));
    return mesh;
}

// A NumPy array of shape (rows, 3) over the vector's storage, which the array then owns (through
// a capsule that deletes the vector with the array's last reference): the library's output is
// handed over without a copy. Element is Vec3 or a triangle; Scalar is float, or int32 for the
// triangles' uint32 indices (reinterpreted, which is exact below 2^31: see mesh_arrays).
template <class Scalar, class Element>
py::array_t<Scalar> adopt_rows(std::vector<Element>&& rows) {
    static_assert(sizeof(Element) == 3 * sizeof(Scalar), "three scalars per row");
    auto owner = std::make_unique<std::vector<Element>>(std::move(rows));
    const auto n = static_cast<py::ssize_t>(owner->size());
    auto* data = reinterpret_cast<Scalar*>(owner->data());
    py::capsule base(owner.get(), [](void* p) { delete static_cast<std::vector<Element>*>(p); });
    owner.release();  // the capsule owns it now
    return py::array_t<Scalar>({n, py::ssize_t(3)}, {py::ssize_t(sizeof(Element)), py::ssize_t(sizeof(Scalar))}, data,
                               base);
}

// (vertices (V, 3) float32, faces (F, 3) int32), taking the mesh's storage.
std::pair<py::array, py::array> mesh_arrays(nmesh::IndexedMesh&& mesh) {
    // Faces are int32 (NumPy's usual index type); every index is below the vertex count.
    if (mesh.positions.size() > std::size_t(std::numeric_limits<std::int32_t>::max()))
        throw py::value_error("the mesh has " + std::to_string(mesh.positions.size()) +
                              " vertices, more than int32 faces can index");
    py::array vertices = adopt_rows<float>(std::move(mesh.positions));
    py::array faces = adopt_rows<std::int32_t>(std::move(mesh.triangles));
    return {std::move(vertices), std::move(faces)};
}

// The progress callback given to reconstruct(), which runs with the GIL released: it takes the
// GIL, lets Python run its signal handlers (Ctrl-C raises KeyboardInterrupt there) and calls the
// user's callable as progress(vertices, target, seconds) during the learning. Any Python
// exception, from either, cancels the learning and is kept, to be raised once reconstruct() has
// returned.
class ProgressBridge {
public:
    explicit ProgressBridge(py::object callback) : callback_(std::move(callback)) {}

    bool operator()(const nmesh::Progress& progress) {
        py::gil_scoped_acquire gil;
        if (error_) return false;  // cancelled already; the library may report once more
        try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            // The finishing stage's reports only give Ctrl-C its chance: the callable hears of the
            // learning (the stage is bounded by the learning's time and cannot be cancelled).
            if (callback_.is_none() || progress.finishing) return true;
            const py::object answer = callback_(progress.vertices, progress.target_vertices, progress.seconds);
            if (answer.is_none()) return true;  // a callback without a return statement continues
            const int keep_going = PyObject_IsTrue(answer.ptr());
            if (keep_going < 0) throw py::error_already_set();  // an object without a truth value
            return keep_going != 0;
        } catch (py::error_already_set& e) {
            error_ = std::move(e);
            return false;
        }
    }

    bool failed() const { return error_.has_value(); }

    // With the GIL held: raises the kept Python exception, if any.
    void raise_if_failed() {
        if (error_) throw *error_;
    }

private:
    py::object callback_;
    std::optional<py::error_already_set> error_;
};

// The library names Parameters' fields; the Python keyword for target_vertices is `vertices`.
void validate(const nmesh::Parameters& params) {
    try {
        params.validate();
    } catch (const nmesh::ParameterError& e) {
        if (e.parameter() != "target_vertices") throw;
        std::string message = e.what();
        const std::string field = "invalid parameter target_vertices";
        if (message.compare(0, field.size(), field) == 0)
            message.replace(0, field.size(), "invalid parameter vertices");
        throw nmesh::ParameterError("vertices", message);
    }
}

// reconstruct() and, when `metrics`, evaluate() on its mesh against the whole cloud, as the
// command-line tool does for --stats. Returns (vertices, faces, the --stats JSON, cancelled).
py::tuple reconstruct(const py::array& points, std::uint32_t target_vertices, double alpha_w, double alpha_n,
                      double alpha, std::uint32_t cvs, std::uint32_t cec, bool edge_swap, bool finish,
                      std::uint64_t seed, double settle, std::uint32_t finish_rounds, std::uint32_t fit_rounds,
                      std::uint32_t surface_fit_rounds, std::uint32_t exchange_passes,
                      std::uint32_t index_points_per_vertex,
                      const std::string& topology, bool fold_guard, bool solid_start, double min_hole,
                      double stray_ratio, double adaptivity, std::uint32_t threads, const py::object& progress, bool metrics) {
    const nmesh::PointSpan cloud = point_view(points, "points");  // `points` is kept alive by the caller's frame
    nmesh::Parameters params;
    params.target_vertices = target_vertices;
    params.alpha_w = alpha_w;
    params.alpha_n = alpha_n;
    params.alpha = alpha;
    params.cvs = cvs;
    params.cec = cec;
    params.edge_swap = edge_swap;
    params.finish = finish;
    params.seed = seed;
    params.settle = settle;
    params.finish_rounds = finish_rounds;
    params.fit_rounds = fit_rounds;
    params.surface_fit_rounds = surface_fit_rounds;
    params.exchange_passes = exchange_passes;
    params.index_points_per_vertex = index_points_per_vertex;
    params.topology = nmesh::parse_topology(topology.c_str());  // ParameterError: ValueError
    params.fold_guard = fold_guard;
    params.solid_start = solid_start;
    params.min_hole = float(min_hole);
    params.stray_ratio = float(stray_ratio);
    params.adaptivity = adaptivity;
    params.threads = threads;
    validate(params);  // before the GIL is released: a bad parameter costs nothing

    ProgressBridge bridge(progress);
    nmesh::Callbacks callbacks;
    callbacks.progress = [&bridge](const nmesh::Progress& p) { return bridge(p); };
    nmesh::Result result;
    nmesh::QualityReport quality;
    {
        // A C++ exception thrown in here reacquires the GIL as it leaves this scope.
        py::gil_scoped_release release;
        result = nmesh::reconstruct(cloud, params, callbacks);
        if (metrics && !bridge.failed()) {
            nmesh::EvalOptions options;
            options.threads = params.threads;
            quality = nmesh::evaluate(cloud, result.mesh, options);
        }
    }
    bridge.raise_if_failed();  // KeyboardInterrupt, or the callback's own exception

    std::ostringstream json;
    nmesh::write_run_json(json, "<array>", params, result, quality);
    const bool cancelled = result.cancelled;
    auto [vertices, faces] = mesh_arrays(std::move(result.mesh));
    return py::make_tuple(std::move(vertices), std::move(faces), py::str(json.str()), cancelled);
}

// Raises `type`(message) with the attribute `name` set to `value` (both str in the file system's
// encoding, as a path is): the structured part of a library error, e.path or e.parameter.
void raise_with(PyObject* type, const char* message, const char* name, const std::string& value) {
    const py::str text = fs_str(message), attribute = fs_str(value.c_str());
    const py::object error = py::reinterpret_steal<py::object>(PyObject_CallFunctionObjArgs(type, text.ptr(), nullptr));
    if (!error || PyObject_SetAttrString(error.ptr(), name, attribute.ptr()) != 0) return;  // that error is raised
    PyErr_SetObject(type, error.ptr());
}

py::array read_points(const std::string& path) {
    nmesh::PointCloud cloud;
    {
        py::gil_scoped_release release;
        cloud = nmesh::read_points(path);
    }
    return adopt_rows<float>(std::move(cloud.points));
}

py::tuple read_mesh(const std::string& path) {
    nmesh::IndexedMesh mesh;
    {
        py::gil_scoped_release release;
        mesh = nmesh::read_mesh(path);
    }
    auto [vertices, faces] = mesh_arrays(std::move(mesh));
    return py::make_tuple(std::move(vertices), std::move(faces));
}

void write_mesh(const std::string& path, const py::array& vertices, const py::array& faces, bool ascii) {
    const nmesh::IndexedMesh mesh = mesh_from(vertices, faces);
    nmesh::MeshWriteOptions options;
    options.ply_ascii = ascii;
    py::gil_scoped_release release;
    nmesh::write_mesh(path, mesh, options);
}

// The metrics of `nmesh eval`, as the JSON object of `nmesh eval --json`.
py::str evaluate(const py::array& points, const py::array& vertices, const py::array& faces, std::uint32_t threads) {
    const nmesh::PointSpan cloud = point_view(points, "points");
    const nmesh::IndexedMesh mesh = mesh_from(vertices, faces);
    nmesh::EvalOptions options;
    options.threads = threads;
    std::ostringstream json;
    {
        py::gil_scoped_release release;
        nmesh::write_json(json, nmesh::evaluate(cloud, mesh, options));
    }
    return py::str(json.str());
}

}  // namespace

PYBIND11_MODULE(_nmesh, m) {
    m.doc() = "The compiled part of the package nmesh; use the functions of nmesh, which convert their arguments.";
    m.attr("__version__") = NMESH_VERSION;

    g_input_error = PyErr_NewExceptionWithDoc(
        "nmesh.InputError",
        "The points cannot be reconstructed or measured: fewer than 4 distinct points, all on one line, "
        "a NaN or infinite coordinate, or a cloud that cannot carry the target size.",
        PyExc_ValueError, nullptr);
    if (!g_input_error) throw py::error_already_set();
    m.add_object("InputError", py::handle(g_input_error).inc_ref());

    // The library's exceptions as Python's: a bad parameter is a ValueError with the parameter's
    // name as e.parameter, a file that cannot be read or written an OSError (the message starts
    // with the path) with the path as e.path, an unusable cloud nmesh.InputError. Anything else
    // falls through to pybind11's own translations.
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const nmesh::InputError& e) {
            PyErr_SetObject(g_input_error, fs_str(e.what()).ptr());
        } catch (const nmesh::ParameterError& e) {
            raise_with(PyExc_ValueError, e.what(), "parameter", e.parameter());
        } catch (const nmesh::IoError& e) {
            raise_with(PyExc_OSError, e.what(), "path", e.path());
        } catch (const nmesh::Error& e) {
            PyErr_SetObject(PyExc_RuntimeError, fs_str(e.what()).ptr());
        }
    });

    using py::arg;
    m.def("reconstruct", &reconstruct, arg("points"), arg("target_vertices"), arg("alpha_w"), arg("alpha_n"),
          arg("alpha"), arg("cvs"), arg("cec"), arg("edge_swap"), arg("finish"), arg("seed"), arg("settle"),
          arg("finish_rounds"), arg("fit_rounds"), arg("surface_fit_rounds"), arg("exchange_passes"),
          arg("index_points_per_vertex"),
          arg("topology"), arg("fold_guard"), arg("solid_start"), arg("min_hole"), arg("stray_ratio"), arg("adaptivity"), arg("threads"),
          arg("progress").none(true), arg("metrics"),
          "Learns a mesh from a float32 (N, 3) C-contiguous array, read in place; returns "
          "(vertices, faces, stats JSON, cancelled).");
    m.def("read_points", &read_points, arg("path"), "The points of a file as a float32 (N, 3) array.");
    m.def("read_mesh", &read_mesh, arg("path"), "(vertices float32 (V, 3), faces int32 (F, 3)) of a mesh file.");
    m.def("write_mesh", &write_mesh, arg("path"), arg("vertices"), arg("faces"), arg("ascii"),
          "Writes float32 (V, 3) vertices and uint32 (F, 3) faces to a .ply, .obj or .off file.");
    m.def("evaluate", &evaluate, arg("points"), arg("vertices"), arg("faces"), arg("threads"),
          "The metrics of `nmesh eval` as its JSON text.");
}
