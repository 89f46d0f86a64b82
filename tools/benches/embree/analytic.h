// glint's sphere and box instances for Embree's user geometry: the same f32 tests as
// glint's src/tracer/geometry/intersect.rs (sphere_interval, intersect_sphere, box_interval,
// intersect_box, to_object_space), in the same order of operations, so that both tracers
// find the same hits. The constants are glint's (src/constants.rs).
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>

const uint32_t KIND_SPHERE = 0;
const uint32_t KIND_CUBE = 1;
const float T_MISS = FLT_MAX;
const float SAFE_RCP_LIMIT = 1.0e30f;

struct Instance {
    uint32_t kind;
    float world_to_object[12];  // rows of a 3×4 affine matrix
    float object_to_world[12];
};

inline float safe_rcp(float x) {
    return std::fabs(x) > 1.0f / SAFE_RCP_LIMIT ? 1.0f / x : std::copysign(SAFE_RCP_LIMIT, x);
}

inline float dot3(const float* a, const float* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// glint's sphere_interval and intersect_sphere (unit sphere at the origin).
inline float intersect_sphere(const float* o, const float* d, float t_max) {
    float a = dot3(d, d);
    float b = dot3(o, d);
    float c = dot3(o, o) - 1.0f;
    float ba = b / a;
    float l[3] = {o[0] - d[0] * ba, o[1] - d[1] * ba, o[2] - d[2] * ba};
    float discriminant = a * (1.0f - dot3(l, l));
    if (discriminant < 0.0f) return T_MISS;
    float q = -b - std::copysign(std::sqrt(discriminant), b);
    float t0 = 0.0f, t1 = 0.0f;
    if (q != 0.0f) {
        float r0 = c / q, r1 = q / a;
        t0 = std::min(r0, r1);
        t1 = std::max(r0, r1);
    }
    if (t0 > 0.0f && t0 < t_max) return t0;
    if (t1 > 0.0f && t1 < t_max) return t1;
    return T_MISS;
}

// glint's box_interval and intersect_box (the box [0,1]³).
inline float intersect_box(const float* o, const float* d, float t_max) {
    float t_near = -FLT_MAX, t_far = FLT_MAX;
    for (int k = 0; k < 3; ++k) {
        float inv = safe_rcp(d[k]);
        float t0 = (0.0f - o[k]) * inv, t1 = (1.0f - o[k]) * inv;
        t_near = std::max(t_near, std::min(t0, t1));
        t_far = std::min(t_far, std::max(t0, t1));
    }
    if (t_near > t_far) return T_MISS;
    float t = t_near > 0.0f ? t_near : t_far;
    return t > 0.0f && t < t_max ? t : T_MISS;
}

// glint's intersect_instance for the two kinds: t in (0, t_max), else T_MISS.
inline float intersect_instance(const Instance& inst, const float* o, const float* d, float t_max) {
    const float* m = inst.world_to_object;
    float oo[3], od[3];
    for (int r = 0; r < 3; ++r) {
        oo[r] = dot3(m + 4 * r, o) + m[4 * r + 3];
        od[r] = dot3(m + 4 * r, d);
    }
    return inst.kind == KIND_SPHERE ? intersect_sphere(oo, od, t_max) : intersect_box(oo, od, t_max);
}

// World bounds of the instance: its object box's corners through object→world, padded
// by a relative 1e-5 (as glint pads its grid bounds) so rounding cannot drop a hit.
inline void world_bounds(const Instance& inst, float* lower, float* upper) {
    const float lo = inst.kind == KIND_SPHERE ? -1.0f : 0.0f;
    const float* m = inst.object_to_world;
    for (int r = 0; r < 3; ++r) {
        float centre = m[4 * r + 3], lo_sum = centre, hi_sum = centre;
        for (int k = 0; k < 3; ++k) {
            float a = m[4 * r + k] * lo, b = m[4 * r + k] * 1.0f;
            lo_sum += std::min(a, b);
            hi_sum += std::max(a, b);
        }
        float pad = 1.0e-5f * std::max(std::fabs(lo_sum), std::fabs(hi_sum)) + 1.0e-30f;
        lower[r] = lo_sum - pad;
        upper[r] = hi_sum + pad;
    }
}
