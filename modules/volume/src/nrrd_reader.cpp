// NRRD (Teem's "nearly raw raster data"): attached and detached headers, raw and gzip data,
// single, listed and printf-style data files.
#include "lw/core/file_util.h"
#include "lw/core/limits.h"
#include "lw/volume/volume_reader.h"
#include "reader_util.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>

namespace lw::volume {
namespace {

using detail::fail;

struct NrrdHeader {
    std::map<std::string, std::string> fields; // lower-case field name -> value
    std::map<std::string, int> fieldLines;     // for messages
    std::vector<std::string> listedFiles;      // lines after "data file: LIST"
    std::size_t dataOffset = 0;                // attached data start
    std::map<std::string, std::string> keyValues;

    const std::string* find(std::initializer_list<const char*> names) const {
        for (const char* name : names)
            if (auto it = fields.find(name); it != fields.end())
                return &it->second;
        return nullptr;
    }
};

NrrdHeader parseHeader(const std::filesystem::path& path, const std::vector<std::byte>& bytes) {
    NrrdHeader header;
    const char* text = reinterpret_cast<const char*>(bytes.data());
    const std::size_t size = bytes.size();
    std::size_t pos = 0;
    int lineNumber = 0;
    bool inList = false;
    while (pos < size) {
        const void* newline = std::memchr(text + pos, '\n', size - pos);
        const std::size_t end =
            newline ? std::size_t(static_cast<const char*>(newline) - text) : size;
        std::string_view line(text + pos, end - pos);
        pos = newline ? end + 1 : size;
        ++lineNumber;
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        if (lineNumber == 1) {
            if (line.size() < 8 || line.substr(0, 7) != "NRRD000")
                fail(path, "not a NRRD file (the first line must be NRRD000x)");
            continue;
        }
        if (line.empty())
            break; // the blank line ends the header; attached data follows
        if (line.front() == '#')
            continue;
        if (inList) {
            header.listedFiles.emplace_back(detail::trim(line));
            continue;
        }
        if (const auto kv = line.find(":="); kv != std::string_view::npos) {
            header.keyValues[std::string(line.substr(0, kv))] = std::string(line.substr(kv + 2));
            continue;
        }
        const auto colon = line.find(": ");
        if (colon == std::string_view::npos)
            fail(path, "bad header line " + std::to_string(lineNumber) + ": '" +
                           std::string(line.substr(0, 80)) + "' is not 'field: value'");
        std::string name = detail::toLower(detail::trim(line.substr(0, colon)));
        const std::string value(detail::trim(line.substr(colon + 2)));
        // Old (NRRD0001..3) spellings without the space.
        if (name == "datafile")
            name = "data file";
        else if (name == "lineskip")
            name = "line skip";
        else if (name == "byteskip")
            name = "byte skip";
        else if (name == "centerings")
            name = "centers";
        header.fields[name] = value;
        header.fieldLines[name] = lineNumber;
        if (name == "data file") {
            const auto parts = detail::splitWhitespace(value);
            inList = !parts.empty() && parts[0] == "LIST";
        }
    }
    header.dataOffset = pos;
    return header;
}

const std::string& required(const std::filesystem::path& path, const NrrdHeader& header,
                            const char* name) {
    const std::string* value = header.find({name});
    if (!value)
        fail(path, std::string("header has no '") + name + ":' field");
    return *value;
}

std::string lineRef(const NrrdHeader& header, const char* name) {
    auto it = header.fieldLines.find(name);
    return it == header.fieldLines.end() ? std::string()
                                         : " (line " + std::to_string(it->second) + ")";
}

detail::SourceType parseType(const std::filesystem::path& path, const NrrdHeader& header) {
    using detail::SourceType;
    const std::string type = detail::toLower(required(path, header, "type"));
    static const std::map<std::string, SourceType> types = {
        {"uchar", SourceType::UInt8},
        {"unsigned char", SourceType::UInt8},
        {"uint8", SourceType::UInt8},
        {"uint8_t", SourceType::UInt8},
        {"signed char", SourceType::Int8},
        {"char", SourceType::Int8},
        {"int8", SourceType::Int8},
        {"int8_t", SourceType::Int8},
        {"short", SourceType::Int16},
        {"short int", SourceType::Int16},
        {"signed short", SourceType::Int16},
        {"signed short int", SourceType::Int16},
        {"int16", SourceType::Int16},
        {"int16_t", SourceType::Int16},
        {"ushort", SourceType::UInt16},
        {"unsigned short", SourceType::UInt16},
        {"unsigned short int", SourceType::UInt16},
        {"uint16", SourceType::UInt16},
        {"uint16_t", SourceType::UInt16},
        {"int", SourceType::Int32},
        {"signed int", SourceType::Int32},
        {"int32", SourceType::Int32},
        {"int32_t", SourceType::Int32},
        {"uint", SourceType::UInt32},
        {"unsigned int", SourceType::UInt32},
        {"uint32", SourceType::UInt32},
        {"uint32_t", SourceType::UInt32},
        {"float", SourceType::Float32},
        {"double", SourceType::Float64},
    };
    const auto it = types.find(type);
    if (it == types.end())
        fail(path, "unsupported NRRD type '" + type + "'" + lineRef(header, "type") +
                       "; expected uchar, short, ushort, float (or int8, int, uint, double)");
    return it->second;
}

// "(1,0,0) (0,1,0) none" -> one entry per axis, nullopt for "none".
std::vector<std::optional<glm::dvec3>> parseVectors(const std::filesystem::path& path,
                                                    const NrrdHeader& header, const char* field) {
    const std::string& text = *header.find({field});
    std::vector<std::optional<glm::dvec3>> vectors;
    std::size_t i = 0;
    const auto bad = [&](const std::string& why) {
        fail(path, std::string("bad '") + field + "'" + lineRef(header, field) + ": " + why);
    };
    while (i < text.size()) {
        if (text[i] == ' ' || text[i] == '\t') {
            ++i;
            continue;
        }
        if (text.compare(i, 4, "none") == 0) {
            vectors.emplace_back(std::nullopt);
            i += 4;
            continue;
        }
        if (text[i] != '(')
            bad("expected '(' or 'none'");
        const auto close = text.find(')', i);
        if (close == std::string::npos)
            bad("missing ')'");
        std::string_view inner(text.data() + i + 1, close - i - 1);
        std::vector<double> components;
        std::size_t start = 0;
        while (start <= inner.size()) {
            const auto comma = inner.find(',', start);
            const auto piece = inner.substr(
                start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
            const auto value = detail::parseDouble(piece);
            if (!value || !std::isfinite(*value))
                bad("'" + std::string(piece) + "' is not a number");
            components.push_back(*value);
            if (comma == std::string_view::npos)
                break;
            start = comma + 1;
        }
        if (components.size() != 3)
            bad("vectors must have 3 components (3D space)");
        vectors.emplace_back(glm::dvec3(components[0], components[1], components[2]));
        i = close + 1;
    }
    return vectors;
}

// Expands "quarter.%d" with one integer (the only conversion NRRD allows).
std::string formatDataFileName(const std::filesystem::path& path, const std::string& pattern,
                               long long number) {
    const auto percent = pattern.find('%');
    if (percent == std::string::npos)
        fail(path, "data file pattern '" + pattern + "' has no %d");
    std::size_t i = percent + 1;
    bool zeroPad = false;
    if (i < pattern.size() && pattern[i] == '0') {
        zeroPad = true;
        ++i;
    }
    int width = 0;
    while (i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i])) &&
           width < 100)
        width = width * 10 + (pattern[i++] - '0');
    if (i >= pattern.size() || (pattern[i] != 'd' && pattern[i] != 'i' && pattern[i] != 'u'))
        fail(path, "data file pattern '" + pattern + "' must use %d, %0Nd or %Nd");
    if (pattern.find('%', i + 1) != std::string::npos)
        fail(path, "data file pattern '" + pattern + "' has more than one conversion");
    const std::string digits = std::to_string(number < 0 ? -number : number);
    const std::size_t used = digits.size() + (number < 0 ? 1 : 0);
    const std::size_t pad = used < std::size_t(width) ? std::size_t(width) - used : 0;
    std::string formatted;
    if (!zeroPad)
        formatted.append(pad, ' ');
    if (number < 0)
        formatted.push_back('-');
    if (zeroPad)
        formatted.append(pad, '0');
    formatted.append(digits);
    std::string name = pattern.substr(0, percent);
    name.append(formatted);
    name.append(pattern, i + 1, std::string::npos);
    return name;
}

struct DataFiles {
    std::vector<std::filesystem::path> paths; // empty: attached data
    int subdim = 0;                           // dimensions held by each file
};

DataFiles resolveDataFiles(const std::filesystem::path& path, const NrrdHeader& header,
                           int dimension) {
    DataFiles files;
    files.subdim = dimension;
    const std::string* value = header.find({"data file"});
    if (!value)
        return files;
    const std::filesystem::path folder = path.parent_path();
    const auto resolve = [&](const std::string& name) {
        const std::filesystem::path p(name);
        return p.is_absolute() ? p : folder / p;
    };
    const auto parts = detail::splitWhitespace(*value);
    const auto parseSubdim = [&](std::size_t index) {
        if (index >= parts.size())
            return dimension - 1;
        const auto n = detail::parseInteger(parts[index]);
        if (!n || *n < 1 || *n > dimension)
            fail(path, "bad data file subdimension '" + parts[index] + "'" +
                           lineRef(header, "data file"));
        return int(*n);
    };
    if (parts.empty())
        fail(path, "empty 'data file:'" + lineRef(header, "data file"));
    if (parts[0] == "LIST") {
        files.subdim = parseSubdim(1);
        if (header.listedFiles.empty())
            fail(path, "'data file: LIST' is followed by no file names");
        for (const auto& name : header.listedFiles)
            files.paths.push_back(resolve(name));
        return files;
    }
    if (parts.size() >= 4 && parts[0].find('%') != std::string::npos) {
        const auto first = detail::parseInteger(parts[1]);
        const auto last = detail::parseInteger(parts[2]);
        const auto step = detail::parseInteger(parts[3]);
        constexpr long long kLimit = 1000000000000LL; // keeps the arithmetic below exact
        if (!first || !last || !step || *step == 0 || std::llabs(*first) > kLimit ||
            std::llabs(*last) > kLimit || std::llabs(*step) > kLimit)
            fail(path, "bad data file pattern '" + *value + "'" + lineRef(header, "data file") +
                           "; expected '<format> <min> <max> <step> [<subdim>]'");
        if ((*last - *first) / *step < 0)
            fail(path, "data file pattern '" + *value + "' never reaches its max");
        files.subdim = parseSubdim(4);
        const long long count = (*last - *first) / *step + 1;
        if (count > 1000000)
            fail(path, "data file pattern names too many files (" + std::to_string(count) + ")");
        for (long long i = 0, n = *first; i < count; ++i, n += *step)
            files.paths.push_back(resolve(formatDataFileName(path, parts[0], n)));
        return files;
    }
    // A single file; its name may contain spaces, so take the whole value.
    files.paths.push_back(resolve(*value));
    return files;
}

// Finds `expected` bytes of element data in one file's bytes (after the header for attached
// data): line skip, decompression, byte skip, size check. Points into `bytes` or `inflated`.
// gzip data may inflate only to what the header declares (byte skip + data, plus a margin).
const std::byte* extractData(const std::filesystem::path& dataPath,
                             const std::vector<std::byte>& bytes, std::size_t start,
                             long long lineSkip, long long byteSkip, bool gzip,
                             std::size_t expected, std::vector<std::byte>& inflated) {
    std::size_t pos = start;
    for (long long line = 0; line < lineSkip; ++line) {
        const void* newline = pos < bytes.size()
                                  ? std::memchr(bytes.data() + pos, '\n', bytes.size() - pos)
                                  : nullptr;
        if (!newline)
            fail(dataPath, "file ends before the " + std::to_string(lineSkip) + " lines to skip");
        pos = std::size_t(static_cast<const std::byte*>(newline) - bytes.data()) + 1;
    }
    const std::byte* data = bytes.data() + std::min(pos, bytes.size());
    std::size_t size = bytes.size() - std::min(pos, bytes.size());
    if (gzip) {
        const std::size_t skip = std::size_t(std::max(byteSkip, 0LL));
        const std::size_t declared = expected > std::numeric_limits<std::size_t>::max() - skip
                                         ? std::numeric_limits<std::size_t>::max()
                                         : expected + skip;
        inflated = core::gunzip(data, size, dataPath.string(), core::inflateBound(declared));
        data = inflated.data();
        size = inflated.size();
    }
    if (byteSkip == -1) {
        // -1: the data sits at the end of the file, after a header of unknown length.
        if (size < expected)
            fail(dataPath, "truncated data: " + std::to_string(size) + " bytes, expected " +
                               std::to_string(expected));
        return data + (size - expected);
    }
    if (std::size_t(byteSkip) > size)
        fail(dataPath, "file is shorter than the byte skip of " + std::to_string(byteSkip));
    data += byteSkip;
    size -= std::size_t(byteSkip);
    if (size < expected)
        fail(dataPath, "truncated data: " + std::to_string(size) + " bytes, expected " +
                           std::to_string(expected));
    return data;
}

// How the element data is laid out, from the header: each field checked by its own function.
struct DataLayout {
    int dimension = 3;
    glm::ivec3 dims{1};
    detail::SourceType sourceType = detail::SourceType::UInt8;
    std::size_t totalBytes = 0; // within the import limits
    bool gzip = false;
    bool bigEndian = false;
    long long lineSkip = 0;
    long long byteSkip = 0;
};

int parseDimension(const std::filesystem::path& path, const NrrdHeader& header) {
    const auto dimension = detail::parseInteger(required(path, header, "dimension"));
    if (!dimension || *dimension < 1 || *dimension > 3)
        fail(path, "unsupported dimension '" + required(path, header, "dimension") + "'" +
                       lineRef(header, "dimension") +
                       "; only 1 to 3 dimensional scalar volumes are read");
    return int(*dimension);
}

glm::ivec3 parseSizes(const std::filesystem::path& path, const NrrdHeader& header, int dim) {
    const auto sizeParts = detail::splitWhitespace(required(path, header, "sizes"));
    if (sizeParts.size() != std::size_t(dim))
        fail(path, "'sizes' has " + std::to_string(sizeParts.size()) + " entries for dimension " +
                       std::to_string(dim) + lineRef(header, "sizes"));
    glm::ivec3 dims(1);
    for (int a = 0; a < dim; ++a) {
        const auto n = detail::parseInteger(sizeParts[std::size_t(a)]);
        if (!n || *n < 1 || *n > std::numeric_limits<int>::max())
            fail(path, "bad size '" + sizeParts[std::size_t(a)] + "'" + lineRef(header, "sizes"));
        dims[a] = int(*n);
    }
    return dims;
}

bool parseGzipEncoding(const std::filesystem::path& path, const NrrdHeader& header) {
    const std::string encoding = detail::toLower(required(path, header, "encoding"));
    if (encoding == "gzip" || encoding == "gz")
        return true;
    if (encoding != "raw")
        fail(path, "unsupported NRRD encoding '" + encoding + "'" + lineRef(header, "encoding") +
                       "; only raw and gzip are read");
    return false;
}

bool parseBigEndian(const std::filesystem::path& path, const NrrdHeader& header,
                    std::size_t elementSize) {
    if (const std::string* endian = header.find({"endian"})) {
        const std::string e = detail::toLower(*endian);
        if (e != "big" && e != "little")
            fail(path, "bad endian '" + *endian + "'" + lineRef(header, "endian"));
        return e == "big";
    }
    if (elementSize > 1)
        fail(path, "header has no 'endian:' field, needed for " + std::to_string(elementSize * 8) +
                       "-bit data");
    return false;
}

void parseSkips(const std::filesystem::path& path, const NrrdHeader& header, DataLayout& layout) {
    if (const std::string* v = header.find({"line skip"})) {
        const auto n = detail::parseInteger(*v);
        if (!n || *n < 0)
            fail(path, "bad line skip '" + *v + "'");
        layout.lineSkip = *n;
    }
    if (const std::string* v = header.find({"byte skip"})) {
        const auto n = detail::parseInteger(*v);
        if (!n || *n < -1)
            fail(path, "bad byte skip '" + *v + "'");
        if (*n == -1 && layout.gzip)
            fail(path, "byte skip -1 is only allowed with raw encoding");
        layout.byteSkip = *n;
    }
}

DataLayout parseLayout(const std::filesystem::path& path, const NrrdHeader& header,
                       const core::ImportLimits& limits) {
    DataLayout layout;
    layout.dimension = parseDimension(path, header);
    layout.dims = parseSizes(path, header, layout.dimension);
    layout.sourceType = parseType(path, header);
    const std::size_t elementSize = detail::sourceTypeSize(layout.sourceType);
    layout.totalBytes = detail::checkVolumeSize(path, layout.dims, elementSize,
                                                detail::targetVoxelType(layout.sourceType), limits);
    layout.gzip = parseGzipEncoding(path, header);
    layout.bigEndian = parseBigEndian(path, header, elementSize);
    parseSkips(path, header, layout);
    return layout;
}

// Geometry: space directions win over spacings; RAS-like spaces are flipped to LPS.
VolumeGeometry parseGeometry(const std::filesystem::path& path, const NrrdHeader& header, int dim) {
    glm::dvec3 spacing(1.0), origin(0.0);
    std::array<glm::dvec3, 3> axes = {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0),
                                      glm::dvec3(0, 0, 1)};
    if (header.find({"space directions"})) {
        const auto vectors = parseVectors(path, header, "space directions");
        if (vectors.size() != std::size_t(dim))
            fail(path, "'space directions' has " + std::to_string(vectors.size()) +
                           " entries for dimension " + std::to_string(dim));
        for (int a = 0; a < dim; ++a) {
            if (!vectors[std::size_t(a)])
                fail(path,
                     "'space directions' is 'none' for a spatial axis; vector data is not read");
            const double length = glm::length(*vectors[std::size_t(a)]);
            if (!(length > 0.0))
                fail(path,
                     "'space directions' has a zero vector" + lineRef(header, "space directions"));
            spacing[a] = length;
            axes[std::size_t(a)] = *vectors[std::size_t(a)] / length;
        }
        if (dim == 2)
            axes[2] = glm::normalize(glm::cross(axes[0], axes[1]));
    } else if (const std::string* v = header.find({"spacings"})) {
        const auto parts = detail::splitWhitespace(*v);
        if (parts.size() != std::size_t(dim))
            fail(path, "'spacings' has " + std::to_string(parts.size()) +
                           " entries for dimension " + std::to_string(dim));
        for (int a = 0; a < dim; ++a) {
            const auto s = detail::parseDouble(parts[std::size_t(a)]);
            if (!s)
                fail(path,
                     "bad spacing '" + parts[std::size_t(a)] + "'" + lineRef(header, "spacings"));
            // NaN means "unknown" in NRRD; zero would collapse the grid.
            if (std::isfinite(*s) && *s != 0.0)
                spacing[a] = std::abs(*s);
        }
    }
    if (header.find({"space origin"})) {
        const auto vectors = parseVectors(path, header, "space origin");
        if (vectors.size() != 1 || !vectors[0])
            fail(path, "'space origin' must be one vector" + lineRef(header, "space origin"));
        origin = *vectors[0];
    }
    if (const std::string* space = header.find({"space"})) {
        const std::string s = detail::toLower(*space);
        glm::dvec3 flip(1.0);
        if (s == "right-anterior-superior" || s == "ras")
            flip = {-1, -1, 1};
        else if (s == "left-anterior-superior" || s == "las")
            flip = {1, -1, 1};
        for (auto& axis : axes)
            axis *= flip;
        origin *= flip;
    }
    return VolumeGeometry::regular(origin, spacing, axes[0], axes[1], axes[2]);
}

// One source (attached data or one detached file): the volume is built straight from the file
// buffer, no intermediate copy.
Volume readSingleSource(const std::filesystem::path& path, const NrrdHeader& header,
                        std::vector<std::byte>& bytes, const DataFiles& files,
                        const DataLayout& layout, VolumeGeometry geometry) {
    if (files.paths.empty() && path.extension() == ".nhdr")
        fail(path, "detached header (.nhdr) without a 'data file:' field");
    std::vector<std::byte> dataBytes;
    const std::filesystem::path& dataPath = files.paths.empty() ? path : files.paths[0];
    if (!files.paths.empty()) {
        bytes.clear();
        bytes.shrink_to_fit();
        dataBytes = core::readFileBytes(dataPath);
    }
    std::vector<std::byte> inflated;
    const std::byte* data =
        extractData(dataPath, files.paths.empty() ? bytes : dataBytes,
                    files.paths.empty() ? header.dataOffset : 0, layout.lineSkip, layout.byteSkip,
                    layout.gzip, layout.totalBytes, inflated);
    return detail::makeVolume(layout.dims, layout.sourceType, data, layout.bigEndian,
                              std::move(geometry));
}

// Each file holds the first `subdim` axes; the files enumerate the rest.
Volume readFileList(const std::filesystem::path& path, const NrrdHeader& header,
                    const DataFiles& files, const DataLayout& layout, VolumeGeometry geometry) {
    std::size_t filesNeeded = 1;
    for (int a = files.subdim; a < layout.dimension; ++a)
        filesNeeded *= std::size_t(layout.dims[a]);
    if (files.paths.size() != filesNeeded)
        fail(path, "header names " + std::to_string(files.paths.size()) + " data files, expected " +
                       std::to_string(filesNeeded) + lineRef(header, "data file"));
    const std::size_t perFile = layout.totalBytes / filesNeeded;
    std::vector<std::byte> data;
    data.reserve(layout.totalBytes); // within the import limits (parseLayout)
    std::vector<std::byte> inflated;
    for (const auto& file : files.paths) {
        const std::vector<std::byte> fileBytes = core::readFileBytes(file);
        const std::byte* chunk = extractData(file, fileBytes, 0, layout.lineSkip, layout.byteSkip,
                                             layout.gzip, perFile, inflated);
        data.insert(data.end(), chunk, chunk + perFile);
    }
    return detail::makeVolume(layout.dims, layout.sourceType, data.data(), layout.bigEndian,
                              std::move(geometry));
}

// Description and our own rescale key/values (see writeNrrd): NRRD has no standard rescale field.
void applyMetadata(const NrrdHeader& header, Volume& volume) {
    if (const std::string* content = header.find({"content"}))
        volume.setDescription(*content);
    const auto slope = header.keyValues.find("linework_rescale_slope");
    const auto intercept = header.keyValues.find("linework_rescale_intercept");
    if (slope != header.keyValues.end() && intercept != header.keyValues.end()) {
        const auto s = detail::parseDouble(slope->second),
                   i = detail::parseDouble(intercept->second);
        if (s && i && std::isfinite(*s) && std::isfinite(*i) && *s != 0.0)
            volume.setValueMapping({*s, *i});
    }
}

Volume readNrrdUnguarded(const std::filesystem::path& path, const core::ImportLimits& limits) {
    std::vector<std::byte> bytes = core::readFileBytes(path);
    const NrrdHeader header = parseHeader(path, bytes);
    const DataLayout layout = parseLayout(path, header, limits);
    VolumeGeometry geometry = parseGeometry(path, header, layout.dimension);
    const DataFiles files = resolveDataFiles(path, header, layout.dimension);
    Volume volume = files.paths.size() <= 1
                        ? readSingleSource(path, header, bytes, files, layout, std::move(geometry))
                        : readFileList(path, header, files, layout, std::move(geometry));
    applyMetadata(header, volume);
    return volume;
}

} // namespace

Volume readNrrd(const std::filesystem::path& path, const core::ImportLimits& limits) {
    return core::atModuleBoundary(path.string(), [&] { return readNrrdUnguarded(path, limits); });
}

namespace {

std::string formatNumber(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string formatVector(glm::dvec3 v) {
    std::string text = "(";
    text.append(formatNumber(v.x)).append(",").append(formatNumber(v.y)).append(",");
    text.append(formatNumber(v.z)).append(")");
    return text;
}

} // namespace

void writeNrrd(const std::filesystem::path& path, const Volume& volume) {
    if (volume.isEmpty())
        fail(path, "cannot write an empty volume");
    const char* type = "uchar";
    switch (volume.voxelType()) {
    case VoxelType::UInt8:
        type = "uchar";
        break;
    case VoxelType::Int16:
        type = "short";
        break;
    case VoxelType::UInt16:
        type = "ushort";
        break;
    case VoxelType::Float32:
        type = "float";
        break;
    }
    const VolumeGeometry& g = volume.geometry();
    const glm::ivec3 dims = volume.dims();
    std::string header = "NRRD0004\n# Written by Linework\n";
    header += std::string("type: ") + type + "\n";
    header += "dimension: 3\n";
    header += "space: left-posterior-superior\n";
    header += "sizes: " + std::to_string(dims.x) + " " + std::to_string(dims.y) + " " +
              std::to_string(dims.z) + "\n";
    // Uneven slices are written with the mean step: NRRD cannot describe per-slice positions.
    header += "space directions: " + formatVector(g.axisI() * g.spacingI()) + " " +
              formatVector(g.axisJ() * g.spacingJ()) + " " +
              formatVector(g.stackAxis() * g.sliceStep()) + "\n";
    header += "space origin: " + formatVector(g.origin()) + "\n";
    if (!volume.description().empty()) {
        std::string content = volume.description();
        for (char& c : content)
            if (c == '\n' || c == '\r')
                c = ' ';
        header += "content: " + content + "\n";
    }
    header += "endian: little\nencoding: raw\n";
    if (!volume.valueMapping().isIdentity())
        header += "linework_rescale_slope:=" + formatNumber(volume.valueMapping().slope) +
                  "\nlinework_rescale_intercept:=" + formatNumber(volume.valueMapping().intercept) +
                  "\n";
    header += "\n";

    std::vector<std::byte> file(header.size() + volume.byteSize());
    std::memcpy(file.data(), header.data(), header.size());
    std::memcpy(file.data() + header.size(), volume.data(), volume.byteSize());
    if (!detail::hostIsLittleEndian())
        detail::swapBytesInPlace(file.data() + header.size(), volume.voxelCount(),
                                 voxelSize(volume.voxelType()));
    core::writeFileAtomically(path, file.data(), file.size());
}

} // namespace lw::volume
