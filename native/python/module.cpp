// candela._native: the pybind11 boundary (docs/architecture.md). Flat numpy arrays and a params dict in,
// a Session out. Blocking calls release the GIL; no worker thread ever calls into Python.
#include <cmath>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bsdf/material.h"
#include "bsdf/material_inputs.h"
#include "core/error.h"
#include "film/exr_io.h"
#include "film/pixel_filter.h"
#include "integrators/integrator.h"
#include "integrators/pixel_sampling.h"
#include "lights/light.h"
#include "sampling/sampler.h"
#include "scene/ray_visibility.h"
#include "session/memory_estimate.h"
#include "session/session.h"
#include "session/viewport_session.h"
#include "texture/node_math.h"
#include "texture/shader_program.h"

namespace py = pybind11;
using namespace candela;

namespace {

// 2: closure table; 3: shader programs, textures, UVs; 4: light column visible_camera, vertex_normals; 5: published
// integrator settings (capabilities' integrator_params, common_params), progress in the integrator's unit and stages.
constexpr int k_abi_version = 5;

template <typename T>
void add_array(SceneArrays& arrays, const std::string& key, ElemType type, const py::handle& value) {
    // forcecast converts dtypes (float64 → float32, int → uint32, bool → uint8); c_style makes it contiguous.
    py::array_t<T, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(value);
    } catch (const py::error_already_set&) {}
    if (!a) throw InvalidScene("scene array '" + key + "' cannot be converted to " + elem_type_name(type));
    std::vector<size_t> shape(a.shape(), a.shape() + a.ndim());
    arrays.set(key, type, std::move(shape), a.data());
}

SceneArrays arrays_from_dict(const py::dict& dict, std::vector<std::string>* unknown) {
    SceneArrays arrays;
    for (const auto& item : dict) {
        const std::string key = py::str(item.first);
        const ArraySpec* spec = find_array_spec(key);
        if (!spec) {
            unknown->push_back(key);
            continue;
        }
        switch (spec->type) {
        case ElemType::F32: add_array<float>(arrays, key, spec->type, item.second); break;
        case ElemType::U32: add_array<uint32_t>(arrays, key, spec->type, item.second); break;
        case ElemType::U8: add_array<uint8_t>(arrays, key, spec->type, item.second); break;
        }
    }
    return arrays;
}

Params params_from_dict(const py::dict& dict) {
    Params params;
    for (const auto& item : dict) {
        const std::string key = py::str(item.first);
        const py::handle v = item.second;
        if (py::isinstance<py::bool_>(v))
            params.set(key, v.cast<bool>());
        else if (py::isinstance<py::int_>(v))
            params.set(key, v.cast<int64_t>());
        else if (py::isinstance<py::float_>(v))
            params.set(key, v.cast<double>());
        else if (py::isinstance<py::str>(v))
            params.set(key, v.cast<std::string>());
        else if (py::hasattr(v, "item")) {  // numpy scalar
            const py::object s = v.attr("item")();
            if (py::isinstance<py::bool_>(s))
                params.set(key, s.cast<bool>());
            else if (py::isinstance<py::int_>(s))
                params.set(key, s.cast<int64_t>());
            else if (py::isinstance<py::float_>(s))
                params.set(key, s.cast<double>());
            else
                throw InvalidParameter("parameter '" + key + "' has an unsupported type");
        } else {
            throw InvalidParameter("parameter '" + key + "' must be a bool, int, float or str");
        }
    }
    return params;
}

std::unique_ptr<Session> make_session(const py::dict& arrays_dict, const py::dict& params_dict) {
    std::vector<std::string> unknown;
    SceneArrays arrays = arrays_from_dict(arrays_dict, &unknown);
    Params params = params_from_dict(params_dict);
    std::unique_ptr<Session> session;
    {
        py::gil_scoped_release release;  // validation of millions of triangles needs no Python
        session = std::make_unique<Session>(std::move(arrays), std::move(params));
    }
    for (const auto& key : unknown) session->add_log("unknown scene array '" + key + "' was ignored");
    return session;
}

/// [(level, message), ...], level "INFO" or "WARNING" (core/message_log.h).
py::list log_entries(const std::vector<LogEntry>& entries) {
    py::list out;
    for (const auto& e : entries) out.append(py::make_tuple(log_level_name(e.level), e.message));
    return out;
}

/// A published setting as the add-on builds its property from it (core/param_spec.h).
py::dict spec_dict(const ParamSpec& s) {
    py::dict d;
    d["key"] = s.key;
    d["label"] = s.label;
    d["description"] = s.description;
    d["group"] = s.group;
    d["active_if"] = s.active_if;
    switch (s.type) {
    case ParamType::Bool:
        d["type"] = "BOOL";
        d["default"] = s.default_value != 0.0;
        break;
    case ParamType::Int:
        d["type"] = "INT";
        d["default"] = int64_t(s.default_value);
        d["min"] = int64_t(s.min);
        d["max"] = int64_t(s.max);
        d["soft_max"] = int64_t(s.soft_max > 0.0 ? s.soft_max : s.max);
        break;
    case ParamType::Float:
        d["type"] = "FLOAT";
        d["default"] = s.default_value;
        d["min"] = s.min;
        d["max"] = s.max;
        d["soft_max"] = s.soft_max > 0.0 ? s.soft_max : s.max;
        break;
    case ParamType::Enum: {
        d["type"] = "ENUM";
        d["default"] = s.default_item;
        py::list items;
        for (const EnumItem& item : s.items) items.append(py::make_tuple(item.id, item.label, item.description));
        d["items"] = items;
        break;
    }
    }
    return d;
}

py::list spec_list(const std::vector<ParamSpec>& specs) {
    py::list out;
    for (const ParamSpec& s : specs) out.append(spec_dict(s));
    return out;
}

py::dict capabilities() {
    py::dict d;
    py::list integrators;
    py::dict integrator_params;
    py::list viewport_integrators;
    for (const auto& e : integrator_registry()) {
        integrators.append(py::make_tuple(e.name, e.description, e.label));
        integrator_params[py::str(e.name)] = spec_list(e.specs());
        if (e.viewport) viewport_integrators.append(e.name);
    }
    d["integrators"] = integrators;
    // The integrators the 3D viewport renders with (IntegratorEntry::viewport); it shows the others with PATH.
    d["viewport_integrators"] = viewport_integrators;
    d["integrator_params"] = integrator_params;
    d["common_params"] = spec_list(common_param_specs());
    d["target_arch"] = CANDELA_TARGET_ARCH;
    d["samplers"] = sampler_names();
    d["pixel_filters"] = PixelFilter::names();
    d["material_columns"] = material_columns();
    d["closure_columns"] = closure_columns();
    d["light_columns"] = light_columns();
    py::dict light_types, material_types;
    for (size_t i = 0; i < light_type_names().size(); ++i) light_types[py::str(light_type_names()[i])] = i;
    for (size_t i = 0; i < material_type_names().size(); ++i) material_types[py::str(material_type_names()[i])] = i;
    py::dict closure_types;
    for (size_t i = 0; i < closure_type_names().size(); ++i) closure_types[py::str(closure_type_names()[i])] = i;
    d["light_types"] = light_types;
    d["material_types"] = material_types;
    d["closure_types"] = closure_types;
    py::dict instance_flags;  // `instance_flags` bits (scene/ray_visibility.h)
    instance_flags["CAMERA"] = int(k_ray_camera);
    instance_flags["DIFFUSE"] = int(k_ray_diffuse);
    instance_flags["GLOSSY"] = int(k_ray_glossy);
    instance_flags["TRANSMISSION"] = int(k_ray_transmission);
    instance_flags["SHADOW"] = int(k_ray_shadow);
    instance_flags["HOLDOUT"] = int(k_object_holdout);
    d["instance_flags"] = instance_flags;
    // Shader programs (docs/architecture.md): every enumeration the add-on encodes, by name → value.
    auto enum_dict = [](const std::vector<std::string>& names) {
        py::dict e;
        for (size_t i = 0; i < names.size(); ++i) e[py::str(names[i])] = i;
        return e;
    };
    d["shader_ops"] = enum_dict(shader_op_names());
    d["coord_kinds"] = enum_dict(coord_kind_names());
    d["math_ops"] = enum_dict(math_op_names());
    d["mix_blends"] = enum_dict(mix_blend_names());
    d["color_models"] = enum_dict(color_model_names());
    d["normal_map_spaces"] = enum_dict(normal_map_space_names());
    d["image_projections"] = enum_dict(image_projection_names());
    d["tex_interpolations"] = enum_dict(tex_interpolation_names());
    d["tex_extensions"] = enum_dict(tex_extension_names());
    d["tex_color_spaces"] = enum_dict(tex_color_space_names());
    d["tex_storages"] = enum_dict(tex_storage_names());
    d["input_targets"] = enum_dict(input_target_names());
    d["musgrave_types"] = enum_dict(musgrave_type_names());
    d["voronoi_features"] = enum_dict(voronoi_feature_names());
    d["voronoi_metrics"] = enum_dict(voronoi_metric_names());
    d["wave_types"] = enum_dict(wave_type_names());
    d["wave_profiles"] = enum_dict(wave_profile_names());
    d["gradient_types"] = enum_dict(gradient_type_names());
    d["vector_math_ops"] = enum_dict(vector_math_op_names());
    d["map_range_types"] = enum_dict(map_range_type_names());
    d["sky_models"] = enum_dict(sky_model_names());
    py::list passes;
    for (const auto& [name, channels] : Session::pass_names()) passes.append(py::make_tuple(name, channels));
    d["passes"] = passes;
    py::dict strategy_passes;  // BDPT's strategy images by strategy depth (bdpt_strategy_depth's range)
    for (int depth = 0; depth <= 4; ++depth) strategy_passes[py::int_(depth)] = Session::strategy_pass_names(depth);
    d["bdpt_strategy_passes"] = strategy_passes;
    d["film_bytes_per_pixel"] = film_bytes_per_pixel();  // for the memory figure in Blender's header
    return d;
}

py::object get_pass(const Session& s, const std::string& name) {
    int channels = 0;
    std::vector<float> data;
    {
        py::gil_scoped_release release;
        data = s.get_pass(name, &channels);
    }
    if (channels == 0) return py::none();
    const size_t pixels = size_t(s.width()) * s.height();
    py::array_t<float> out({pixels, size_t(channels)});
    std::copy(data.begin(), data.end(), out.mutable_data());
    return std::move(out);
}

Affine affine_from(const py::handle& matrix) {
    auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(matrix);
    if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
        throw InvalidParameter("camera_to_world must be a 4x4 matrix");
    for (ssize_t i = 0; i < 16; ++i)
        if (!std::isfinite(a.data()[i])) throw InvalidParameter("camera_to_world is not finite");
    return Affine::from_rows(a.data());
}

uint64_t viewport_update_scene(ViewportSession& s, const py::dict& arrays_dict, const py::dict& params_dict) {
    std::vector<std::string> unknown;
    SceneArrays arrays = arrays_from_dict(arrays_dict, &unknown);
    Params params = params_from_dict(params_dict);
    py::gil_scoped_release release;  // validation of millions of triangles needs no Python
    return s.update_scene(std::move(arrays), std::move(params));
}

py::object viewport_image(const ViewportSession& s, uint64_t since) {
    ViewportImage image;
    bool fresh;
    {
        py::gil_scoped_release release;
        fresh = s.image(since, &image);
    }
    if (!fresh) return py::none();
    py::array_t<float> pixels({size_t(image.height), size_t(image.width), size_t(4)});
    std::copy(image.rgba.begin(), image.rgba.end(), pixels.mutable_data());
    py::dict d;
    d["version"] = image.version;
    d["request"] = image.request;
    d["frame_width"] = image.frame_width;
    d["frame_height"] = image.frame_height;
    d["x0"] = image.x0;
    d["y0"] = image.y0;
    d["width"] = image.width;
    d["height"] = image.height;
    d["pixel_size"] = image.pixel_size;
    d["samples"] = image.samples;
    d["pixels"] = pixels;
    return std::move(d);
}

py::dict viewport_status(const ViewportSession& s) {
    const ViewportStatus st = s.status();
    py::dict d;
    d["phase"] = st.phase;
    d["samples_done"] = st.samples_done;
    d["samples_total"] = st.samples_total;
    d["pixel_size"] = st.pixel_size;
    d["build_seconds"] = st.build_seconds;
    d["seconds_to_first_image"] =
        st.seconds_to_first_image >= 0.0 ? py::object(py::float_(st.seconds_to_first_image)) : py::none();
    d["scene_bytes"] = st.scene_bytes;
    d["film_bytes"] = st.film_bytes;
    d["bvh_built"] = st.bvh_built;
    d["bvh_reused"] = st.bvh_reused;
    d["error"] = st.error ? py::object(py::str(*st.error)) : py::none();
    d["note"] = st.note;
    return d;
}

}  // namespace

PYBIND11_MODULE(_native, m) {
    m.doc() = "Candela's native renderer core";
    m.attr("ABI_VERSION") = k_abi_version;
    m.def("capabilities", &capabilities, "Integrators, samplers, filters and array column layouts");
    m.def(
        "read_exr",
        [](const std::string& path) {
            int w = 0, h = 0;
            std::vector<float> rgba;
            {
                py::gil_scoped_release release;
                rgba = read_exr_rgba(path, &w, &h);
            }
            py::array_t<float> out({size_t(h), size_t(w), size_t(4)});
            std::copy(rgba.begin(), rgba.end(), out.mutable_data());
            return out;
        },
        py::arg("path"), "An EXR's RGBA as float32 (height, width, 4), row 0 = bottom (Blender's order)");
    m.def(
        "read_exr_channels",
        [](const std::string& path) {
            int w = 0, h = 0;
            std::map<std::string, std::vector<float>> channels;
            {
                py::gil_scoped_release release;
                channels = read_exr_channels(path, &w, &h);
            }
            py::dict out;
            for (const auto& [name, data] : channels) {
                py::array_t<float> a({size_t(h), size_t(w)});
                std::copy(data.begin(), data.end(), a.mutable_data());
                out[py::str(name)] = a;
            }
            return out;
        },
        py::arg("path"),
        "Every channel of an EXR by name (multilayer: 'ViewLayer.Depth.Z', ...) as float32 (height, width), "
        "row 0 = bottom");

    py::register_exception<InvalidScene>(m, "InvalidScene", PyExc_ValueError);
    py::register_exception<InvalidParameter>(m, "InvalidParameter", PyExc_ValueError);
    py::register_exception<InternalError>(m, "InternalError", PyExc_RuntimeError);

    py::class_<Session>(m, "Session")
        .def(py::init(&make_session), py::arg("arrays"), py::arg("params"))
        .def("start", &Session::start)
        .def("wait", &Session::wait, py::arg("timeout_s"), py::call_guard<py::gil_scoped_release>())
        .def("cancel", &Session::cancel)
        .def("join", &Session::join, py::call_guard<py::gil_scoped_release>())
        .def("progress",
             [](const Session& s) {
                 const SessionProgress p = s.progress();
                 py::dict d;
                 d["phase"] = phase_name(p.phase);
                 // samples_done/samples_total: the progress in the integrator's unit ("unit").
                 d["samples_done"] = p.work_done;
                 d["samples_total"] = p.work_total;
                 d["unit"] = p.unit;
                 d["stage"] = p.stage.name;
                 d["stage_done"] = p.stage.done;
                 d["stage_total"] = p.stage.total;
                 d["stage_percent"] = p.stage.percent;  // show the stage's progress as a percentage
                 d["note"] = p.stage.note;              // the integrator's status beside it ("1,234 records")
                 d["method"] = p.method;
                 d["fraction"] = p.fraction;
                 d["elapsed_s"] = p.elapsed_s;
                 d["relative_error"] = p.relative_error >= 0.0 ? py::object(py::float_(p.relative_error)) : py::none();
                 d["noise_unavailable"] = p.noise_unavailable;  // no honest estimate: the status shows "n/a"
                 d["stop_reason"] = stop_reason_name(p.stop_reason);
                 return d;
             })
        .def("stats",
             [](const Session& s) {
                 const SessionStats st = s.stats();
                 py::dict d;
                 d["build_seconds"] = st.build_seconds;
                 d["render_seconds"] = st.render_seconds;
                 d["samples_per_second"] = st.samples_per_second;
                 d["paths"] = st.paths;
                 d["rays"] = st.rays;
                 d["nan_samples"] = st.nan_samples;
                 d["unique_triangles"] = st.scene.unique_triangles;
                 d["instanced_triangles"] = st.scene.instanced_triangles;
                 d["meshes"] = st.scene.meshes;
                 d["instances"] = st.scene.instances;
                 d["emissive_triangles"] = st.scene.emissive_triangles;
                 d["embree_bytes"] = st.scene.embree_bytes;
                 d["shading_bytes"] = st.scene.shading_bytes;
                 d["scene_bytes"] = st.scene.embree_bytes + st.scene.shading_bytes;
                 py::list stages;  // the stages that ended, one per name, in the order they began
                 for (const StageProgress::Finished& f : st.stages) {
                     py::dict stage;
                     stage["name"] = f.name;
                     stage["runs"] = f.runs;
                     stage["seconds"] = f.seconds;
                     stage["done"] = f.done;
                     stage["total"] = f.total;
                     stages.append(stage);
                 }
                 d["stages"] = stages;
                 return d;
             })
        .def("get_pass", &get_pass, py::arg("name"))
        .def("take_log", &Session::take_log)
        .def("take_log_entries", [](Session& s) { return log_entries(s.take_log_entries()); })
        .def_property_readonly("error", &Session::error)
        .def_property_readonly("width", &Session::width)
        .def_property_readonly("height", &Session::height);

    // The 3D viewport's session (session/viewport_session.h): scene, settings and view updates restart it.
    py::class_<ViewportSession>(m, "ViewportSession")
        .def(py::init<int>(), py::arg("threads") = 0)
        .def("update_scene", &viewport_update_scene, py::arg("arrays"), py::arg("params"))
        .def(
            "update_settings",
            [](ViewportSession& s, const py::dict& params) { return s.update_settings(params_from_dict(params)); },
            py::arg("params"))
        .def(
            "set_view",
            [](ViewportSession& s, const py::dict& view, const py::handle& camera_to_world) {
                return s.set_view(params_from_dict(view), affine_from(camera_to_world));
            },
            py::arg("view"), py::arg("camera_to_world"))
        .def("pause", &ViewportSession::pause)
        .def("stop", &ViewportSession::stop, py::call_guard<py::gil_scoped_release>())
        .def("image_version", &ViewportSession::image_version)
        .def("image_request", &ViewportSession::image_request)
        .def("image", &viewport_image, py::arg("since") = 0)
        .def("status", &viewport_status)
        .def("take_log", &ViewportSession::take_log)
        .def("take_log_entries", [](ViewportSession& s) { return log_entries(s.take_log_entries()); });
}
