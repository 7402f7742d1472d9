// Reading and writing images as OpenEXR (the only OpenEXR include in Candela).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace candela {

/// Writes RGBA float32 pixels stored bottom row first (Blender's order) as a scene-linear EXR
/// (half-float channels are not used: values above 65504 stay exact). Throws InternalError on failure.
void write_exr_rgba(const std::string& path, int width, int height, const std::vector<float>& rgba_bottom_up);

/// Reads an EXR's R, G, B (and A, 1 if absent) as float32 rows bottom to top. Throws InvalidScene.
std::vector<float> read_exr_rgba(const std::string& path, int* width, int* height);

/// Reads every channel of an EXR by its full name (a multilayer EXR's "ViewLayer.Depth.Z", …) as float32 rows
/// bottom to top. Throws InvalidScene.
std::map<std::string, std::vector<float>> read_exr_channels(const std::string& path, int* width, int* height);

}  // namespace candela
