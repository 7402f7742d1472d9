// RAII ownership of Embree 3 handles. The device's error callback stores the first error so it becomes
// an exception on the calling thread (Embree must never print or abort inside Blender).
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

namespace candela {

class EmbreeDevice {
public:
    explicit EmbreeDevice(int threads);
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;

    RTCDevice get() const { return m_device; }
    /// Throws InternalError (or Cancelled) if Embree reported an error since the last check.
    void check(const char* what);
    /// Bytes Embree holds for this device now (geometry buffers, BVHs), from its memory monitor.
    int64_t bytes() const { return m_bytes.load(std::memory_order_relaxed); }

private:
    static void on_error(void* self, RTCError code, const char* message);
    static bool on_memory(void* self, ssize_t bytes, bool post);
    std::atomic<int64_t> m_bytes{0};
    RTCDevice m_device = nullptr;
    std::mutex m_mutex;
    RTCError m_code = RTC_ERROR_NONE;
    std::string m_message;
};

/// Owns an RTCScene.
class EmbreeScene {
public:
    EmbreeScene() = default;
    explicit EmbreeScene(RTCScene s) : m_scene(s) {}
    ~EmbreeScene() {
        if (m_scene) rtcReleaseScene(m_scene);
    }
    EmbreeScene(EmbreeScene&& o) noexcept : m_scene(o.m_scene) { o.m_scene = nullptr; }
    EmbreeScene& operator=(EmbreeScene&& o) noexcept {
        std::swap(m_scene, o.m_scene);
        return *this;
    }
    RTCScene get() const { return m_scene; }

private:
    RTCScene m_scene = nullptr;
};

}  // namespace candela
