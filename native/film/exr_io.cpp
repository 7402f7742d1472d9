#include "film/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
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

std::vector<float> read_exr_rgba(const std::string& path, int* width, int* height) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        std::vector<float> top_down(size_t(w) * h * 4, 0.f);
        Imf::FrameBuffer fb;
        const size_t xs = 4 * sizeof(float), ys = size_t(w) * xs;
        char* base = reinterpret_cast<char*>(top_down.data()) - dw.min.x * xs - dw.min.y * ys;
        const char* names[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xs, ys, 1, 1, c == 3 ? 1.0 : 0.0));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        std::vector<float> out(top_down.size());
        const size_t row = size_t(w) * 4;
        for (int y = 0; y < h; ++y)
            std::copy_n(top_down.data() + size_t(h - 1 - y) * row, row, out.data() + size_t(y) * row);
        *width = w;
        *height = h;
        return out;
    } catch (const std::exception& e) {
        throw InvalidScene("could not read '" + path + "': " + e.what());
    }
}

std::map<std::string, std::vector<float>> read_exr_channels(const std::string& path, int* width, int* height) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        std::map<std::string, std::vector<float>> top_down;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
            top_down[it.name()].assign(size_t(w) * h, 0.f);
        Imf::FrameBuffer fb;
        const size_t xs = sizeof(float), ys = size_t(w) * xs;
        for (auto& [name, buf] : top_down) {
            char* base = reinterpret_cast<char*>(buf.data()) - dw.min.x * xs - dw.min.y * ys;
            fb.insert(name.c_str(), Imf::Slice(Imf::FLOAT, base, xs, ys));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        std::map<std::string, std::vector<float>> out;
        for (auto& [name, buf] : top_down) {
            std::vector<float>& o = out[name];
            o.resize(buf.size());
            for (int y = 0; y < h; ++y) std::copy_n(buf.data() + size_t(h - 1 - y) * w, w, o.data() + size_t(y) * w);
        }
        *width = w;
        *height = h;
        return out;
    } catch (const std::exception& e) {
        throw InvalidScene("could not read '" + path + "': " + e.what());
    }
}

}  // namespace candela
