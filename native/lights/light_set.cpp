#include <cmath>

#include "core/error.h"
#include "input/scene_arrays.h"
#include "lights/light.h"

namespace candela {

LightPdfMode parse_light_pdf_mode(const std::string& name) {
    if (name == "AREA") return LightPdfMode::Area;
    if (name == "SOLID_ANGLE") return LightPdfMode::SolidAngle;
    throw InvalidScene("light_pdf '" + name + "' is unknown (AREA, SOLID_ANGLE)");
}

const char* light_pdf_mode_name(LightPdfMode mode) { return mode == LightPdfMode::Area ? "AREA" : "SOLID_ANGLE"; }

const std::vector<std::string>& light_columns() {
    static const std::vector<std::string> cols = {
        "strength_r", "strength_g", "strength_b", "pos_x",      "pos_y", "pos_z", "dir_x",
        "dir_y",      "dir_z",      "u_x",        "u_y",        "u_z",   "v_x",   "v_y",
        "v_z",        "radius",     "spot_size",  "spot_blend", "angle", "shape", "visible_camera"};
    return cols;
}

const std::vector<std::string>& light_type_names() {
    static const std::vector<std::string> names = {"POINT", "SPOT", "SUN", "AREA"};
    return names;
}

std::vector<Light> load_blender_lights(const SceneArrays& arrays, const Vec3& offset) {
    std::vector<Light> out;
    if (!arrays.has("lights")) return out;
    const Array& types = arrays.get("light_type");
    const Array& rows = arrays.get("lights");
    const size_t cols = rows.shape[1];
    if (cols < light_columns().size())
        throw InvalidScene("'lights' has " + std::to_string(cols) + " columns, expected " +
                           std::to_string(light_columns().size()));
    for (size_t i = 0; i < types.shape[0]; ++i) {
        const float* r = rows.data<float>() + i * cols;
        const std::string where = "light " + std::to_string(i);
        const Color strength(r[0], r[1], r[2]);
        const Vec3 pos = Vec3(r[3], r[4], r[5]) + offset;
        const Vec3 dir(r[6], r[7], r[8]);
        const Vec3 u(r[9], r[10], r[11]), v(r[12], r[13], r[14]);
        const float radius = r[15], spot_size = r[16], spot_blend = r[17], angle = r[18];
        const bool ellipse = r[19] > 0.5f;
        const bool visible_camera = r[20] > 0.5f;
        if (min_component(strength) < 0.f) throw InvalidScene(where + ": negative strength");
        if (is_black(strength)) continue;
        const uint32_t type = types.data<uint32_t>()[i];
        if (type >= light_type_names().size())
            throw InvalidScene(where + ": light_type " + std::to_string(type) + " is unknown");
        const std::string& name = light_type_names()[type];
        const bool directional = name != "POINT";
        if (directional && std::fabs(length(dir) - 1.f) > 1e-3f)
            throw InvalidScene(where + ": direction (dir_x, dir_y, dir_z) must be a unit vector");
        if (radius < 0.f) throw InvalidScene(where + ": negative radius");

        if (name == "POINT" || name == "SPOT") {
            PointLight p;
            p.position = pos;
            p.intensity = strength * k_inv_four_pi;
            p.radius = radius;
            if (name == "SPOT") {
                p.spot.direction = dir;
                p.spot.cos_half = std::cos(clamp(spot_size, 0.f, k_pi) * 0.5f);
                p.spot.smooth = (1.f - p.spot.cos_half) * clamp(spot_blend, 0.f, 1.f);
                p.spot.cycles34_cosine = true;
            }
            out.emplace_back(p);
        } else if (name == "SUN") {
            SunLight s;
            s.to_sun = -dir;
            s.irradiance = strength;
            s.tan_half_angle = std::tan(clamp(angle, 0.f, 3.f) * 0.5f);
            out.emplace_back(s);
        } else {
            AreaLight a;
            a.center = pos;
            a.u = u;
            a.v = v;
            a.normal = dir;
            a.ellipse = ellipse;
            a.visible_camera = visible_camera;
            a.area = length(u) * length(v) * (ellipse ? k_pi / 4.f : 1.f);
            if (!(a.area > 0.f)) continue;  // a zero-size area light emits nothing
            a.radiance = strength / (4.f * a.area);
            out.emplace_back(a);
        }
    }
    return out;
}

uint32_t LightSet::add(Light light) {
    const auto index = static_cast<uint32_t>(m_lights.size());
    if (std::holds_alternative<AreaLight>(light)) m_area_lights.push_back(index);
    if (auto* tri = std::get_if<TriangleLight>(&light)) tri->prepare();
    if (std::holds_alternative<WorldLight>(light)) {
        if (m_world >= 0) throw InternalError("a scene has one world light");
        m_world = static_cast<int>(index);
    }
    m_lights.push_back(std::move(light));
    return index;
}

void LightSet::finalize(float scene_radius) {
    std::vector<float> power(m_lights.size());
    for (size_t i = 0; i < m_lights.size(); ++i) {
        std::visit(
            [&](auto& l) {
                using T = std::decay_t<decltype(l)>;
                if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, WorldLight>)
                    l.scene_radius = scene_radius;
            },
            m_lights[i]);
        power[i] = light_power(m_lights[i]);
    }
    m_selection = Distribution1D(std::move(power));
}

}  // namespace candela
