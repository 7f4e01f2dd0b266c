// NIfTI-1: .nii, .nii.gz and .hdr/.img pairs in either byte order. NIfTI world space is RAS+;
// Linework works in DICOM LPS, so x and y are negated on the way in.
#include "lw/core/file_util.h"
#include "lw/volume/volume_reader.h"
#include "reader_util.h"

#include <array>
#include <cmath>
#include <cstring>

namespace lw::volume {
namespace {

using detail::fail;

constexpr std::size_t kHeaderSize = 348;

bool endsWith(const std::string& text, std::string_view suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::vector<std::byte> readMaybeGzipped(const std::filesystem::path& path) {
    std::vector<std::byte> bytes = core::readFileBytes(path);
    if (core::looksGzipped(bytes.data(), bytes.size()))
        bytes = core::gunzip(bytes.data(), bytes.size(), path.string());
    return bytes;
}

// Reads header fields at fixed offsets with the file's byte order.
class HeaderView {
public:
    HeaderView(const std::byte* data, bool swap) : m_data(data), m_swap(swap) {}

    template <typename T> T get(std::size_t offset) const {
        std::byte raw[sizeof(T)];
        std::memcpy(raw, m_data + offset, sizeof(T));
        if (m_swap)
            std::reverse(raw, raw + sizeof(T));
        T value;
        std::memcpy(&value, raw, sizeof(T));
        return value;
    }
    std::int16_t i16(std::size_t offset) const { return get<std::int16_t>(offset); }
    std::int32_t i32(std::size_t offset) const { return get<std::int32_t>(offset); }
    double f32(std::size_t offset) const { return double(get<float>(offset)); }

private:
    const std::byte* m_data;
    bool m_swap;
};

// The companion .img(.gz) of a .hdr(.gz).
std::filesystem::path imagePathFor(const std::filesystem::path& headerPath) {
    std::string name = headerPath.string();
    const bool gz = endsWith(name, ".gz");
    if (gz)
        name.resize(name.size() - 3);
    if (endsWith(name, ".hdr"))
        name.resize(name.size() - 4);
    for (const char* suffix : {".img", ".img.gz", ".IMG"}) {
        const std::filesystem::path candidate = name + suffix;
        std::error_code ec;
        if (std::filesystem::exists(candidate, ec))
            return candidate;
    }
    return name + ".img";
}

bool usable(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && glm::length(v) > 0.0;
}

} // namespace

Volume readNifti(const std::filesystem::path& requested) {
    std::filesystem::path path = requested;
    {
        // Given the .img of a pair, read the header next to it.
        std::string name = path.string();
        const bool gz = endsWith(name, ".gz");
        std::string base = gz ? name.substr(0, name.size() - 3) : name;
        if (endsWith(base, ".img")) {
            base.resize(base.size() - 4);
            path = std::filesystem::exists(base + ".hdr") ? base + ".hdr" : base + ".hdr.gz";
        }
    }
    std::vector<std::byte> bytes = readMaybeGzipped(path);
    if (bytes.size() < kHeaderSize)
        fail(path, "truncated NIfTI header: " + std::to_string(bytes.size()) + " of 348 bytes");

    std::int32_t sizeofHdr;
    std::memcpy(&sizeofHdr, bytes.data(), 4);
    bool swap = false;
    if (sizeofHdr != std::int32_t(kHeaderSize)) {
        if (__builtin_bswap32(std::uint32_t(sizeofHdr)) == kHeaderSize)
            swap = true;
        else if (__builtin_bswap32(std::uint32_t(sizeofHdr)) == 540 || sizeofHdr == 540)
            fail(path, "NIfTI-2 files are not supported (only NIfTI-1)");
        else
            fail(path,
                 "not a NIfTI-1 file (sizeof_hdr is " + std::to_string(sizeofHdr) + ", not 348)");
    }
    const HeaderView h(bytes.data(), swap);
    const char* magic = reinterpret_cast<const char*>(bytes.data() + 344);
    const bool singleFile = std::memcmp(magic, "n+1\0", 4) == 0;
    const bool pair = std::memcmp(magic, "ni1\0", 4) == 0;
    // Analyze 7.5 headers have no magic; they are read as a pair, like NIfTI "ni1".
    const bool analyze = !singleFile && !pair;

    const int rank = h.i16(40);
    if (rank < 1 || rank > 7)
        fail(path, "bad dim[0] = " + std::to_string(rank) + " (must be 1..7)");
    glm::ivec3 dims(1);
    for (int a = 0; a < 3 && a < rank; ++a) {
        const int n = h.i16(std::size_t(42 + 2 * a));
        if (n < 1)
            fail(path, "bad dim[" + std::to_string(a + 1) + "] = " + std::to_string(n));
        dims[a] = n;
    }
    for (int a = 3; a < rank; ++a) {
        const int n = h.i16(std::size_t(42 + 2 * a));
        if (n > 1)
            fail(path, std::to_string(rank) + "D image with dim[" + std::to_string(a + 1) +
                           "] = " + std::to_string(n) + "; only single 3D volumes are read");
    }

    using detail::SourceType;
    const int datatype = h.i16(70);
    SourceType sourceType;
    switch (datatype) {
    case 2:
        sourceType = SourceType::UInt8;
        break;
    case 4:
        sourceType = SourceType::Int16;
        break;
    case 8:
        sourceType = SourceType::Int32;
        break;
    case 16:
        sourceType = SourceType::Float32;
        break;
    case 64:
        sourceType = SourceType::Float64;
        break;
    case 256:
        sourceType = SourceType::Int8;
        break;
    case 512:
        sourceType = SourceType::UInt16;
        break;
    case 768:
        sourceType = SourceType::UInt32;
        break;
    default:
        fail(path, "unsupported NIfTI datatype " + std::to_string(datatype) +
                       " (complex, RGB and 64-bit integer data are not read)");
    }
    const std::size_t elementSize = detail::sourceTypeSize(sourceType);
    const auto expected = detail::checkedByteCount(dims, elementSize);
    if (!expected)
        fail(path, "image dimensions are too large");

    const double voxOffset = h.f32(108);
    const std::byte* data = nullptr;
    std::vector<std::byte> imageBytes;
    const std::filesystem::path* dataPath = &path;
    std::filesystem::path imagePath;
    std::size_t available = 0;
    if (singleFile) {
        if (!std::isfinite(voxOffset) || voxOffset < double(kHeaderSize) ||
            voxOffset > double(bytes.size()))
            fail(path, "bad vox_offset " + std::to_string(voxOffset) + " for a file of " +
                           std::to_string(bytes.size()) + " bytes");
        const auto offset = std::size_t(voxOffset);
        data = bytes.data() + offset;
        available = bytes.size() - offset;
    } else {
        imagePath = imagePathFor(path);
        dataPath = &imagePath;
        imageBytes = readMaybeGzipped(imagePath);
        const double offset = std::isfinite(voxOffset) && voxOffset > 0.0 ? voxOffset : 0.0;
        if (offset > double(imageBytes.size()))
            fail(imagePath,
                 "vox_offset " + std::to_string(voxOffset) + " is past the end of the file");
        data = imageBytes.data() + std::size_t(offset);
        available = imageBytes.size() - std::size_t(offset);
    }
    if (available < *expected)
        fail(*dataPath, "truncated image data: " + std::to_string(available) + " bytes, expected " +
                            std::to_string(*expected) + " for " +
                            detail::describeShape(dims, detail::targetVoxelType(sourceType)));

    // Geometry, in the order NIfTI prescribes: sform, then qform, then plain pixdim.
    std::array<double, 8> pixdim{};
    for (int i = 0; i < 8; ++i)
        pixdim[std::size_t(i)] = h.f32(std::size_t(76 + 4 * i));
    glm::dvec3 spacing(1.0);
    for (int a = 0; a < 3; ++a) {
        const double p = std::abs(pixdim[std::size_t(a + 1)]);
        if (std::isfinite(p) && p > 0.0 && a < rank)
            spacing[a] = p;
    }
    const glm::dvec3 toLps(-1.0, -1.0, 1.0);
    VolumeGeometry geometry;
    bool haveGeometry = false;
    const int qformCode = analyze ? 0 : h.i16(252);
    const int sformCode = analyze ? 0 : h.i16(254);
    if (sformCode > 0) {
        glm::dvec3 columns[3];
        glm::dvec3 offset;
        for (int row = 0; row < 3; ++row) {
            const std::size_t base = std::size_t(280 + 16 * row);
            for (int c = 0; c < 3; ++c)
                columns[c][row] = h.f32(base + std::size_t(4 * c));
            offset[row] = h.f32(base + 12);
        }
        if (usable(columns[0]) && usable(columns[1]) && usable(columns[2]) &&
            std::isfinite(offset.x) && std::isfinite(offset.y) && std::isfinite(offset.z)) {
            const glm::dvec3 s(glm::length(columns[0]), glm::length(columns[1]),
                               glm::length(columns[2]));
            geometry = VolumeGeometry::regular(offset * toLps, s, columns[0] * toLps,
                                               columns[1] * toLps, columns[2] * toLps);
            haveGeometry = true;
        }
    }
    if (!haveGeometry && qformCode > 0) {
        double b = h.f32(256), c = h.f32(260), d = h.f32(264);
        const glm::dvec3 offset(h.f32(268), h.f32(272), h.f32(276));
        if (std::isfinite(b) && std::isfinite(c) && std::isfinite(d) && std::isfinite(offset.x) &&
            std::isfinite(offset.y) && std::isfinite(offset.z)) {
            double a = 1.0 - (b * b + c * c + d * d);
            if (a < 1e-7) {
                // Nearly a 180 degree rotation: renormalise (b,c,d), as nifti1_io does.
                const double n = std::sqrt(b * b + c * c + d * d);
                b /= n;
                c /= n;
                d /= n;
                a = 0.0;
            } else {
                a = std::sqrt(a);
            }
            const double qfac = pixdim[0] < 0.0 ? -1.0 : 1.0;
            const glm::dvec3 col0(a * a + b * b - c * c - d * d, 2 * (b * c + a * d),
                                  2 * (b * d - a * c));
            const glm::dvec3 col1(2 * (b * c - a * d), a * a + c * c - b * b - d * d,
                                  2 * (c * d + a * b));
            const glm::dvec3 col2 = qfac * glm::dvec3(2 * (b * d + a * c), 2 * (c * d - a * b),
                                                      a * a + d * d - c * c - b * b);
            geometry = VolumeGeometry::regular(offset * toLps, spacing, col0 * toLps, col1 * toLps,
                                               col2 * toLps);
            haveGeometry = true;
        }
    }
    if (!haveGeometry)
        geometry = VolumeGeometry::regular(glm::dvec3(0.0), spacing, glm::dvec3(-1, 0, 0),
                                           glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));

    Volume volume = detail::makeVolume(dims, sourceType, data,
                                       swap != !detail::hostIsLittleEndian(), std::move(geometry));
    const double slope = h.f32(112), intercept = h.f32(116);
    // slope 0 (or NaN) means "no scaling" in NIfTI-1.
    if (std::isfinite(slope) && slope != 0.0)
        volume.setValueMapping({slope, std::isfinite(intercept) ? intercept : 0.0});
    {
        const char* descrip = reinterpret_cast<const char*>(bytes.data() + 148);
        volume.setDescription(std::string(descrip, strnlen(descrip, 80)));
    }
    return volume;
}

} // namespace lw::volume
