// BSDFs: a closed family of value types behind std::variant. All directions are in the local shading
// frame (z = shading normal, flipped to the side of wo), so a BSDF never sees world space.
// f() excludes the cosine; sample() returns f, the sampled wi and its solid-angle pdf.
#pragma once

#include <variant>

#include "bsdf/lambert.h"

namespace candela {

using Bsdf = std::variant<LambertBsdf>;

inline Color bsdf_f(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
    return std::visit([&](const auto& x) { return x.f(wo, wi); }, b);
}
inline float bsdf_pdf(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
    return std::visit([&](const auto& x) { return x.pdf(wo, wi); }, b);
}
inline BsdfSample bsdf_sample(const Bsdf& b, const Vec3& wo, Vec2 u) {
    return std::visit([&](const auto& x) { return x.sample(wo, u); }, b);
}

}  // namespace candela
