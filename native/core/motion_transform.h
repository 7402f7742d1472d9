// Transform motion over the shutter (motion blur): a rigid-plus-scale transform sampled at evenly spaced times
// of the shutter interval (time 0 its opening, 1 its closing) and interpolated between the samples as Cycles 3.4
// and Embree do it (Embree's rtcSetGeometryTransformQuaternion): each sample is decomposed as M = T·R·S — S upper
// triangular (scale, shear and a shift), R a rotation kept as a unit quaternion, T a translation — and between
// two samples S and T are interpolated linearly and R by spherical linear interpolation (slerp). A rotating
// object then turns on an arc instead of shrinking through the chord, which linear matrix interpolation does.
// docs/light_paths.md ("Motion blur") describes the feature and its limits.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/transform.h"

namespace candela {

/// One sample of a moving transform, decomposed (Embree's RTCQuaternionDecomposition holds exactly these).
struct DecomposedTransform {
    float s[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};  // upper-triangular S with its shift (column 3)
    float q[4] = {1, 0, 0, 0};                                   // rotation quaternion (r, i, j, k)
    Vec3 t{0.f};                                                 // translation

    /// M = T·R·S by Gram–Schmidt on M's columns (a QR factorisation): R's columns are the orthonormalised
    /// columns of M, S = Rᵀ·M. A mirroring M (det < 0) keeps R a rotation and puts the reflection in S's last
    /// diagonal entry. The shift of S is zero (the translation carries the offset).
    static DecomposedTransform from(const Affine& m) {
        DecomposedTransform d;
        const Vec3 c0 = m.column(0), c1 = m.column(1), c2 = m.column(2);
        const Vec3 q0 = normalize(c0);
        Vec3 q1 = c1 - q0 * dot(q0, c1);
        q1 = normalize(q1);
        Vec3 q2 = cross(q0, q1);  // right-handed: R is a rotation
        const Vec3 r[3] = {q0, q1, q2};
        const Vec3 c[3] = {c0, c1, c2};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) d.s[i][j] = j < i ? 0.f : dot(r[i], c[j]);
        // Quaternion of the rotation matrix with columns q0, q1, q2 (Shepperd's method: the largest pivot).
        const float R[3][3] = {{q0.x, q1.x, q2.x}, {q0.y, q1.y, q2.y}, {q0.z, q1.z, q2.z}};
        const float tr = R[0][0] + R[1][1] + R[2][2];
        if (tr > 0.f) {
            const float w = std::sqrt(1.f + tr) * 2.f;
            d.q[0] = 0.25f * w;
            d.q[1] = (R[2][1] - R[1][2]) / w;
            d.q[2] = (R[0][2] - R[2][0]) / w;
            d.q[3] = (R[1][0] - R[0][1]) / w;
        } else if (R[0][0] > R[1][1] && R[0][0] > R[2][2]) {
            const float w = std::sqrt(1.f + R[0][0] - R[1][1] - R[2][2]) * 2.f;
            d.q[0] = (R[2][1] - R[1][2]) / w;
            d.q[1] = 0.25f * w;
            d.q[2] = (R[0][1] + R[1][0]) / w;
            d.q[3] = (R[0][2] + R[2][0]) / w;
        } else if (R[1][1] > R[2][2]) {
            const float w = std::sqrt(1.f + R[1][1] - R[0][0] - R[2][2]) * 2.f;
            d.q[0] = (R[0][2] - R[2][0]) / w;
            d.q[1] = (R[0][1] + R[1][0]) / w;
            d.q[2] = 0.25f * w;
            d.q[3] = (R[1][2] + R[2][1]) / w;
        } else {
            const float w = std::sqrt(1.f + R[2][2] - R[0][0] - R[1][1]) * 2.f;
            d.q[0] = (R[1][0] - R[0][1]) / w;
            d.q[1] = (R[0][2] + R[2][0]) / w;
            d.q[2] = (R[1][2] + R[2][1]) / w;
            d.q[3] = 0.25f * w;
        }
        d.t = m.translation();
        return d;
    }

    /// T·R·S as an affine matrix.
    Affine compose() const {
        const float w = q[0], x = q[1], y = q[2], z = q[3];
        const float R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                               {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                               {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
        Affine m;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) {
                float v = 0.f;
                for (int k = 0; k < 3; ++k) v += R[i][k] * s[k][j];
                m.m[i][j] = v + (j == 3 ? t[i] : 0.f);
            }
        return m;
    }

    /// The interpolation at fraction f ∈ [0, 1] from a to b: S and T linearly, R by slerp (the quaternions are
    /// on one hemisphere: MotionTransform makes consecutive samples' dot product non-negative).
    static DecomposedTransform lerp(const DecomposedTransform& a, const DecomposedTransform& b, float f) {
        DecomposedTransform d;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) d.s[i][j] = a.s[i][j] + (b.s[i][j] - a.s[i][j]) * f;
        d.t = a.t + (b.t - a.t) * f;
        float cos_theta = a.q[0] * b.q[0] + a.q[1] * b.q[1] + a.q[2] * b.q[2] + a.q[3] * b.q[3];
        float wa = 1.f - f, wb = f;
        if (cos_theta < 0.9995f) {  // slerp; nearly equal rotations take the (normalised) linear blend
            const float theta = std::acos(std::fmax(-1.f, std::fmin(1.f, cos_theta)));
            const float sin_theta = std::sin(theta);
            wa = std::sin((1.f - f) * theta) / sin_theta;
            wb = std::sin(f * theta) / sin_theta;
        }
        float n = 0.f;
        for (int k = 0; k < 4; ++k) {
            d.q[k] = wa * a.q[k] + wb * b.q[k];
            n += d.q[k] * d.q[k];
        }
        n = 1.f / std::sqrt(n);
        for (float& v : d.q) v *= n;
        return d;
    }
};

/// A transform sampled at steps ≥ 1 evenly spaced shutter times (one step: it does not move).
class MotionTransform {
public:
    MotionTransform() = default;
    explicit MotionTransform(const std::vector<Affine>& steps) {
        for (const Affine& a : steps) {
            DecomposedTransform d = DecomposedTransform::from(a);
            if (!m_steps.empty()) {  // the shorter arc between consecutive samples
                const float* p = m_steps.back().q;
                if (p[0] * d.q[0] + p[1] * d.q[1] + p[2] * d.q[2] + p[3] * d.q[3] < 0.f)
                    for (float& v : d.q) v = -v;
            }
            m_steps.push_back(d);
        }
    }
    size_t steps() const { return m_steps.size(); }
    bool moves() const { return m_steps.size() > 1; }
    const DecomposedTransform& step(size_t i) const { return m_steps[i]; }
    /// The transform at shutter time `time` ∈ [0, 1] (clamped).
    Affine at(float time) const {
        if (m_steps.size() == 1) return m_steps[0].compose();
        const float x = std::fmin(std::fmax(time, 0.f), 1.f) * float(m_steps.size() - 1);
        const size_t i = std::min(size_t(x), m_steps.size() - 2);
        return DecomposedTransform::lerp(m_steps[i], m_steps[i + 1], x - float(i)).compose();
    }
    /// Adds `offset` to every sample's translation (camera-world space).
    void translate(const Vec3& offset) {
        for (DecomposedTransform& d : m_steps) d.t += offset;
    }

private:
    std::vector<DecomposedTransform> m_steps;
};

}  // namespace candela
