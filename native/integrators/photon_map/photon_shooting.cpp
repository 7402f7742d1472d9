#include "integrators/photon_map/photon_shooting.h"

#include <algorithm>

#include "core/error.h"
#include "core/parallel_ordered.h"
#include "core/rng.h"
#include "scene/shutter_time.h"

namespace candela {

PhotonShot shoot_photons(const PhotonTracer& tracer, const EmitterSet& emitters, PhotonStore store, int64_t paths,
                         uint64_t seed, uint32_t stream, RenderContext& ctx, const char* stage_name) {
    PhotonShot shot;
    double power = 0.0;
    for (uint32_t i = 0; i < emitters.size(); ++i) power += emitters.power(i);
    shot.flux_scale = power > 0.0 ? float(power) : 1.f;
    shot.emitted_paths = double(paths);
    if (paths <= 0 || emitters.empty()) return shot;
    const float inv_scale = 1.f / shot.flux_scale;
    const PhotonPaths kind = store == PhotonStore::Caustic ? PhotonPaths::CausticOnly : PhotonPaths::All;
    const size_t batches = size_t((paths + k_photon_batch - 1) / k_photon_batch);
    const uint64_t key = hash_combine(seed, 0x70686f746f6eULL + stream);
    // Motion blur: every photon is traced at the caller's shutter time (its pass's, or the shutter's middle).
    const float time = shutter_time();
    ctx.counters.stage.begin(stage_name, paths);
    int64_t done = 0;
    struct Batch {
        std::vector<Photon> photons;
        PathStats stats;
    };
    parallel_ordered(
        ctx.threads, batches, size_t(2 * resolve_thread_count(ctx.threads)),
        [&](size_t b) {
            Batch out;
            if (ctx.cancel.cancelled()) return out;
            const ShutterScope scope(time);
            SobolSampler sampler(key, 1);
            const int64_t begin = int64_t(b) * k_photon_batch, end = std::min(paths, begin + k_photon_batch);
            out.photons.reserve(size_t(2 * (end - begin)));  // about 1.4 stored per path in the Cornell box
            for (int64_t i = begin; i < end; ++i) {
                sampler.start_pixel_sample(stream, uint32_t(uint64_t(key) >> 32), uint32_t(i));
                uint32_t arrival = 0;
                tracer.trace(
                    sampler, kind,
                    [&](const PhotonArrival& a) {
                        const bool keep = store == PhotonStore::Global    ? !a.caustic
                                          : store == PhotonStore::Caustic ? a.caustic
                                                                          : a.depth >= 1;
                        ++arrival;
                        if (!keep) return;
                        const float u =
                            float(hash32(uint32_t(mix64(key ^ (uint64_t(i) << 8) ^ arrival))) >> 8) * 0x1p-24f;
                        Photon p;
                        p.x = a.hit->p.x;
                        p.y = a.hit->p.y;
                        p.z = a.hit->p.z;
                        p.flux = encode_flux(a.flux * inv_scale, u);
                        p.dir = encode_direction(a.w);
                        if (p.flux != 0u) out.photons.push_back(p);
                    },
                    out.stats);
            }
            return out;
        },
        [&](size_t b, Batch&& batch) {
            shot.photons.insert(shot.photons.end(), batch.photons.begin(), batch.photons.end());
            batch.stats.flush(ctx.counters);
            done = std::min(paths, int64_t(b + 1) * k_photon_batch);
            ctx.counters.stage.set_done(done);
        },
        &ctx.cancel);
    if (ctx.cancel.cancelled()) throw Cancelled();
    return shot;
}

PhotonMap build_photon_map(PhotonShot shot, RenderContext& ctx, const char* stage_name) {
    PhotonMap map;
    ctx.counters.stage.begin(stage_name, 2 * int64_t(shot.photons.size()));
    map.build(std::move(shot.photons), ctx.threads, &ctx.counters.stage, &ctx.cancel);
    map.flux_scale = shot.flux_scale;
    map.emitted_paths = shot.emitted_paths;
    return map;
}

}  // namespace candela
