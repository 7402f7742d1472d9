#include "shader_test_helpers.h"

namespace candela::test {

uint32_t ProgramBuilder::image(uint32_t w, uint32_t h, const std::vector<Color>& rgb, TexColorSpace cs) {
    const uint32_t first = uint32_t(texels.size() / 4);
    for (const Color& c : rgb) texels.insert(texels.end(), {c.x, c.y, c.z, 1.f});
    texture_info.insert(texture_info.end(), {first, w, h, uint32_t(cs), uint32_t(TexStorage::Float)});
    return uint32_t(texture_info.size() / 5 - 1);
}

uint32_t ProgramBuilder::byte_image(uint32_t w, uint32_t h, const std::vector<std::array<uint8_t, 3>>& rgb,
                                    TexColorSpace cs) {
    const uint32_t first = uint32_t(bytes.size() / 4);
    for (const auto& c : rgb) bytes.insert(bytes.end(), {c[0], c[1], c[2], 255});
    texture_info.insert(texture_info.end(), {first, w, h, uint32_t(cs), uint32_t(TexStorage::Byte)});
    return uint32_t(texture_info.size() / 5 - 1);
}

uint32_t ProgramBuilder::ramp(const std::vector<std::array<float, 4>>& table) {
    for (const auto& e : table) ramps.insert(ramps.end(), e.begin(), e.end());
    return uint32_t(ramps.size() / (4 * k_ramp_size) - 1);
}

uint32_t ProgramBuilder::op(ShaderOpCode code, uint32_t a, uint32_t b, uint32_t c, std::array<uint32_t, 4> i) {
    ops.push_back(ShaderOp{code, a, b, c, {i[0], i[1], i[2], i[3]}});
    return uint32_t(ops.size()) - 1 - program_start.back();
}

uint32_t ProgramBuilder::constant(const Vec3& v) {
    const uint32_t offset = uint32_t(consts.size());
    consts.insert(consts.end(), {v.x, v.y, v.z});
    return op(ShaderOpCode::Const, 0, 0, 0, {offset, 0, 0, 0});
}

uint32_t ProgramBuilder::end_program() {
    program_start.push_back(uint32_t(ops.size()));
    return uint32_t(program_start.size() - 2);
}

void ProgramBuilder::bind(InputTarget target, uint32_t row, uint32_t column, uint32_t channels, uint32_t program,
                          uint32_t reg) {
    bindings.insert(bindings.end(), {uint32_t(target), row, column, channels, program, reg});
}

std::shared_ptr<const ShaderLibrary> ProgramBuilder::library() const {
    return std::make_shared<const ShaderLibrary>(TexturePools{texels, bytes, texture_info}, ramps, consts, ops,
                                                 program_start);
}

void ProgramBuilder::add_to(SceneArrays& a) const {
    if (!texture_info.empty()) {
        if (!texels.empty()) a.set("textures", ElemType::F32, {texels.size() / 4, 4}, texels.data());
        if (!bytes.empty()) a.set("textures_u8", ElemType::U8, {bytes.size() / 4, 4}, bytes.data());
        a.set("texture_info", ElemType::U32, {texture_info.size() / 5, 5}, texture_info.data());
    }
    if (!ramps.empty()) a.set("ramps", ElemType::F32, {ramps.size() / (4 * k_ramp_size), k_ramp_size, 4}, ramps.data());
    if (!consts.empty()) a.set("shader_consts", ElemType::F32, {consts.size()}, consts.data());
    std::vector<uint32_t> rows;
    for (const ShaderOp& o : ops)
        rows.insert(rows.end(), {uint32_t(o.code), o.a, o.b, o.c, o.i[0], o.i[1], o.i[2], o.i[3]});
    a.set("shader_ops", ElemType::U32, {ops.size(), 8}, rows.data());
    a.set("shader_programs", ElemType::U32, {program_start.size()}, program_start.data());
    if (!bindings.empty()) a.set("input_bindings", ElemType::U32, {bindings.size() / 6, 6}, bindings.data());
}

Vec3 eval(const ShaderLibrary& lib, uint32_t p, uint32_t r, const ShadingInputs& in) {
    ShaderRegisters regs(lib.program_size(p));
    lib.evaluate(p, in, regs.data());
    return regs[r];
}

}  // namespace candela::test
