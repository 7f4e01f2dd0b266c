#include "lw/dicom/volume_assembler.h"

#include "dicom_file.h"
#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/core/module_boundary.h"
#include "lw/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

namespace lw::dicom {

namespace {

constexpr double kOrientationTolerance = 1e-4;
constexpr double kSpacingTolerance = 1e-4;   // relative
constexpr double kPositionTolerance = 1e-3;  // mm along the normal: "the same position"
constexpr double kUnevenGapTolerance = 0.01; // relative: "gaps differ by more than 1%"

struct FrameRef {
    std::size_t instance = 0;
    int frame = 0;
    const InstanceInfo* info = nullptr;
    const FrameInfo* frameInfo = nullptr;
};

std::string formatNumber(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return buffer;
}

bool sameOrientation(const std::optional<std::array<double, 6>>& a,
                     const std::optional<std::array<double, 6>>& b) {
    if (a.has_value() != b.has_value())
        return false;
    if (!a)
        return true;
    for (std::size_t i = 0; i < 6; ++i)
        if (std::abs((*a)[i] - (*b)[i]) > kOrientationTolerance)
            return false;
    return true;
}

bool sameSpacing(const std::optional<glm::dvec2>& a, const std::optional<glm::dvec2>& b) {
    if (a.has_value() != b.has_value())
        return false;
    if (!a)
        return true;
    auto close = [](double x, double y) {
        return std::abs(x - y) <= kSpacingTolerance * std::max(std::abs(x), std::abs(y));
    };
    return close(a->x, b->x) && close(a->y, b->y);
}

bool sameRescale(const FrameInfo& a, const FrameInfo& b) {
    auto close = [](double x, double y) {
        return std::abs(x - y) <= 1e-6 * std::max({1.0, std::abs(x), std::abs(y)});
    };
    return close(a.rescaleSlope, b.rescaleSlope) && close(a.rescaleIntercept, b.rescaleIntercept);
}

// What a volume must share: frames that differ in any of these cannot be one grid.
struct GroupKey {
    int rows = 0;
    int columns = 0;
    std::optional<std::array<double, 6>> orientation;
    std::optional<glm::dvec2> spacing;
    std::string frameType; // enhanced objects only: classic ImageType varies harmlessly
    double slope = 1.0;
    double intercept = 0.0;
    bool hasPosition = true;
    // Frames without a position are stacked only within one file (a classic multi-frame object):
    // nothing says that separate files without positions belong to one stack, and stacking two
    // unrelated images with an assumed spacing would be a volume made up.
    std::optional<std::size_t> unplacedInstance;

    bool matches(const GroupKey& other) const {
        return rows == other.rows && columns == other.columns &&
               sameOrientation(orientation, other.orientation) &&
               sameSpacing(spacing, other.spacing) && frameType == other.frameType &&
               std::abs(slope - other.slope) <= 1e-6 * std::max({1.0, std::abs(slope)}) &&
               std::abs(intercept - other.intercept) <=
                   1e-6 * std::max({1.0, std::abs(intercept)}) &&
               hasPosition == other.hasPosition && unplacedInstance == other.unplacedInstance;
    }
};

GroupKey keyOf(const FrameRef& f) {
    GroupKey key;
    key.rows = f.info->rows;
    key.columns = f.info->columns;
    key.orientation = f.frameInfo->orientation;
    key.spacing = f.frameInfo->pixelSpacing;
    if (f.info->isEnhanced)
        key.frameType = f.frameInfo->frameType;
    key.slope = f.frameInfo->rescaleSlope;
    key.intercept = f.frameInfo->rescaleIntercept;
    key.hasPosition = f.frameInfo->position.has_value();
    if (!key.hasPosition)
        key.unplacedInstance = f.instance;
    return key;
}

struct Group {
    GroupKey key;
    std::vector<FrameRef> frames;
    std::string label;
    std::vector<std::string> warnings;
};

glm::dvec3 rowAxis(const GroupKey& key) {
    if (!key.orientation)
        return {1, 0, 0};
    const auto& o = *key.orientation;
    return {o[0], o[1], o[2]};
}

glm::dvec3 columnAxis(const GroupKey& key) {
    if (!key.orientation)
        return {0, 1, 0};
    const auto& o = *key.orientation;
    return {o[3], o[4], o[5]};
}

glm::dvec3 normalOf(const GroupKey& key) {
    const glm::dvec3 n = glm::cross(rowAxis(key), columnAxis(key));
    const double length = glm::length(n);
    return length > 0 ? n / length : glm::dvec3(0, 0, 1);
}

double distanceAlongNormal(const FrameRef& f, const glm::dvec3& normal) {
    return glm::dot(*f.frameInfo->position, normal);
}

// Order of frames that share a position: acquisition order as far as the headers tell it.
bool occurrenceLess(const FrameRef& a, const FrameRef& b) {
    auto rank = [](const FrameRef& f) {
        return std::make_tuple(f.frameInfo->temporalPosition.value_or(0),
                               f.info->acquisitionNumber.value_or(0),
                               f.info->instanceNumber.value_or(0), f.instance, f.frame);
    };
    return rank(a) < rank(b);
}

// The group's frames sorted along its slice normal, in clusters of frames at one position.
std::vector<std::vector<FrameRef>> positionClusters(Group& group) {
    const glm::dvec3 normal = normalOf(group.key);
    std::sort(group.frames.begin(), group.frames.end(), [&](const FrameRef& a, const FrameRef& b) {
        return distanceAlongNormal(a, normal) < distanceAlongNormal(b, normal);
    });
    std::vector<std::vector<FrameRef>> positions;
    for (const FrameRef& f : group.frames) {
        if (!positions.empty() &&
            std::abs(distanceAlongNormal(f, normal) -
                     distanceAlongNormal(positions.back().front(), normal)) <= kPositionTolerance &&
            glm::length(*f.frameInfo->position - *positions.back().front().frameInfo->position) <=
                10 * kPositionTolerance)
            positions.back().push_back(f);
        else
            positions.push_back({f});
    }
    return positions;
}

// The group split by a header attribute that separates the repeats cleanly (each value once per
// position), labelled with the attribute; empty when no attribute does.
std::vector<Group> splitByAttribute(const Group& group,
                                    const std::vector<std::vector<FrameRef>>& positions) {
    using Discriminator = std::function<std::optional<int>(const FrameRef&)>;
    const std::vector<std::pair<std::string, Discriminator>> candidates = {
        {"temporal position", [](const FrameRef& f) { return f.frameInfo->temporalPosition; }},
        {"acquisition", [](const FrameRef& f) { return f.info->acquisitionNumber; }},
    };
    for (const auto& candidate : candidates) {
        // Named, not a structured binding: lambdas may not capture those before C++20's P1091
        // (clang 14, the fuzz build's compiler, rejects it).
        const std::string& name = candidate.first;
        const Discriminator& value = candidate.second;
        std::map<int, std::vector<FrameRef>> split;
        const bool everyFrame =
            std::all_of(group.frames.begin(), group.frames.end(),
                        [&](const FrameRef& f) { return value(f).has_value(); });
        if (!everyFrame)
            continue;
        for (const FrameRef& f : group.frames)
            split[*value(f)].push_back(f);
        if (split.size() < 2)
            continue;
        bool clean = true;
        for (const auto& p : positions) {
            std::set<int> seen;
            for (const FrameRef& f : p)
                clean = clean && seen.insert(*value(f)).second;
        }
        if (!clean)
            continue;
        std::vector<Group> result;
        for (auto& [v, frames] : split) {
            Group part;
            part.key = group.key;
            part.frames = std::move(frames);
            part.label = name + " " + std::to_string(v);
            result.push_back(std::move(part));
        }
        return result;
    }
    return {};
}

// dcm2niix style: the n-th frame at each position (in acquisition order) goes to volume n.
std::vector<Group> splitByOccurrence(const Group& group,
                                     std::vector<std::vector<FrameRef>> positions,
                                     std::size_t duplicates) {
    std::size_t volumes = 0;
    for (auto& p : positions) {
        std::sort(p.begin(), p.end(), occurrenceLess);
        volumes = std::max(volumes, p.size());
    }
    std::vector<Group> result(volumes);
    for (std::size_t v = 0; v < volumes; ++v) {
        result[v].key = group.key;
        result[v].label = "repeat " + std::to_string(v + 1);
        result[v].warnings.push_back(
            std::to_string(duplicates) +
            " duplicate positions in the series: frames at the same position were "
            "split into " +
            std::to_string(volumes) + " volumes in acquisition order");
    }
    for (const auto& p : positions)
        for (std::size_t k = 0; k < p.size(); ++k)
            result[k].frames.push_back(p[k]);
    return result;
}

// Frames at one position in groups of duplicates. Returns the groups split so that no
// position repeats: by a header attribute when one separates them cleanly, otherwise by the
// order of occurrence (the first frame at each position goes to volume 1, the second to 2...).
std::vector<Group> splitDuplicates(Group group, std::vector<std::string>& seriesWarnings) {
    std::vector<std::vector<FrameRef>> positions = positionClusters(group);
    std::size_t duplicates = 0;
    for (const auto& p : positions)
        duplicates += p.size() - 1;
    if (duplicates == 0)
        return {std::move(group)};
    if (positions.size() == 1) {
        seriesWarnings.push_back(
            "all " + std::to_string(group.frames.size()) +
            " slices share one position: not a volume (no volume made of them)");
        return {};
    }
    std::vector<Group> byAttribute = splitByAttribute(group, positions);
    if (!byAttribute.empty())
        return byAttribute;
    return splitByOccurrence(group, std::move(positions), duplicates);
}

// The most common gap, clustering gaps within 1% of each other (ties: the smaller gap).
double commonGap(std::vector<double> gaps) {
    std::sort(gaps.begin(), gaps.end());
    double best = gaps.front();
    std::size_t bestCount = 0;
    for (std::size_t i = 0; i < gaps.size(); ++i) {
        std::size_t count = 0;
        double sum = 0;
        for (double g : gaps)
            if (std::abs(g - gaps[i]) <= kUnevenGapTolerance * std::abs(gaps[i])) {
                ++count;
                sum += g;
            }
        if (count > bestCount) {
            bestCount = count;
            best = sum / double(count);
        }
    }
    return best;
}

volume::VoxelType chooseVoxelType(const std::vector<const InstanceInfo*>& instances,
                                  std::vector<std::string>& warnings) {
    std::set<volume::VoxelType> types;
    bool unsignedNeeds16Bits = false;
    for (const InstanceInfo* info : instances) {
        const volume::VoxelType type = storedVoxelType(*info);
        types.insert(type);
        if (type == volume::VoxelType::UInt16 && info->bitsStored >= 16)
            unsignedNeeds16Bits = true;
    }
    if (types.size() == 1)
        return *types.begin();
    if (types.count(volume::VoxelType::Int16)) {
        if (unsignedNeeds16Bits)
            warnings.push_back(
                "signed and unsigned 16-bit slices mixed: unsigned values above 32767 are clipped");
        return volume::VoxelType::Int16;
    }
    return volume::VoxelType::UInt16; // uint8 and uint16 mixed
}

// Slices a gap of `ratio` common gaps hides; none when the ratio is no whole multiple. A gap
// of more than kMaxMissingPerGap is no run of lost slices (a scout, a second station): it is
// reported as an uneven gap only, and the estimate stays small whatever the positions say.
constexpr double kMaxMissingPerGap = 1000.0;

int missingSlicesInGap(double ratio) {
    if (!std::isfinite(ratio))
        return 0;
    const double whole = std::round(ratio);
    if (whole < 2 || whole - 1 > kMaxMissingPerGap || std::abs(ratio - whole) >= 0.1)
        return 0;
    return int(whole) - 1;
}

// Gaps along the stack: min/max, whether they are uneven, and the missing slices they suggest.
void measureGaps(const std::vector<glm::dvec3>& positions, VolumePlan& plan) {
    if (positions.size() < 2)
        return;
    const glm::dvec3 axis = plan.geometry.stackAxis();
    std::vector<double> gaps;
    for (std::size_t k = 1; k < positions.size(); ++k)
        gaps.push_back(glm::dot(positions[k] - positions[k - 1], axis));
    plan.minGap = *std::min_element(gaps.begin(), gaps.end());
    plan.maxGap = *std::max_element(gaps.begin(), gaps.end());
    plan.unevenGaps = plan.maxGap - plan.minGap > kUnevenGapTolerance * std::abs(plan.maxGap);
    if (!plan.unevenGaps)
        return;
    const double common = commonGap(gaps);
    long long missing = 0; // at most kMaxMissingPerGap per gap: cannot overflow for any frame count
    for (double g : gaps)
        missing += missingSlicesInGap(common > 0 ? g / common : 0.0);
    plan.missingSlices = int(std::min<long long>(missing, std::numeric_limits<int>::max()));
    plan.warnings.push_back("uneven slice gaps: " + formatNumber(plan.minGap) + " to " +
                            formatNumber(plan.maxGap) + " mm");
    if (plan.missingSlices > 0)
        plan.warnings.push_back(
            "about " + std::to_string(plan.missingSlices) + " missing slice(s): gaps of " +
            "whole multiples of the common gap " + formatNumber(common) + " mm");
}

// Why a frame's position cannot be a patient's (not finite, or farther than 10 m from the
// origin); empty when it can. Such a frame is left out with this reason: one damaged header
// must neither stretch the volume to a kilometre nor overflow the slice arithmetic.
std::string implausiblePosition(const FrameInfo& frame) {
    if (!frame.position)
        return {};
    const glm::dvec3 p = *frame.position;
    for (int axis = 0; axis < 3; ++axis) {
        if (!std::isfinite(p[axis]))
            return "ImagePositionPatient is not a finite number";
        if (std::abs(p[axis]) > core::kMaxPlausibleExtentMm)
            return "implausible ImagePositionPatient (" + formatNumber(p.x) + ", " +
                   formatNumber(p.y) + ", " + formatNumber(p.z) +
                   " mm): more than 10 m from the origin";
    }
    return {};
}

VolumePlan makePlan(const SeriesInfo& series, Group group) {
    VolumePlan plan;
    plan.seriesInstanceUid = series.seriesInstanceUid;
    plan.label = group.label;
    plan.warnings = group.warnings;
    const GroupKey& key = group.key;
    const glm::dvec3 normal = normalOf(key);

    if (key.hasPosition) {
        std::stable_sort(group.frames.begin(), group.frames.end(),
                         [&](const FrameRef& a, const FrameRef& b) {
                             return distanceAlongNormal(a, normal) < distanceAlongNormal(b, normal);
                         });
    } else {
        // Nothing places these frames in space: keep the order the headers imply (frame order
        // within a file, then InstanceNumber) and say so.
        std::stable_sort(
            group.frames.begin(), group.frames.end(), [](const FrameRef& a, const FrameRef& b) {
                return std::make_tuple(a.info->instanceNumber.value_or(0), a.instance, a.frame) <
                       std::make_tuple(b.info->instanceNumber.value_or(0), b.instance, b.frame);
            });
        if (group.frames.size() > 1)
            plan.warnings.push_back(
                "no ImagePositionPatient: " + std::to_string(group.frames.size()) +
                " frames stacked in frame/instance order with an assumed slice spacing");
        else
            plan.warnings.push_back("no ImagePositionPatient: a single slice placed at the origin");
    }
    if (!key.orientation)
        plan.warnings.push_back("no ImageOrientationPatient: axial orientation assumed");
    if (!key.spacing)
        plan.warnings.push_back("no PixelSpacing: 1 mm assumed");

    const FrameRef& first = group.frames.front();
    double step = 1.0;
    if (first.info->spacingBetweenSlices && *first.info->spacingBetweenSlices > 0)
        step = *first.info->spacingBetweenSlices;
    else if (first.frameInfo->sliceThickness && *first.frameInfo->sliceThickness > 0)
        step = *first.frameInfo->sliceThickness;

    std::vector<glm::dvec3> positions;
    positions.reserve(group.frames.size());
    for (std::size_t k = 0; k < group.frames.size(); ++k) {
        const FrameRef& f = group.frames[k];
        const glm::dvec3 p = key.hasPosition ? *f.frameInfo->position : normal * (double(k) * step);
        positions.push_back(p);
        plan.slices.push_back(SliceRef{f.instance, f.frame, p});
    }

    // PixelSpacing is (row spacing, column spacing): the distance between rows runs along
    // the column axis (J), the distance between columns along the row axis (I).
    const glm::dvec2 spacing = key.spacing.value_or(glm::dvec2(1.0, 1.0));
    plan.geometry = volume::VolumeGeometry::fromSlicePositions(
        rowAxis(key), columnAxis(key), spacing.y, spacing.x, positions, step);
    plan.dims = glm::ivec3(key.columns, key.rows, int(group.frames.size()));
    plan.tiltDegrees = plan.geometry.tiltDegrees();
    plan.valueMapping = volume::ValueMapping{key.slope, key.intercept};

    measureGaps(positions, plan);
    if (plan.tiltDegrees > 0.01)
        plan.warnings.push_back("gantry tilt " + formatNumber(plan.tiltDegrees) +
                                " degrees (sheared volume)");

    std::vector<const InstanceInfo*> instances;
    std::set<std::size_t> seen;
    for (const FrameRef& f : group.frames) {
        if (seen.insert(f.instance).second) {
            instances.push_back(f.info);
            if (std::find(plan.transferSyntaxes.begin(), plan.transferSyntaxes.end(),
                          f.info->transferSyntaxUid) == plan.transferSyntaxes.end())
                plan.transferSyntaxes.push_back(f.info->transferSyntaxUid);
        }
    }
    plan.voxelType = chooseVoxelType(instances, plan.warnings);
    return plan;
}

// Labels for sibling volumes: only what differs between them is worth saying.
void labelGroups(std::vector<Group>& groups) {
    if (groups.size() < 2)
        return;
    auto differs = [&](auto project) {
        for (const Group& g : groups)
            if (project(g) != project(groups.front()))
                return true;
        return false;
    };
    const bool size =
        differs([](const Group& g) { return std::make_pair(g.key.rows, g.key.columns); });
    const bool type = differs([](const Group& g) { return g.key.frameType; });
    const bool rescale =
        differs([](const Group& g) { return std::make_pair(g.key.slope, g.key.intercept); });
    const bool spacing = differs([](const Group& g) {
        return g.key.spacing ? std::make_pair(g.key.spacing->x, g.key.spacing->y)
                             : std::make_pair(0.0, 0.0);
    });
    const bool placed = differs([](const Group& g) { return g.key.hasPosition; });
    bool orientation = false;
    for (const Group& g : groups)
        orientation =
            orientation || !sameOrientation(g.key.orientation, groups.front().key.orientation);

    std::vector<std::array<double, 6>> orientations;
    for (Group& g : groups) {
        std::vector<std::string> parts;
        if (size)
            parts.push_back(std::to_string(g.key.columns) + "x" + std::to_string(g.key.rows));
        if (orientation) {
            std::size_t index = orientations.size();
            for (std::size_t i = 0; i < orientations.size(); ++i)
                if (sameOrientation(orientations[i], g.key.orientation))
                    index = i;
            if (index == orientations.size() && g.key.orientation)
                orientations.push_back(*g.key.orientation);
            parts.push_back("orientation " + std::to_string(index + 1));
        }
        if (spacing && g.key.spacing)
            parts.push_back("pixel spacing " + formatNumber(g.key.spacing->x) + "/" +
                            formatNumber(g.key.spacing->y));
        if (type)
            parts.push_back(g.key.frameType.empty() ? std::string("no frame type")
                                                    : g.key.frameType);
        if (rescale)
            parts.push_back("rescale " + formatNumber(g.key.slope) + "/" +
                            formatNumber(g.key.intercept));
        if (placed && !g.key.hasPosition)
            parts.push_back("without position");
        if (!g.key.hasPosition && groups.size() > 1)
            parts.push_back("file " +
                            std::filesystem::path(g.frames.front().info->path).filename().string());
        if (!g.label.empty())
            parts.push_back(g.label);
        std::string label;
        for (const auto& part : parts)
            label += (label.empty() ? "" : ", ") + part;
        g.label = label;
    }
}

} // namespace

static SeriesAssembly planVolumesUnguarded(const SeriesInfo& series) {
    SeriesAssembly assembly;
    std::vector<FrameRef> frames;
    std::size_t withoutPixels = 0;
    for (std::size_t i = 0; i < series.instances.size(); ++i) {
        const InstanceInfo& info = series.instances[i];
        if (!info.hasPixelData) {
            ++withoutPixels;
            continue;
        }
        try {
            (void)storedVoxelType(info);
        } catch (const core::Error& e) {
            assembly.errors.push_back(FileError{info.path, e.reason()});
            continue;
        }
        std::string implausible;
        for (const FrameInfo& frame : info.frames)
            if (implausible = implausiblePosition(frame); !implausible.empty())
                break;
        if (!implausible.empty()) {
            assembly.errors.push_back(FileError{info.path, implausible});
            continue;
        }
        for (const FrameInfo& frame : info.frames)
            frames.push_back(FrameRef{i, frame.frameIndex, &info, &frame});
    }
    if (withoutPixels > 0)
        assembly.warnings.push_back(std::to_string(withoutPixels) +
                                    " instance(s) have no pixel data");
    if (frames.empty())
        return assembly;

    std::vector<Group> groups;
    for (const FrameRef& f : frames) {
        const GroupKey key = keyOf(f);
        auto it = std::find_if(groups.begin(), groups.end(),
                               [&](const Group& g) { return g.key.matches(key); });
        if (it == groups.end()) {
            groups.push_back(Group{key, {}, {}, {}});
            it = groups.end() - 1;
        }
        it->frames.push_back(f);
    }
    bool classicRescaleSplit = false;
    for (const Group& g : groups)
        for (const Group& h : groups)
            if (&g != &h && !g.frames.front().info->isEnhanced &&
                !sameRescale(*g.frames.front().frameInfo, *h.frames.front().frameInfo))
                classicRescaleSplit = true;
    if (classicRescaleSplit)
        assembly.warnings.push_back(
            "rescale slope/intercept varies between slices: the series is split by rescale");
    if (groups.size() > 1)
        assembly.warnings.push_back(
            "series split into " + std::to_string(groups.size()) +
            " groups (orientation, size, pixel spacing, frame type or rescale differ)");

    std::vector<Group> split;
    for (Group& g : groups) {
        if (!g.key.hasPosition) {
            split.push_back(std::move(g));
            continue;
        }
        for (Group& part : splitDuplicates(std::move(g), assembly.warnings))
            split.push_back(std::move(part));
    }
    labelGroups(split);
    for (Group& g : split) {
        try {
            assembly.volumes.push_back(makePlan(series, std::move(g)));
        } catch (const core::Error& e) {
            assembly.warnings.push_back(std::string("a group of frames could not be planned: ") +
                                        e.what());
        }
    }
    return assembly;
}

// Everything loadVolume can know before it allocates: the plan matches the series, the volume
// fits the import limits, and each file's native pixel data is as long as its header says (a
// 65535x65535 header without its pixels must fail here, not after allocating 8 GB).
void checkBeforeLoading(const SeriesInfo& series, const VolumePlan& plan,
                        const core::ImportLimits& limits) {
    if (plan.slices.empty() || plan.dims.z != int(plan.slices.size()))
        throw core::Error(series.seriesInstanceUid, "the volume plan has no slices");
    volume::checkVolumeAllocation(plan.dims, plan.voxelType, limits, series.seriesInstanceUid);
    std::map<std::size_t, int> lastFrame; // per instance: the highest frame the plan uses
    for (const SliceRef& slice : plan.slices) {
        if (slice.instance >= series.instances.size())
            throw core::Error(series.seriesInstanceUid,
                              "the volume plan does not match the series");
        const InstanceInfo& info = series.instances[slice.instance];
        if (info.rows != plan.dims.y || info.columns != plan.dims.x)
            throw core::Error(info.path, "image size differs from the volume's");
        lastFrame[slice.instance] = std::max(lastFrame[slice.instance], slice.frame);
    }
    for (const auto& [instance, frame] : lastFrame) {
        const InstanceInfo& info = series.instances[instance];
        if (!info.nativePixelDataBytes)
            continue; // encapsulated: the decoder finds out frame by frame
        const std::size_t needed = core::checkedProduct(
            {std::size_t(frame) + 1, std::size_t(info.rows), std::size_t(info.columns),
             std::size_t(std::max(1, info.samplesPerPixel)),
             std::size_t(std::max(1, info.bitsAllocated / 8))},
            info.path, "the pixel data");
        if (*info.nativePixelDataBytes < needed)
            throw core::Error(
                info.path, "pixel data truncated: " + std::to_string(*info.nativePixelDataBytes) +
                               " bytes where the header declares " + std::to_string(needed));
    }
}

static volume::Volume loadVolumeUnguarded(const SeriesInfo& series, const VolumePlan& plan,
                                          core::Progress* progress,
                                          const core::ImportLimits& limits) {
    checkBeforeLoading(series, plan, limits);
    volume::Volume result(plan.dims, plan.voxelType, plan.geometry);
    result.setValueMapping(plan.valueMapping);
    std::string description = series.description;
    if (!plan.label.empty())
        description += (description.empty() ? "" : " ") + ("(" + plan.label + ")");
    result.setDescription(description);

    // One work item per file: a multi-frame object is opened and decompressed once, and
    // single-frame series (the common case) still spread over all cores.
    std::map<std::size_t, std::vector<int>> slicesByInstance;
    for (int z = 0; z < int(plan.slices.size()); ++z)
        slicesByInstance[plan.slices[std::size_t(z)].instance].push_back(z);
    std::vector<std::pair<std::size_t, std::vector<int>>> work(slicesByInstance.begin(),
                                                               slicesByInstance.end());

    if (progress)
        progress->setTotal(plan.slices.size(),
                           "Loading " + std::to_string(plan.slices.size()) + " slices");
    core::parallelFor(work.size(), [&](std::size_t item) {
        // Named, not a structured binding: clang 14 cannot capture one in the lambda below.
        const InstanceInfo& info = series.instances[work[item].first];
        const std::vector<int>& zs = work[item].second;
        // A library failure while decoding names this file, not just the series.
        core::atModuleBoundary(info.path, [&] {
            FrameDecoder decoder(info, limits);
            for (int z : zs) {
                if (progress)
                    progress->throwIfCancelled();
                decoder.decodeFrame(plan.slices[std::size_t(z)].frame, plan.voxelType,
                                    result.sliceData(z));
                if (progress)
                    progress->step();
            }
        });
    });
    return result;
}

static volume::Volume loadSliceUnguarded(const SeriesInfo& series, const VolumePlan& plan,
                                         std::size_t sliceIndex, core::Progress* progress,
                                         const core::ImportLimits& limits) {
    if (sliceIndex >= plan.slices.size())
        throw core::Error(series.seriesInstanceUid,
                          "slice " + std::to_string(sliceIndex) + " is outside the volume plan (" +
                              std::to_string(plan.slices.size()) + " slices)");
    VolumePlan one = plan;
    one.slices = {plan.slices[sliceIndex]};
    one.dims.z = 1;
    one.geometry = plan.geometry.subStack(int(sliceIndex), 1);
    return loadVolumeUnguarded(series, one, progress, limits);
}

// The public entries: nothing but core::Error and core::Cancelled leaves them. The subject is
// the series; errors of one file already name that file.
SeriesAssembly planVolumes(const SeriesInfo& series) {
    return core::atModuleBoundary(series.seriesInstanceUid,
                                  [&] { return planVolumesUnguarded(series); });
}

volume::Volume loadVolume(const SeriesInfo& series, const VolumePlan& plan,
                          core::Progress* progress, const core::ImportLimits& limits) {
    return core::atModuleBoundary(series.seriesInstanceUid, [&] {
        return loadVolumeUnguarded(series, plan, progress, limits);
    });
}

volume::Volume loadSlice(const SeriesInfo& series, const VolumePlan& plan, std::size_t sliceIndex,
                         core::Progress* progress, const core::ImportLimits& limits) {
    return core::atModuleBoundary(series.seriesInstanceUid, [&] {
        return loadSliceUnguarded(series, plan, sliceIndex, progress, limits);
    });
}

} // namespace lw::dicom
