// Embree 3's side of tools/benches/meshload.sh: loads an OBJ with a plain C loader (`v` and
// `f` lines, polygons fan-triangulated, 1-based and negative indices; vertices shared as
// written) and builds it as one triangle geometry with RTC_BUILD_QUALITY_MEDIUM, as
// trace.cpp does, then prints the load and build times and the process's peak resident
// memory (VmHWM), one per line, for the table of docs/performance-trace.md.
//
//   glint-embree-objload FILE.obj [--threads N]
#include <embree3/rtcore.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

static double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// VmHWM of this process in kB (0 when /proc is not there).
static long peak_rss_kb() {
    FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    long kb = 0;
    while (std::fgets(line, sizeof line, f)) {
        if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::strtol(line + 6, nullptr, 10);
    }
    std::fclose(f);
    return kb;
}

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: glint-embree-objload FILE.obj [--threads N]\n");
        return 2;
    }
    int threads = 0;
    if (argc == 4 && std::strcmp(argv[2], "--threads") == 0) threads = std::atoi(argv[3]);
    auto start = std::chrono::steady_clock::now();
    FILE* f = std::fopen(argv[1], "r");
    if (!f) {
        std::perror(argv[1]);
        return 1;
    }
    std::vector<float> vertices;
    std::vector<unsigned> indices;
    std::vector<long> corners;
    static char line[1 << 16];
    while (std::fgets(line, sizeof line, f)) {
        char* p = line;
        while (*p == ' ' || *p == '\t') p++;
        if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
            char* end = p + 1;
            for (int k = 0; k < 3; k++) vertices.push_back(std::strtof(end, &end));
        } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
            corners.clear();
            char* q = p + 1;
            for (;;) {
                char* end;
                long i = std::strtol(q, &end, 10);
                if (end == q) break;
                long count = long(vertices.size() / 3);
                corners.push_back(i < 0 ? count + i : i - 1);
                q = end;
                while (*q && *q != ' ' && *q != '\t' && *q != '\n') q++;  // skip /t/n
            }
            for (size_t k = 1; k + 1 < corners.size(); k++) {
                indices.push_back(unsigned(corners[0]));
                indices.push_back(unsigned(corners[k]));
                indices.push_back(unsigned(corners[k + 1]));
            }
        }
    }
    std::fclose(f);
    double load = seconds_since(start);
    size_t nv = vertices.size() / 3, nt = indices.size() / 3;
    for (unsigned i : indices) {
        if (i >= nv) {
            std::fprintf(stderr, "face index %u out of range\n", i + 1);
            return 1;
        }
    }
    start = std::chrono::steady_clock::now();
    std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
    RTCDevice device = rtcNewDevice(config.c_str());
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree reads 16 bytes per vertex: share our buffer, padded by one float.
    vertices.push_back(0.0f);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               vertices.data(), 0, 3 * sizeof(float), nv);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               indices.data(), 0, 3 * sizeof(unsigned), nt);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    double build = seconds_since(start);
    std::printf("embree %s, %zu triangles, %zu vertices\n", RTC_VERSION_STRING, nt, nv);
    std::printf("load: %.3f s\n", load);
    std::printf("build: %.3f s\n", build);
    std::printf("peak RSS: %ld kB\n", peak_rss_kb());
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}
