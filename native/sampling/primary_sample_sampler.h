// The primary-sample-space sampler of Metropolis light transport (Kelemen et al. 2002, "A simple and robust
// mutation strategy for the Metropolis light transport algorithm"; pbrt-v3 §16.4.3). A path is a deterministic
// function of a vector u ∈ [0, 1)^∞ of uniforms (the sampler's coordinates, by the same dimension indices every
// other sampler uses, sampling/sampler.h): the Markov chain mutates u and the path tracer reads it through the same
// sample_1d/sample_2d interface, so the integrator's code is not duplicated.
//
// Mutations, one per iteration (start_iteration):
//   large step (probability p_large): every coordinate a fresh uniform — an independent sample, which keeps the
//     chain ergodic;
//   small step: every coordinate u_i ← (u_i + σ·N(0, 1)) mod 1 — a symmetric random walk on the unit torus, so the
//     proposal density T(u → u') = T(u' → u) and the Metropolis acceptance is min(1, f(u')/f(u)).
// Coordinates are mutated lazily, when the path reads them: a coordinate last touched at iteration m, read at
// iteration n, first catches up with the large steps it missed (a fresh uniform, if a large step happened after m)
// and then with the n − m small steps since (one Gaussian step of σ·√(n − m): the sum of n − m independent
// N(0, σ²) steps — exact on the torus because wrapping commutes with addition). Every coordinate read in an
// iteration keeps a backup of its previous value and time stamp; reject() restores them exactly, accept() drops
// them. Values the path never reads cost nothing.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/vec.h"

namespace candela {

/// The inverse error function (Giles 2010, single-precision approximation): erf(erf_inv(x)) ≈ x on (−1, 1).
float erf_inv(float x);

class PrimarySampleSampler {
public:
    PrimarySampleSampler(float sigma = 0.01f, float p_large = 0.3f) : m_sigma(sigma), m_p_large(p_large) {}

    /// Re-seeds the stream of fresh values and of step decisions (the state itself is kept).
    void seed(uint64_t key) { m_rng.seed(mix64(key), key ^ 0x6d6c7473616d706cULL); }

    /// Begins the next proposal: a large step with probability p_large (or `force_large`), else a small step.
    void start_iteration(bool force_large = false) {
        ++m_iteration;
        m_large = force_large || m_rng.next_float() < m_p_large;
        m_touched.clear();
    }
    /// The proposal became the chain's state.
    void accept() {
        if (m_large) m_last_large = m_iteration;
        m_touched.clear();
    }
    /// The proposal was rejected: every coordinate read since start_iteration is restored, bit for bit, and the
    /// iteration count with it (the next proposal starts from the same state and time stamps).
    void reject() {
        for (uint32_t i : m_touched) {
            Coordinate& c = m_x[i];
            c.value = c.backup;
            c.modified = c.modified_backup;
        }
        --m_iteration;
        m_touched.clear();
    }
    bool large_step() const { return m_large; }
    int64_t iteration() const { return m_iteration; }
    float sigma() const { return m_sigma; }
    float p_large() const { return m_p_large; }

    /// Coordinate `dim` of the current proposal (mutated on first read in this iteration).
    float sample_1d(uint32_t dim) const { return ready(dim); }
    Vec2 sample_2d(uint32_t dim) const {
        const float x = ready(dim);
        return {x, ready(dim + 1)};
    }
    /// The coordinates read so far (for tests: the state's values).
    size_t size() const { return m_x.size(); }
    float value(uint32_t dim) const { return dim < m_x.size() ? m_x[dim].value : -1.f; }

    // The Sampler interface's positioning: a primary-sample state has no pixel or sample index.
    void start_pixel_sample(uint32_t, uint32_t, uint32_t) {}

private:
    struct Coordinate {
        float value = 0.f, backup = 0.f;
        int64_t modified = -1, modified_backup = -1;  // the iteration the value belongs to (-1: never drawn)
    };
    /// Brings coordinate i up to the current iteration (reads mutate: the sampler is lazily evaluated, hence the
    /// `mutable` state behind the const read interface the path code uses).
    float ready(uint32_t i) const {
        if (i >= m_x.size()) m_x.resize(size_t(i) + 1);
        Coordinate& c = m_x[i];
        if (c.modified == m_iteration) return c.value;
        // Not read since before the state's last large step (or never): the state's value is a fresh uniform drawn
        // as of that step — part of the state, not of the proposal, so it is drawn before the backup.
        if (c.modified < m_last_large) {
            c.value = m_rng.next_float();
            c.modified = m_last_large;
            if (c.modified == m_iteration) return c.value;  // the initial state (iteration 0)
        }
        c.backup = c.value;
        c.modified_backup = c.modified;
        m_touched.push_back(i);
        if (m_large) {
            c.value = m_rng.next_float();
        } else {
            // The small steps since the last touch, folded into one: N(0, σ²·(n − m)), wrapped to [0, 1).
            const int64_t n = m_iteration - c.modified;
            const float normal = 1.41421356f * erf_inv(2.f * m_rng.next_float() - 1.f);
            float v = c.value + normal * m_sigma * std::sqrt(float(n));
            v -= std::floor(v);
            c.value = v < 1.f ? v : 0.f;  // v − ⌊v⌋ rounds up to 1 for tiny negative v
        }
        c.modified = m_iteration;
        return c.value;
    }

    float m_sigma, m_p_large;
    mutable Pcg32 m_rng;
    mutable std::vector<Coordinate> m_x;
    mutable std::vector<uint32_t> m_touched;
    int64_t m_iteration = 0;
    int64_t m_last_large = 0;  // the iteration of the state's last accepted large step (0: the initial state is one)
    bool m_large = false;
};

}  // namespace candela
