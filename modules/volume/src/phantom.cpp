#include "lw/volume/phantom.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

// Every expression below mirrors phantom.py's numpy code in float32 with the same operand
// order, so the only differences left are the last-bit rounding of exp/sin/cos (+-1 HU after
// rounding, which the reference allows). Do not "simplify" the arithmetic: it is the contract.

namespace lw::volume {
namespace {

constexpr double kW = 0.008;
constexpr double kBone = 1100.0;
constexpr double kMargin = 14 * kW;
constexpr double kPi = 3.14159265358979323846;

enum class PrimKind { Sph, TorZ, TorY, Shell, CapZ, Gyr };

struct Prim {
    PrimKind kind;
    std::array<double, 6> p{}; // phantom.py's parameters in double, as the bbox uses them
    std::array<float, 6> f{};  // the same cast to float32, as the signed distance uses them
    int i0 = 0, i1 = 0, j0 = 0, j1 = 0, k0 = 0, k1 = 0; // index box [i0, i1) ...
};

std::vector<Prim> makePrims() {
    std::vector<Prim> prims;
    auto add = [&](PrimKind kind, std::initializer_list<double> values) {
        Prim prim{kind};
        std::copy(values.begin(), values.end(), prim.p.begin());
        for (std::size_t i = 0; i < prim.p.size(); ++i)
            prim.f[i] = float(prim.p[i]);
        prims.push_back(prim);
    };
    for (int k = 0; k < 9; ++k) {
        const double zc = -0.8 + 0.2 * k;
        add(PrimKind::Sph, {0.0, -0.35, zc, 0.075});
        add(PrimKind::Sph, {0.0, -0.47, zc, 0.04});
    }
    for (int j = 0; j < 6; ++j)
        add(PrimKind::TorZ, {0.0, -0.05, -0.1 + 0.12 * j, 0.5, 0.03});
    add(PrimKind::Shell, {0.0, 0.0, 0.62, 0.28, 0.0175});
    add(PrimKind::TorY, {0.0, 0.0, -0.72, 0.35, 0.06});
    for (int s : {-1, 1}) {
        add(PrimKind::Sph, {s * 0.35, 0.0, -0.83, 0.1});
        add(PrimKind::CapZ, {s * 0.38, 0.0, -1.1, -0.85, 0.05});
    }
    add(PrimKind::Gyr, {0.25, 0.1, 0.2, 0.42, 2 * kPi / 0.12, 0.4});
    return prims;
}

struct Box {
    double x0, x1, y0, y1, z0, z1;
};

Box boundingBox(const Prim& prim) {
    const auto& p = prim.p;
    const double m = kMargin;
    switch (prim.kind) {
    case PrimKind::Sph:
    case PrimKind::Gyr:
        return {p[0] - p[3] - m, p[0] + p[3] + m, p[1] - p[3] - m,
                p[1] + p[3] + m, p[2] - p[3] - m, p[2] + p[3] + m};
    case PrimKind::TorZ: {
        const double e = p[3] + p[4] + m;
        return {p[0] - e, p[0] + e, p[1] - e, p[1] + e, p[2] - p[4] - m, p[2] + p[4] + m};
    }
    case PrimKind::TorY: {
        const double e = p[3] + p[4] + m;
        return {p[0] - e, p[0] + e, p[1] - p[4] - m, p[1] + p[4] + m, p[2] - e, p[2] + e};
    }
    case PrimKind::Shell: {
        const double e = p[3] + p[4] + m;
        return {p[0] - e, p[0] + e, p[1] - e, p[1] + e, p[2] - e, p[2] + e};
    }
    case PrimKind::CapZ:
        return {p[0] - p[4] - m, p[0] + p[4] + m, p[1] - p[4] - m,
                p[1] + p[4] + m, p[2] - p[4] - m, p[3] + p[4] + m};
    }
    return {};
}

// phantom.py's _idx_range: i = (c + 1)(n - 1) / 2, evaluated left to right in double.
void indexRange(int n, double lo, double hi, int& i0, int& i1) {
    i0 = std::max(0, int(std::floor((lo + 1) * (n - 1) / 2)));
    i1 = std::min(n, int(std::ceil((hi + 1) * (n - 1) / 2)) + 1);
}

// np.linspace(-1, 1, n) in float64, then cast to float32.
std::vector<float> axisCoordinates(int n) {
    std::vector<float> c(static_cast<std::size_t>(n));
    if (n == 1) {
        c[0] = -1.0f;
        return c;
    }
    const double step = 2.0 / double(n - 1);
    for (int i = 0; i < n; ++i)
        c[std::size_t(i)] = float(double(i) * step + -1.0);
    c[std::size_t(n - 1)] = 1.0f;
    return c;
}

inline float sigmoid(float t) {
    return 1.0f / (1.0f + std::exp(-t));
}
inline float sq(float v) {
    return v * v;
}

inline float signedDistance(const Prim& prim, float X, float Y, float Z) {
    const auto& p = prim.f;
    switch (prim.kind) {
    case PrimKind::Sph:
        return std::sqrt(sq(X - p[0]) + sq(Y - p[1]) + sq(Z - p[2])) - p[3];
    case PrimKind::TorZ: {
        const float q = std::sqrt(sq(X - p[0]) + sq(Y - p[1])) - p[3];
        return std::sqrt(q * q + sq(Z - p[2])) - p[4];
    }
    case PrimKind::TorY: {
        const float q = std::sqrt(sq(X - p[0]) + sq(Z - p[2])) - p[3];
        return std::sqrt(q * q + sq(Y - p[1])) - p[4];
    }
    case PrimKind::Shell:
        return std::abs(std::sqrt(sq(X - p[0]) + sq(Y - p[1]) + sq(Z - p[2])) - p[3]) - p[4];
    case PrimKind::CapZ: {
        const float zz = std::clamp(Z, p[2], p[3]);
        return std::sqrt(sq(X - p[0]) + sq(Y - p[1]) + sq(Z - zz)) - p[4];
    }
    case PrimKind::Gyr: {
        const float k = p[4];
        const float g = std::sin(k * X) * std::cos(k * Y) + std::sin(k * Y) * std::cos(k * Z) +
                        std::sin(k * Z) * std::cos(k * X);
        const float sdg = (std::abs(g) - p[5]) / float(1.3 * double(k));
        const float sds = std::sqrt(sq(X - p[0]) + sq(Y - p[1]) + sq(Z - p[2])) - p[3];
        return std::max(sdg, sds);
    }
    }
    return 0.0f;
}

// phantom.py's _noise: a 32-bit integer hash of the global voxel index, in [-16, 16).
inline float hashNoise(std::uint64_t index) {
    std::uint32_t i = std::uint32_t(index);
    i ^= i >> 16;
    i *= 0x7feb352du;
    i ^= i >> 15;
    i *= 0x846ca68bu;
    i ^= i >> 16;
    return float(i >> 27) - 16.0f;
}

} // namespace

PhantomKind parsePhantomKind(std::string_view name) {
    if (name == "ct")
        return PhantomKind::Ct;
    if (name == "sphere")
        return PhantomKind::Sphere;
    throw core::Error("phantom kind '" + std::string(name) + "'", "expected ct or sphere");
}

std::string_view phantomKindName(PhantomKind kind) {
    return kind == PhantomKind::Ct ? "ct" : "sphere";
}

volume::Volume makePhantom(glm::ivec3 dims, PhantomKind kind, unsigned threads,
                           const core::ImportLimits& limits, core::Progress* progress) {
    if (dims.x < 1 || dims.y < 1 || dims.z < 1)
        throw core::Error("phantom size", "every dimension must be at least 1");
    volume::checkVolumeAllocation(dims, volume::VoxelType::Int16, limits, "phantom", "the phantom");
    const int nx = dims.x, ny = dims.y, nz = dims.z;
    const glm::dvec3 spacing(1.0);
    const glm::dvec3 origin = -0.5 * glm::dvec3(dims - 1) * spacing;
    volume::Volume out(dims, volume::VoxelType::Int16,
                       volume::VolumeGeometry::regular(origin, spacing));
    out.setDescription(std::string("phantom ") + std::string(phantomKindName(kind)));

    const std::vector<float> cx = axisCoordinates(nx), cy = axisCoordinates(ny),
                             cz = axisCoordinates(nz);
    std::vector<Prim> prims;
    if (kind == PhantomKind::Ct) {
        for (Prim prim : makePrims()) {
            const Box b = boundingBox(prim);
            indexRange(nx, b.x0, b.x1, prim.i0, prim.i1);
            indexRange(ny, b.y0, b.y1, prim.j0, prim.j1);
            indexRange(nz, b.z0, b.z1, prim.k0, prim.k1);
            if (prim.i0 < prim.i1 && prim.j0 < prim.j1 && prim.k0 < prim.k1)
                prims.push_back(prim);
        }
    }
    std::int16_t* voxels = out.dataAs<std::int16_t>();
    const std::size_t sliceSize = std::size_t(nx) * std::size_t(ny);
    if (progress)
        progress->setTotal(std::size_t(nz), "Generating the phantom");

    // A slice is the grain of progress and cancel: 1 M voxels at 1024 x 1024, a few ms per core.
    // parallelFor abandons the slices not yet started once a body throws Cancelled.
    core::parallelFor(
        std::size_t(nz),
        [&](std::size_t zi) {
            if (progress)
                progress->throwIfCancelled();
            const int z = int(zi);
            const float Z = cz[zi];
            std::vector<float> row(static_cast<std::size_t>(nx));
            std::vector<const Prim*> active;
            for (int y = 0; y < ny; ++y) {
                const float Y = cy[std::size_t(y)];
                if (kind == PhantomKind::Ct) {
                    for (int x = 0; x < nx; ++x) {
                        const float X = cx[std::size_t(x)];
                        const float re = std::sqrt(sq(X / 0.85f) + sq(Y / 0.65f) + sq(Z / 0.95f));
                        row[std::size_t(x)] = -1000.0f + 1040.0f * sigmoid((1.0f - re) / 0.02f);
                    }
                } else {
                    for (int x = 0; x < nx; ++x) {
                        const float X = cx[std::size_t(x)];
                        const float r = std::sqrt(X * X + Y * Y + Z * Z);
                        row[std::size_t(x)] = -1000.0f + 2000.0f * sigmoid((0.6f - r) / 0.01f);
                    }
                }
                // Primitives in phantom.py's order: float addition is not associative.
                for (const Prim& prim : prims) {
                    if (z < prim.k0 || z >= prim.k1 || y < prim.j0 || y >= prim.j1)
                        continue;
                    for (int x = prim.i0; x < prim.i1; ++x) {
                        const float sd = signedDistance(prim, cx[std::size_t(x)], Y, Z);
                        row[std::size_t(x)] += float(kBone) * sigmoid(-sd / float(kW));
                    }
                }
                const std::size_t base =
                    std::size_t(z) * sliceSize + std::size_t(y) * std::size_t(nx);
                std::int16_t* dst = voxels + base;
                for (int x = 0; x < nx; ++x) {
                    const float v = row[std::size_t(x)] + hashNoise(base + std::size_t(x));
                    // np.rint rounds half to even, as nearbyint does in the default rounding mode.
                    const float r = std::nearbyint(v);
                    dst[x] = std::int16_t(std::clamp(r, -1024.0f, 3071.0f));
                }
            }
            if (progress)
                progress->step();
        },
        threads);
    return out;
}

PhantomChecksum phantomChecksum(const volume::Volume& volume, double iso) {
    PhantomChecksum total;
    const glm::ivec3 d = volume.dims();
    std::vector<PhantomChecksum> perSlice(std::size_t(std::max(d.z, 0)));
    volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const T* voxels = volume.dataAs<T>();
        const std::size_t sliceSize = std::size_t(d.x) * std::size_t(d.y);
        core::parallelFor(perSlice.size(), [&](std::size_t z) {
            PhantomChecksum c;
            const T* s = voxels + z * sliceSize;
            for (std::size_t i = 0; i < sliceSize; ++i) {
                c.sum += std::int64_t(s[i]);
                c.above += double(s[i]) > iso ? 1 : 0;
            }
            perSlice[z] = c;
        });
    });
    for (const auto& c : perSlice) {
        total.sum += c.sum;
        total.above += c.above;
    }
    return total;
}

} // namespace lw::volume
