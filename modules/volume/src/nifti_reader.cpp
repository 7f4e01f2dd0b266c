// NIfTI-1: .nii, .nii.gz and .hdr/.img pairs in either byte order. NIfTI world space is RAS+;
// Linework works in DICOM LPS, so x and y are negated on the way in.
#include "lw/core/file_util.h"
#include "lw/volume/volume_reader.h"
#include "reader_util.h"

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

namespace lw::volume {
namespace {

using detail::fail;

constexpr std::size_t kHeaderSize = 348;

bool endsWith(const std::string& text, std::string_view suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
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

// Given the .img(.gz) of a pair, the header next to it; otherwise `requested` itself.
std::filesystem::path headerPathFor(const std::filesystem::path& requested) {
    const std::string name = requested.string();
    const bool gz = endsWith(name, ".gz");
    std::string base = gz ? name.substr(0, name.size() - 3) : name;
    if (!endsWith(base, ".img"))
        return requested;
    base.resize(base.size() - 4);
    return std::filesystem::exists(base + ".hdr") ? base + ".hdr" : base + ".hdr.gz";
}

// A file as stored, and its inflated form when it is gzip: only `prefix` bytes of it until
// the header has said how large the rest should be (a .nii.gz bomb stops at the header's size).
struct StoredFile {
    std::vector<std::byte> raw;
    bool gzipped = false;
};

StoredFile readStored(const std::filesystem::path& path) {
    StoredFile file;
    file.raw = core::readFileBytes(path);
    file.gzipped = core::looksGzipped(file.raw.data(), file.raw.size());
    return file;
}

std::vector<std::byte> inflatedPrefix(const std::filesystem::path& path, const StoredFile& file,
                                      std::size_t count) {
    if (!file.gzipped)
        return std::vector<std::byte>(
            file.raw.begin(), file.raw.begin() + std::ptrdiff_t(std::min(count, file.raw.size())));
    return core::gunzipPrefix(file.raw.data(), file.raw.size(), path.string(), count);
}

// The whole file, inflated to at most `expected` bytes (plus inflateBound's margin).
std::vector<std::byte> inflatedWhole(const std::filesystem::path& path, StoredFile& file,
                                     std::size_t expected) {
    if (!file.gzipped)
        return std::move(file.raw);
    return core::gunzip(file.raw.data(), file.raw.size(), path.string(),
                        core::inflateBound(expected));
}

enum class Layout { SingleFile, Pair, Analyze };

// What the 348-byte header says, every field checked.
struct NiftiHeader {
    bool swap = false;
    Layout layout = Layout::SingleFile;
    int rank = 0;
    glm::ivec3 dims{1};
    detail::SourceType sourceType = detail::SourceType::UInt8;
    std::size_t dataBytes = 0; // dims x element size, within the import limits
    double voxOffset = 0.0;
};

// sizeof_hdr says the byte order (348 either way) and rules out NIfTI-2.
bool detectSwap(const std::filesystem::path& path, const std::byte* bytes) {
    std::int32_t sizeofHdr;
    std::memcpy(&sizeofHdr, bytes, 4);
    if (sizeofHdr == std::int32_t(kHeaderSize))
        return false;
    if (__builtin_bswap32(std::uint32_t(sizeofHdr)) == kHeaderSize)
        return true;
    if (__builtin_bswap32(std::uint32_t(sizeofHdr)) == 540 || sizeofHdr == 540)
        fail(path, "NIfTI-2 files are not supported (only NIfTI-1)");
    fail(path, "not a NIfTI-1 file (sizeof_hdr is " + std::to_string(sizeofHdr) + ", not 348)");
}

Layout layoutOf(const std::byte* bytes) {
    const char* magic = reinterpret_cast<const char*>(bytes + 344);
    if (std::memcmp(magic, "n+1\0", 4) == 0)
        return Layout::SingleFile;
    // Analyze 7.5 headers have no magic; they are read as a pair, like NIfTI "ni1".
    return std::memcmp(magic, "ni1\0", 4) == 0 ? Layout::Pair : Layout::Analyze;
}

// dim[0] and dim[1..3]; higher dimensions must be 1 (a single 3D volume).
void readDims(const std::filesystem::path& path, const HeaderView& h, NiftiHeader& header) {
    header.rank = h.i16(40);
    if (header.rank < 1 || header.rank > 7)
        fail(path, "bad dim[0] = " + std::to_string(header.rank) + " (must be 1..7)");
    for (int a = 0; a < 3 && a < header.rank; ++a) {
        const int n = h.i16(std::size_t(42 + 2 * a));
        if (n < 1)
            fail(path, "bad dim[" + std::to_string(a + 1) + "] = " + std::to_string(n));
        header.dims[a] = n;
    }
    for (int a = 3; a < header.rank; ++a) {
        const int n = h.i16(std::size_t(42 + 2 * a));
        if (n > 1)
            fail(path, std::to_string(header.rank) + "D image with dim[" + std::to_string(a + 1) +
                           "] = " + std::to_string(n) + "; only single 3D volumes are read");
    }
}

detail::SourceType sourceTypeOf(const std::filesystem::path& path, int datatype) {
    using detail::SourceType;
    switch (datatype) {
    case 2:
        return SourceType::UInt8;
    case 4:
        return SourceType::Int16;
    case 8:
        return SourceType::Int32;
    case 16:
        return SourceType::Float32;
    case 64:
        return SourceType::Float64;
    case 256:
        return SourceType::Int8;
    case 512:
        return SourceType::UInt16;
    case 768:
        return SourceType::UInt32;
    default:
        fail(path, "unsupported NIfTI datatype " + std::to_string(datatype) +
                       " (complex, RGB and 64-bit integer data are not read)");
    }
}

NiftiHeader parseHeader(const std::filesystem::path& path, const std::vector<std::byte>& bytes,
                        const core::ImportLimits& limits) {
    if (bytes.size() < kHeaderSize)
        fail(path, "truncated NIfTI header: " + std::to_string(bytes.size()) + " of 348 bytes");
    NiftiHeader header;
    header.swap = detectSwap(path, bytes.data());
    header.layout = layoutOf(bytes.data());
    const HeaderView h(bytes.data(), header.swap);
    readDims(path, h, header);
    header.sourceType = sourceTypeOf(path, h.i16(70));
    header.dataBytes =
        detail::checkVolumeSize(path, header.dims, detail::sourceTypeSize(header.sourceType),
                                detail::targetVoxelType(header.sourceType), limits);
    header.voxOffset = h.f32(108);
    return header;
}

// The image data: after vox_offset in a single file, or in the companion .img(.gz) of a pair.
// `storage` keeps the bytes `data` points into.
struct ImageData {
    std::vector<std::byte> storage;
    const std::byte* data = nullptr;
    std::filesystem::path path;
};

ImageData readSingleFileData(const std::filesystem::path& path, StoredFile& file,
                             const NiftiHeader& header) {
    if (!std::isfinite(header.voxOffset) || header.voxOffset < double(kHeaderSize) ||
        header.voxOffset > double(std::numeric_limits<std::uint32_t>::max()))
        fail(path, "bad vox_offset " + std::to_string(header.voxOffset));
    const auto offset = std::size_t(header.voxOffset);
    ImageData image{inflatedWhole(path, file, offset + header.dataBytes), nullptr, path};
    if (offset > image.storage.size())
        fail(path, "bad vox_offset " + std::to_string(header.voxOffset) + " for a file of " +
                       std::to_string(image.storage.size()) + " bytes");
    image.data = image.storage.data() + offset;
    return image;
}

ImageData readPairData(const std::filesystem::path& headerPath, const NiftiHeader& header) {
    const std::filesystem::path imagePath = imagePathFor(headerPath);
    const double offset =
        std::isfinite(header.voxOffset) && header.voxOffset > 0.0 ? header.voxOffset : 0.0;
    if (offset > double(std::numeric_limits<std::uint32_t>::max()))
        fail(imagePath,
             "vox_offset " + std::to_string(header.voxOffset) + " is past the end of the file");
    StoredFile file = readStored(imagePath);
    ImageData image{inflatedWhole(imagePath, file, std::size_t(offset) + header.dataBytes), nullptr,
                    imagePath};
    if (offset > double(image.storage.size()))
        fail(imagePath,
             "vox_offset " + std::to_string(header.voxOffset) + " is past the end of the file");
    image.data = image.storage.data() + std::size_t(offset);
    return image;
}

void checkDataLength(const ImageData& image, const NiftiHeader& header) {
    const std::size_t available =
        image.storage.size() - std::size_t(image.data - image.storage.data());
    if (available < header.dataBytes)
        fail(image.path,
             "truncated image data: " + std::to_string(available) + " bytes, expected " +
                 std::to_string(header.dataBytes) + " for " +
                 detail::describeShape(header.dims, detail::targetVoxelType(header.sourceType)));
}

// sform (srow_x/y/z), when its code is set and its columns usable.
std::optional<VolumeGeometry> sformGeometry(const HeaderView& h) {
    glm::dvec3 columns[3];
    glm::dvec3 offset;
    for (int row = 0; row < 3; ++row) {
        const std::size_t base = std::size_t(280 + 16 * row);
        for (int c = 0; c < 3; ++c)
            columns[c][row] = h.f32(base + std::size_t(4 * c));
        offset[row] = h.f32(base + 12);
    }
    if (!usable(columns[0]) || !usable(columns[1]) || !usable(columns[2]) ||
        !std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(offset.z))
        return std::nullopt;
    const glm::dvec3 toLps(-1.0, -1.0, 1.0);
    const glm::dvec3 s(glm::length(columns[0]), glm::length(columns[1]), glm::length(columns[2]));
    return VolumeGeometry::regular(offset * toLps, s, columns[0] * toLps, columns[1] * toLps,
                                   columns[2] * toLps);
}

// qform: the quaternion (b, c, d), qoffset and qfac (sign of pixdim[0]), as nifti1_io does.
std::optional<VolumeGeometry> qformGeometry(const HeaderView& h, glm::dvec3 spacing,
                                            double pixdim0) {
    double b = h.f32(256), c = h.f32(260), d = h.f32(264);
    const glm::dvec3 offset(h.f32(268), h.f32(272), h.f32(276));
    if (!std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d) || !std::isfinite(offset.x) ||
        !std::isfinite(offset.y) || !std::isfinite(offset.z))
        return std::nullopt;
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
    const double qfac = pixdim0 < 0.0 ? -1.0 : 1.0;
    const glm::dvec3 col0(a * a + b * b - c * c - d * d, 2 * (b * c + a * d), 2 * (b * d - a * c));
    const glm::dvec3 col1(2 * (b * c - a * d), a * a + c * c - b * b - d * d, 2 * (c * d + a * b));
    const glm::dvec3 col2 =
        qfac * glm::dvec3(2 * (b * d + a * c), 2 * (c * d - a * b), a * a + d * d - c * c - b * b);
    const glm::dvec3 toLps(-1.0, -1.0, 1.0);
    return VolumeGeometry::regular(offset * toLps, spacing, col0 * toLps, col1 * toLps,
                                   col2 * toLps);
}

// Geometry, in the order NIfTI prescribes: sform, then qform, then plain pixdim.
VolumeGeometry niftiGeometry(const HeaderView& h, const NiftiHeader& header) {
    std::array<double, 8> pixdim{};
    for (int i = 0; i < 8; ++i)
        pixdim[std::size_t(i)] = h.f32(std::size_t(76 + 4 * i));
    glm::dvec3 spacing(1.0);
    for (int a = 0; a < 3; ++a) {
        const double p = std::abs(pixdim[std::size_t(a + 1)]);
        if (std::isfinite(p) && p > 0.0 && a < header.rank)
            spacing[a] = p;
    }
    const bool analyze = header.layout == Layout::Analyze;
    if (!analyze && h.i16(254) > 0)
        if (auto geometry = sformGeometry(h))
            return *geometry;
    if (!analyze && h.i16(252) > 0)
        if (auto geometry = qformGeometry(h, spacing, pixdim[0]))
            return *geometry;
    return VolumeGeometry::regular(glm::dvec3(0.0), spacing, glm::dvec3(-1, 0, 0),
                                   glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
}

Volume readNiftiUnguarded(const std::filesystem::path& requested,
                          const core::ImportLimits& limits) {
    const std::filesystem::path path = headerPathFor(requested);
    StoredFile file = readStored(path);
    // The header first (from a gzip stream too): it says how large the rest may be.
    std::vector<std::byte> headerBytes = inflatedPrefix(path, file, kHeaderSize);
    const NiftiHeader header = parseHeader(path, headerBytes, limits);
    ImageData image = header.layout == Layout::SingleFile ? readSingleFileData(path, file, header)
                                                          : readPairData(path, header);
    checkDataLength(image, header);
    const std::byte* headerData =
        header.layout == Layout::SingleFile ? image.storage.data() : headerBytes.data();
    const HeaderView h(headerData, header.swap);

    Volume volume =
        detail::makeVolume(header.dims, header.sourceType, image.data,
                           header.swap != !detail::hostIsLittleEndian(), niftiGeometry(h, header));
    const double slope = h.f32(112), intercept = h.f32(116);
    // slope 0 (or NaN) means "no scaling" in NIfTI-1.
    if (std::isfinite(slope) && slope != 0.0)
        volume.setValueMapping({slope, std::isfinite(intercept) ? intercept : 0.0});
    const char* descrip = reinterpret_cast<const char*>(headerData + 148);
    volume.setDescription(std::string(descrip, strnlen(descrip, 80)));
    return volume;
}

} // namespace

Volume readNifti(const std::filesystem::path& path, const core::ImportLimits& limits) {
    return core::atModuleBoundary(path.string(), [&] { return readNiftiUnguarded(path, limits); });
}

} // namespace lw::volume
