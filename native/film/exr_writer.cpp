#include "film/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <algorithm>

#include "core/error.h"

namespace candela {

void write_exr_rgba(const std::string& path, int width, int height, const std::vector<float>& rgba) {
    if (rgba.size() != size_t(width) * height * 4) throw InternalError("write_exr_rgba: buffer size mismatch");
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* names[4] = {"R", "G", "B", "A"};
        for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        // EXR rows run top to bottom; ours bottom to top.
        std::vector<float> top_down(rgba.size());
        const size_t row = size_t(width) * 4;
        for (int y = 0; y < height; ++y)
            std::copy_n(rgba.data() + size_t(height - 1 - y) * row, row, top_down.data() + size_t(y) * row);
        Imf::FrameBuffer fb;
        const size_t xs = 4 * sizeof(float), ys = row * sizeof(float);
        char* base = reinterpret_cast<char*>(top_down.data());
        for (int c = 0; c < 4; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys));
        file.setFrameBuffer(fb);
        file.writePixels(height);
    } catch (const std::exception& e) {
        throw InternalError("could not write '" + path + "': " + e.what());
    }
}

}  // namespace candela
