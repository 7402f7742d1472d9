#include "scene/embree_device.h"

#include "core/error.h"

namespace candela {

EmbreeDevice::EmbreeDevice(int threads) {
    const std::string config = "threads=" + std::to_string(threads > 0 ? threads : 0) + ",verbose=0";
    m_device = rtcNewDevice(config.c_str());
    if (!m_device)
        throw InternalError("Embree: could not create a device (" + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceErrorFunction(m_device, &EmbreeDevice::on_error, this);
    rtcSetDeviceMemoryMonitorFunction(m_device, &EmbreeDevice::on_memory, this);
}

bool EmbreeDevice::on_memory(void* self, ssize_t bytes, bool) {
    // Called from Embree's build threads: allocations positive, releases negative. Never refuses.
    static_cast<EmbreeDevice*>(self)->m_bytes.fetch_add(bytes, std::memory_order_relaxed);
    return true;
}

EmbreeDevice::~EmbreeDevice() {
    if (m_device) rtcReleaseDevice(m_device);
}

void EmbreeDevice::on_error(void* self, RTCError code, const char* message) {
    auto* d = static_cast<EmbreeDevice*>(self);
    std::lock_guard<std::mutex> lock(d->m_mutex);
    if (d->m_code == RTC_ERROR_NONE) {
        d->m_code = code;
        d->m_message = message ? message : "";
    }
}

void EmbreeDevice::check(const char* what) {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_code == RTC_ERROR_NONE) return;
    const RTCError code = m_code;
    const std::string msg = m_message;
    m_code = RTC_ERROR_NONE;
    m_message.clear();
    if (code == RTC_ERROR_CANCELLED) throw Cancelled();
    if (code == RTC_ERROR_OUT_OF_MEMORY) throw InternalError(std::string("Embree ran out of memory while ") + what);
    throw InternalError(std::string("Embree error ") + std::to_string(static_cast<int>(code)) + " while " + what +
                        ": " + msg);
}

}  // namespace candela
