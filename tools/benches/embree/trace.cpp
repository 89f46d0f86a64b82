// Embree 3 beside `glint bench --trace`: traces the rays that glint dumped
// (`glint bench --trace SCENE.lua --dump-rays FILE`) through an Embree scene of the same
// geometry, with the single-ray API (rtcIntersect1 for primary rays, rtcOccluded1 for
// shadow rays) on N threads, and prints the same three lines as glint, the same hit
// counts and checksum, and how many rays Embree answers differently from glint.
//
// Usage: glint-embree-trace DUMP [--threads N] [--repeat K]
// Dump format: src/bin/glint/bench/trace_dump.rs in the glint repository, and README.md here.

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "analytic.h"

namespace {

const uint32_t NO_ITEM = 0xffffffffu;

struct DumpRay {
    float org[3];
    float dir[3];
    float t_max;
    uint32_t glint_answer;
};
static_assert(sizeof(DumpRay) == 32, "dump ray rows are 32 bytes");

struct Dump {
    std::vector<float> triangles;  // 9 floats per triangle
    std::vector<Instance> instances;
    std::vector<DumpRay> primary;
    std::vector<DumpRay> shadow;
};

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "glint-embree-trace: error: %s\n", message.c_str());
    std::exit(1);
}

void read_exact(FILE* f, void* out, size_t bytes, const char* what) {
    if (bytes != 0 && std::fread(out, 1, bytes, f) != bytes) {
        fail(std::string("the dump ends inside its ") + what);
    }
}

Dump read_dump(const char* path) {
    FILE* f = std::fopen(path, "rb");
    if (!f) fail(std::string("cannot open ") + path);
    char magic[8];
    read_exact(f, magic, 8, "header");
    if (std::memcmp(magic, "GLINTRAY", 8) != 0) fail(std::string(path) + " is not a glint ray dump");
    uint32_t header[5];
    read_exact(f, header, sizeof header, "header");
    if (header[0] != 1) fail("dump version " + std::to_string(header[0]) + ", this harness reads 1");
    Dump d;
    d.triangles.resize(size_t(header[1]) * 9);
    d.instances.resize(header[2]);
    d.primary.resize(header[3]);
    d.shadow.resize(header[4]);
    read_exact(f, d.triangles.data(), d.triangles.size() * sizeof(float), "triangles");
    for (Instance& inst : d.instances) {
        read_exact(f, &inst.kind, 4, "instances");
        read_exact(f, inst.world_to_object, sizeof inst.world_to_object, "instances");
        read_exact(f, inst.object_to_world, sizeof inst.object_to_world, "instances");
        if (inst.kind != KIND_SPHERE && inst.kind != KIND_CUBE) fail("an instance of unknown kind " + std::to_string(inst.kind));
    }
    read_exact(f, d.primary.data(), d.primary.size() * sizeof(DumpRay), "primary rays");
    read_exact(f, d.shadow.data(), d.shadow.size() * sizeof(DumpRay), "shadow rays");
    std::fclose(f);
    return d;
}

std::atomic<int64_t> embree_bytes{0};
// Bytes Embree held once the geometry buffers were filled, before the BVH was built.
int64_t buffer_bytes = 0;

bool memory_monitor(void*, ssize_t bytes, bool) {
    embree_bytes += bytes;
    return true;
}

// User geometry callbacks: one primitive per instance (a transformed unit sphere or box).
void instance_bounds(const RTCBoundsFunctionArguments* args) {
    const Instance* instances = static_cast<const Instance*>(args->geometryUserPtr);
    world_bounds(instances[args->primID], &args->bounds_o->lower_x, &args->bounds_o->upper_x);
}

void instance_intersect(const RTCIntersectFunctionNArguments* args) {
    if (args->N != 1) fail("only the single-ray API is used");
    if (!args->valid[0]) return;
    const Instance& inst = static_cast<const Instance*>(args->geometryUserPtr)[args->primID];
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, 1);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, 1);
    float org[3] = {RTCRayN_org_x(ray, 1, 0), RTCRayN_org_y(ray, 1, 0), RTCRayN_org_z(ray, 1, 0)};
    float dir[3] = {RTCRayN_dir_x(ray, 1, 0), RTCRayN_dir_y(ray, 1, 0), RTCRayN_dir_z(ray, 1, 0)};
    float t = intersect_instance(inst, org, dir, RTCRayN_tfar(ray, 1, 0));
    if (t == T_MISS) return;
    RTCRayN_tfar(ray, 1, 0) = t;
    RTCHitN_geomID(hit, 1, 0) = args->geomID;
    RTCHitN_primID(hit, 1, 0) = args->primID;
    RTCHitN_u(hit, 1, 0) = 0.0f;
    RTCHitN_v(hit, 1, 0) = 0.0f;
    RTCHitN_Ng_x(hit, 1, 0) = 0.0f;
    RTCHitN_Ng_y(hit, 1, 0) = 0.0f;
    RTCHitN_Ng_z(hit, 1, 0) = 1.0f;
    RTCHitN_instID(hit, 1, 0, 0) = args->context->instID[0];
}

void instance_occluded(const RTCOccludedFunctionNArguments* args) {
    if (args->N != 1) fail("only the single-ray API is used");
    if (!args->valid[0]) return;
    const Instance& inst = static_cast<const Instance*>(args->geometryUserPtr)[args->primID];
    RTCRayN* ray = args->ray;
    float org[3] = {RTCRayN_org_x(ray, 1, 0), RTCRayN_org_y(ray, 1, 0), RTCRayN_org_z(ray, 1, 0)};
    float dir[3] = {RTCRayN_dir_x(ray, 1, 0), RTCRayN_dir_y(ray, 1, 0), RTCRayN_dir_z(ray, 1, 0)};
    if (intersect_instance(inst, org, dir, RTCRayN_tfar(ray, 1, 0)) != T_MISS) {
        RTCRayN_tfar(ray, 1, 0) = -INFINITY;
    }
}

const unsigned GEOM_TRIANGLES = 0;
const unsigned GEOM_INSTANCES = 1;

RTCScene build_scene(RTCDevice device, Dump& d) {
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    size_t n = d.triangles.size() / 9;
    RTCGeometry tris = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(tris, RTC_BUILD_QUALITY_MEDIUM);
    // A triangle soup, as glint stores it: three vertices per triangle.
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(tris, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    unsigned* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(tris, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    std::copy(d.triangles.begin(), d.triangles.end(), v);
    for (size_t i = 0; i < 3 * n; ++i) idx[i] = unsigned(i);
    rtcCommitGeometry(tris);
    rtcAttachGeometryByID(scene, tris, GEOM_TRIANGLES);
    rtcReleaseGeometry(tris);
    RTCGeometry user = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(user, unsigned(d.instances.size()));
    rtcSetGeometryUserData(user, d.instances.data());
    rtcSetGeometryBoundsFunction(user, instance_bounds, nullptr);
    rtcSetGeometryIntersectFunction(user, instance_intersect);
    rtcSetGeometryOccludedFunction(user, instance_occluded);
    rtcCommitGeometry(user);
    rtcAttachGeometryByID(scene, user, GEOM_INSTANCES);
    rtcReleaseGeometry(user);
    buffer_bytes = embree_bytes.load();
    rtcCommitScene(scene);
    return scene;
}

// Runs body(i) for i in [0, n) on `threads` threads, in chunks handed out in order.
template <class F>
void parallel_for(size_t n, unsigned threads, F body) {
    std::atomic<size_t> next{0};
    const size_t chunk = 1024;
    auto worker = [&]() {
        for (size_t start; (start = next.fetch_add(chunk)) < n;) {
            for (size_t i = start; i < std::min(n, start + chunk); ++i) body(i);
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
}

template <class F>
double fastest_seconds(int repeat, F run) {
    double best = INFINITY;
    for (int r = 0; r < std::max(repeat, 1); ++r) {
        auto start = std::chrono::steady_clock::now();
        run();
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return best;
}

// glint's `rate`: three decimals, or three significant digits below 1.
std::string rate(double x) {
    int decimals = x > 0.0 && x < 1.0 ? std::max(3, 2 - int(std::floor(std::log10(x)))) : 3;
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, x);
    return text;
}

void fill_ray(RTCRay& r, const DumpRay& d) {
    r.org_x = d.org[0];
    r.org_y = d.org[1];
    r.org_z = d.org[2];
    r.dir_x = d.dir[0];
    r.dir_y = d.dir[1];
    r.dir_z = d.dir[2];
    r.tnear = 0.0f;
    r.tfar = d.t_max;
    r.time = 0.0f;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
}

}  // namespace

int main(int argc, char** argv) {
    const char* path = nullptr;
    unsigned threads = 2;
    int repeat = 3;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--threads" && i + 1 < argc) threads = unsigned(std::max(1, std::atoi(argv[++i])));
        else if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
        else if (!path && a[0] != '-') path = argv[i];
        else fail("usage: glint-embree-trace DUMP [--threads N] [--repeat K]");
    }
    if (!path) fail("usage: glint-embree-trace DUMP [--threads N] [--repeat K]");
    Dump d = read_dump(path);
    std::string config = "threads=" + std::to_string(threads);
    RTCDevice device = rtcNewDevice(config.c_str());
    if (!device) fail("rtcNewDevice failed");
    rtcSetDeviceMemoryMonitorFunction(device, memory_monitor, nullptr);
    RTCScene scene = nullptr;
    double build = fastest_seconds(1, [&]() { scene = build_scene(device, d); });
    const uint32_t num_instances = uint32_t(d.instances.size());

    std::vector<uint32_t> items(d.primary.size());
    double t_primary = fastest_seconds(repeat, [&]() {
        parallel_for(d.primary.size(), threads, [&](size_t i) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            RTCRayHit rh;
            fill_ray(rh.ray, d.primary[i]);
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &context, &rh);
            uint32_t g = rh.hit.geomID;
            items[i] = g == RTC_INVALID_GEOMETRY_ID ? NO_ITEM
                       : g == GEOM_TRIANGLES       ? num_instances + rh.hit.primID
                                                   : rh.hit.primID;
        });
    });
    std::vector<uint8_t> occluded(d.shadow.size());
    double t_shadow = fastest_seconds(repeat, [&]() {
        parallel_for(d.shadow.size(), threads, [&](size_t i) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            RTCRay r;
            fill_ray(r, d.shadow[i]);
            rtcOccluded1(scene, &context, &r);
            occluded[i] = r.tfar < 0.0f;
        });
    });

    size_t hits = 0, blocked = 0, primary_differ = 0, shadow_differ = 0;
    uint64_t checksum = 0;
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i] != NO_ITEM) {
            ++hits;
            checksum += uint64_t(items[i]) + 1;
        }
        primary_differ += items[i] != d.primary[i].glint_answer;
    }
    for (size_t i = 0; i < occluded.size(); ++i) {
        blocked += occluded[i];
        shadow_differ += occluded[i] != d.shadow[i].glint_answer;
    }
    size_t triangles = d.triangles.size() / 9;
    std::printf("primary: %s Mrays/s\n", rate(d.primary.size() / t_primary / 1e6).c_str());
    std::printf("shadow: %s Mrays/s\n", rate(d.shadow.size() / t_shadow / 1e6).c_str());
    std::printf("memory: %.1f bytes per triangle\n", double(embree_bytes.load()) / double(std::max<size_t>(triangles, 1)));
    std::printf("of which geometry buffers (a vertex per corner, as glint stores them, and indices): %.1f bytes per triangle\n", double(buffer_bytes) / double(std::max<size_t>(triangles, 1)));
    std::printf("embree %s, %zu triangles, %u other items, %u threads\n", RTC_VERSION_STRING, triangles, num_instances, threads);
    std::printf("primary rays: %zu (%zu hit) in %.1f ms\n", d.primary.size(), hits, t_primary * 1e3);
    std::printf("shadow rays: %zu (%zu occluded) in %.1f ms\n", d.shadow.size(), blocked, t_shadow * 1e3);
    std::printf("hit checksum: %llu\n", (unsigned long long)checksum);
    std::printf("answers differing from glint's: primary %zu of %zu, shadow %zu of %zu\n", primary_differ, d.primary.size(), shadow_differ, d.shadow.size());
    std::printf("build (RTC_BUILD_QUALITY_MEDIUM, scene and buffers): %.1f ms; times: fastest of %d\n", build * 1e3, repeat);
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}
