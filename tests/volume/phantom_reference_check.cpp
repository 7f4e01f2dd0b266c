// Compares makePhantom voxel by voxel with ../shared/tools/phantom.py (every voxel within
// +-1). Exits with the SKIP code when python3 with numpy or the script is not available, so
// CTest reports SKIP instead of a PASS that compared nothing.
#include "lw/volume/phantom.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

// The first Python that imports numpy: $LINEWORK_PYTHON, python3 on PATH (which may be a
// pyenv shim without numpy), then Debian's /usr/bin/python3 that phantom.py names.
std::string findPython() {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("LINEWORK_PYTHON"))
        candidates.push_back(env);
    candidates.push_back("python3");
    candidates.push_back("/usr/bin/python3");
    for (const auto& python : candidates)
        if (std::system(("'" + python + "' -c 'import numpy' > /dev/null 2>&1").c_str()) == 0)
            return python;
    return {};
}

std::string g_python;

int compare(glm::ivec3 dims, lw::volume::PhantomKind kind, const std::filesystem::path& dir) {
    const std::string name = std::string(lw::volume::phantomKindName(kind));
    const std::filesystem::path raw = dir / (name + ".raw");
    const std::string command = "'" + g_python + "' '" + std::string(LINEWORK_PHANTOM_PY) + "' " +
                                std::to_string(dims.x) + " " + std::to_string(dims.y) + " " +
                                std::to_string(dims.z) + " " + name + " '" + raw.string() + "'";
    if (std::system(command.c_str()) != 0) {
        std::printf("FAIL: %s failed\n", command.c_str());
        return 1;
    }
    const lw::volume::Volume ours = lw::volume::makePhantom(dims, kind);
    std::vector<std::int16_t> reference(ours.voxelCount());
    std::ifstream in(raw, std::ios::binary);
    in.read(reinterpret_cast<char*>(reference.data()), std::streamsize(reference.size() * 2));
    if (!in) {
        std::printf("FAIL: %s is shorter than %zu voxels\n", raw.string().c_str(),
                    reference.size());
        return 1;
    }
    const std::int16_t* voxels = ours.dataAs<std::int16_t>();
    std::size_t differing = 0, worse = 0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        const int d = std::abs(int(voxels[i]) - int(reference[i]));
        differing += d != 0;
        if (d > 1 && worse++ < 5)
            std::printf("FAIL: %s voxel %zu: %d vs phantom.py %d\n", name.c_str(), i, voxels[i],
                        reference[i]);
    }
    std::printf("%s %dx%dx%d: %zu of %zu voxels differ by 1, %zu by more\n", name.c_str(), dims.x,
                dims.y, dims.z, differing, reference.size(), worse);
    return worse == 0 ? 0 : 1;
}

} // namespace

int main() {
    if (!std::filesystem::exists(LINEWORK_PHANTOM_PY)) {
        std::printf("SKIP: %s not found\n", LINEWORK_PHANTOM_PY);
        return LINEWORK_SKIP_CODE;
    }
    g_python = findPython();
    if (g_python.empty()) {
        std::printf("SKIP: python3 with numpy not available\n");
        return LINEWORK_SKIP_CODE;
    }
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("lw_phantom_check_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    int failures = 0;
    failures += compare(glm::ivec3(64), lw::volume::PhantomKind::Ct, dir);
    failures += compare(glm::ivec3(64), lw::volume::PhantomKind::Sphere, dir);
    failures += compare(glm::ivec3(47, 38, 29), lw::volume::PhantomKind::Ct, dir);
    std::filesystem::remove_all(dir);
    return failures == 0 ? 0 : 1;
}
