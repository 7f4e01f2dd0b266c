#include "dicom_dcmtk.h"
#include "dicom_file.h"
#include "jpeg2000_decoder.h"
#include "lw/core/error.h"
#include "lw/core/log.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <dcmtk/dcmdata/dccodec.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcpixel.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <dcmtk/dcmdata/dcrledrg.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/dcmjpeg/djdecode.h>
#include <dcmtk/dcmjpls/djdecode.h>
#include <dlfcn.h>
#include <limits>
#include <memory>
#include <span>
#include <utility>

namespace lw::dicom {

namespace {

const core::LogCategory kLog("lw.dicom");

// DCMTK's codec list is global: register the decoders exactly once per process, thread-safe
// through the function-local static, and unregister them at exit.
struct DecoderRegistration {
    DecoderRegistration() {
        DJDecoderRegistration::registerCodecs();
        DJLSDecoderRegistration::registerCodecs();
        DcmRLEDecoderRegistration::registerCodecs();
    }
    ~DecoderRegistration() {
        DcmRLEDecoderRegistration::cleanup();
        DJLSDecoderRegistration::cleanup();
        DJDecoderRegistration::cleanup();
    }
};

void ensureDecoders() {
    static DecoderRegistration registration;
}

bool isJpeg2000(const std::string& uid) {
    return uid == "1.2.840.10008.1.2.4.90" || uid == "1.2.840.10008.1.2.4.91" ||
           uid == "1.2.840.10008.1.2.4.92" || uid == "1.2.840.10008.1.2.4.93";
}

bool isJpegLs(const std::string& uid) {
    return uid == "1.2.840.10008.1.2.4.80" || uid == "1.2.840.10008.1.2.4.81";
}

// DCMTK 3.6.7 ships its own CharLS (libdcmtkcharls); the system CharLS 2 exports JpegLsDecode
// with another ABI, and the dynamic linker binds every caller to whichever library was loaded
// first. Nothing in Linework links the system CharLS (GDCM did, until JPEG 2000 moved to
// OpenJPEG), but a plug-in or a link order could bring it in: then DCMTK's JPEG-LS codec would
// call the wrong function, so JPEG-LS files are refused instead of crashing.
bool dcmtkJpegLsIsSafe() {
    static const bool safe = [] {
        void* symbol = dlsym(RTLD_DEFAULT, "JpegLsDecode");
        Dl_info info{};
        if (!symbol || !dladdr(symbol, &info) || !info.dli_fname)
            return true;
        return std::string(info.dli_fname).find("dcmtkcharls") != std::string::npos;
    }();
    return safe;
}

template <typename T> T clampTo(std::int32_t value) {
    return T(std::clamp<std::int32_t>(value, std::int32_t(std::numeric_limits<T>::min()),
                                      std::int32_t(std::numeric_limits<T>::max())));
}

// The items of an encapsulated pixel sequence, taken out of it: item 0 is the Basic Offset
// Table, the others the fragments. DCMTK's getItem(i) walks its list from the start, so reading
// n fragments that way costs n²/2 steps, which a small file of 100 000 empty fragments turns
// into minutes; remove(0) costs one step.
using PixelItems = std::vector<std::unique_ptr<DcmPixelItem>>;

PixelItems takeItems(DcmPixelSequence& sequence) {
    PixelItems items;
    DcmPixelItem* item = nullptr;
    while (sequence.card() > 0 && sequence.remove(item, 0).good() && item)
        items.emplace_back(item);
    return items;
}

std::span<const std::uint8_t> bytesOf(DcmPixelItem& item) {
    Uint8* bytes = nullptr;
    if (item.getUint8Array(bytes).bad() || !bytes)
        return {};
    return {bytes, item.getLength()};
}

// Fragment index ranges [first, last] of each frame.
using FrameRanges = std::vector<std::pair<std::size_t, std::size_t>>;

// The ranges from each frame's first fragment, the last frame taking the rest.
FrameRanges rangesFromStarts(const std::vector<std::size_t>& starts, std::size_t items) {
    FrameRanges ranges;
    for (std::size_t f = 0; f < starts.size(); ++f)
        ranges.push_back({starts[f], f + 1 < starts.size() ? starts[f + 1] - 1 : items - 1});
    return ranges;
}

// The Basic Offset Table: each frame's first fragment by the byte offset of its item from the
// first fragment's (PS3.5 A.4). Empty when the table is absent or does not match the fragments.
FrameRanges framesByOffsetTable(const PixelItems& items, int frames) {
    const auto table = bytesOf(*items[0]);
    if (table.size() != 4 * std::size_t(frames))
        return {};
    std::vector<std::size_t> starts;
    std::uint64_t offset = 0;
    for (std::size_t index = 1; index < items.size() && int(starts.size()) < frames; ++index) {
        const std::uint8_t* entry = table.data() + 4 * starts.size();
        const std::uint32_t wanted = std::uint32_t(entry[0]) | std::uint32_t(entry[1]) << 8 |
                                     std::uint32_t(entry[2]) << 16 | std::uint32_t(entry[3]) << 24;
        if (wanted < offset)
            return {}; // offsets must grow: a frame cannot start inside another
        if (wanted == offset)
            starts.push_back(index);
        offset += std::uint64_t(items[index]->getLength()) + 8; // the item tag and length
    }
    return int(starts.size()) == frames ? rangesFromStarts(starts, items.size()) : FrameRanges{};
}

// Without a usable table: a JPEG 2000 frame ends with the EOC marker (FFD9), perhaps followed by
// the one byte of padding that makes a fragment's length even.
FrameRanges framesByEndMarkers(const PixelItems& items, int frames) {
    std::vector<std::size_t> starts{1};
    for (std::size_t index = 1; index + 1 < items.size() && int(starts.size()) < frames; ++index) {
        auto bytes = bytesOf(*items[index]);
        if (bytes.size() >= 3 && bytes.back() == 0)
            bytes = bytes.first(bytes.size() - 1);
        if (bytes.size() >= 2 && bytes[bytes.size() - 2] == 0xFF && bytes.back() == 0xD9)
            starts.push_back(index + 1);
    }
    return int(starts.size()) == frames ? rangesFromStarts(starts, items.size()) : FrameRanges{};
}

// Which fragments make each frame: all of them for one frame, one each when there are as many
// as frames, else the offset table, else the end markers. Empty when none of these tells.
FrameRanges frameFragments(const PixelItems& items, int frames) {
    if (items.size() < 2 || frames < 1)
        return {};
    if (frames == 1)
        return {{1, items.size() - 1}};
    if (items.size() - 1 == std::size_t(frames)) {
        FrameRanges ranges;
        for (std::size_t index = 1; index < items.size(); ++index)
            ranges.push_back({index, index});
        return ranges;
    }
    FrameRanges ranges = framesByOffsetTable(items, frames);
    return ranges.empty() ? framesByEndMarkers(items, frames) : ranges;
}

} // namespace

struct FrameDecoder::Impl {
    InstanceInfo info;
    core::ImportLimits limits;
    DcmFileFormat file;
    std::vector<std::byte> inflated; // gzip-wrapped files: the DICOM bytes
    bool loaded = false;

    // Native pixel data (after DCMTK's decompression where needed), host order, every frame.
    const Uint8* bytes8 = nullptr;
    const Uint16* words16 = nullptr;
    std::size_t byteLength = 0;

    // JPEG 2000: each frame is decoded from its fragments when asked for, into frameBuffer.
    PixelItems jpeg2000Items;
    FrameRanges jpeg2000Frames;
    std::vector<std::byte> frameBuffer;
    int bufferedFrame = -1;

    int bitsStored = 0; // effective: may follow the codestream where the header is wrong
    int highBit = 0;

    std::string where(int frame) const {
        return info.path + " (frame " + std::to_string(frame + 1) + " of " +
               std::to_string(info.numberOfFrames) + ")";
    }

    [[noreturn]] void fail(int frame, const std::string& reason) const {
        throw core::Error(where(frame), reason);
    }

    // What the header declares for the whole pixel data: a deflated data set may inflate to
    // little more than this (the header read checked it against the limits already).
    std::size_t declaredPixelBytes() const {
        return core::checkedProduct({std::size_t(std::max(info.rows, 0)),
                                     std::size_t(std::max(info.columns, 0)),
                                     std::size_t(std::max(info.numberOfFrames, 1)),
                                     std::size_t(std::max(info.samplesPerPixel, 1)),
                                     std::size_t(std::max(1, (info.bitsAllocated + 7) / 8))},
                                    info.path, "the pixel data the header declares");
    }

    void load(int frame);
    void prepareJpeg2000(int frame, DcmPixelData& pixelData, E_TransferSyntax xfer);
    void followCodestreamPrecision(std::span<const std::uint8_t> codestream);
    std::span<const std::uint8_t> jpeg2000Codestream(int frame, std::vector<std::uint8_t>& joined);
    const void* frameSamples(int frame, std::size_t frameBytes);
};

void FrameDecoder::Impl::load(int frame) {
    ensureDecoders();
    loadDicomFile(info.path, file, false, &inflated, limits, declaredPixelBytes());
    DcmDataset& ds = *file.getDataset();
    DcmElement* element = nullptr;
    if (ds.findAndGetElement(DCM_PixelData, element, OFFalse).bad() || !element)
        fail(frame, "no pixel data");
    auto* pixelData = OFdynamic_cast(DcmPixelData*, element);
    if (!pixelData)
        fail(frame, "pixel data element of unexpected type");

    bitsStored = info.bitsStored;
    highBit = info.highBit;
    const E_TransferSyntax xfer = ds.getOriginalXfer();
    const DcmXfer xferInfo(xfer);
    const std::string syntaxUid =
        info.transferSyntaxUid.empty() ? xferInfo.getXferID() : info.transferSyntaxUid;
    if (isJpeg2000(syntaxUid)) {
        prepareJpeg2000(frame, *pixelData, xfer);
        loaded = true;
        return;
    }
    if (xferInfo.isEncapsulated()) {
        if (isJpegLs(syntaxUid) && !dcmtkJpegLsIsSafe())
            fail(frame, "JPEG-LS cannot be decoded: another CharLS library was loaded before "
                        "DCMTK's");
        // Decompress the whole object once: a multi-frame file is decoded a single time, and
        // DCMTK assembles frames split over several fragments itself.
        const OFCondition status = ds.chooseRepresentation(EXS_LittleEndianExplicit, nullptr);
        if (status.bad() || !ds.canWriteXfer(EXS_LittleEndianExplicit))
            fail(frame, "cannot decode " + std::string(xferInfo.getXferName()) + " (" + syntaxUid +
                            ")" +
                            (status.bad() ? std::string(": ") + status.text() : std::string()));
    }

    // Native pixel data: DCMTK has swapped big-endian words into host order while loading.
    byteLength = pixelData->getLength(EXS_LittleEndianExplicit);
    if (info.bitsAllocated == 16) {
        Uint16* words = nullptr;
        if (pixelData->getUint16Array(words).bad() || !words)
            fail(frame, "cannot read pixel data (file truncated or corrupt)");
        words16 = words;
    } else {
        Uint8* values = nullptr;
        if (pixelData->getUint8Array(values).bad() || !values)
            fail(frame, "cannot read pixel data (file truncated or corrupt)");
        bytes8 = values;
    }
    loaded = true;
}

// Finds each frame's fragments in the sequence DCMTK parsed; nothing is decoded yet.
void FrameDecoder::Impl::prepareJpeg2000(int frame, DcmPixelData& pixelData,
                                         E_TransferSyntax xfer) {
    DcmPixelSequence* sequence = nullptr;
    if (pixelData.getEncapsulatedRepresentation(xfer, nullptr, sequence).bad() || !sequence)
        fail(frame, "JPEG 2000 pixel data is not encapsulated");
    jpeg2000Items = takeItems(*sequence);
    jpeg2000Frames = frameFragments(jpeg2000Items, info.numberOfFrames);
    if (jpeg2000Frames.empty())
        fail(frame, "cannot tell which of the " + std::to_string(jpeg2000Items.size()) +
                        " pixel data items belong to which of the " +
                        std::to_string(info.numberOfFrames) + " frames");
    std::vector<std::uint8_t> joined;
    followCodestreamPrecision(jpeg2000Codestream(0, joined));
}

// The codestream's own precision: where it disagrees with BitsStored, the header is the one
// that is wrong (pydicom's 693_* files), and masking to it would cut off real bits.
void FrameDecoder::Impl::followCodestreamPrecision(std::span<const std::uint8_t> codestream) {
    const auto size = detail::readJpeg2000Size(codestream);
    if (!size)
        return; // the decode of the frame reports it
    if (size->precision != info.bitsStored) {
        kLog.warning(info.path + ": BitsStored " + std::to_string(info.bitsStored) +
                     " disagrees with the JPEG 2000 precision " + std::to_string(size->precision) +
                     "; using the codestream's");
        bitsStored = size->precision;
        highBit = size->precision - 1;
    }
    if (size->isSigned != (info.pixelRepresentation == 1))
        kLog.warning(info.path + ": PixelRepresentation disagrees with the JPEG 2000 codestream; "
                                 "values are read as the header says");
}

// One frame's codestream: its fragment in place, or several joined into `joined`.
std::span<const std::uint8_t>
FrameDecoder::Impl::jpeg2000Codestream(int frame, std::vector<std::uint8_t>& joined) {
    const auto [first, last] = jpeg2000Frames[std::size_t(frame)];
    if (first == last)
        return bytesOf(*jpeg2000Items[first]);
    for (std::size_t index = first; index <= last; ++index) {
        const auto bytes = bytesOf(*jpeg2000Items[index]);
        joined.insert(joined.end(), bytes.begin(), bytes.end());
    }
    return joined;
}

// The samples of one frame in the native layout (bitsAllocated each, host order).
const void* FrameDecoder::Impl::frameSamples(int frame, std::size_t frameBytes) {
    if (!jpeg2000Frames.empty()) {
        if (bufferedFrame != frame) {
            std::vector<std::uint8_t> joined;
            frameBuffer.resize(frameBytes);
            bufferedFrame = -1;
            detail::decodeJpeg2000(jpeg2000Codestream(frame, joined),
                                   {info.rows, info.columns, info.bitsAllocated}, frameBuffer,
                                   where(frame));
            bufferedFrame = frame;
        }
        return frameBuffer.data();
    }
    const std::size_t needed = (std::size_t(frame) + 1) * frameBytes;
    if (byteLength < needed)
        fail(frame, "pixel data truncated: " + std::to_string(byteLength) + " bytes where " +
                        std::to_string(needed) + " are needed");
    if (words16)
        return words16 + std::size_t(frame) * frameBytes / 2;
    return bytes8 + std::size_t(frame) * frameBytes;
}

FrameDecoder::FrameDecoder(const InstanceInfo& instance, const core::ImportLimits& limits)
    : m_impl(std::make_unique<Impl>()) {
    m_impl->info = instance;
    m_impl->limits = limits;
    m_impl->info.frames.clear(); // geometry is not needed here
}

FrameDecoder::~FrameDecoder() = default;

void FrameDecoder::decodeFrame(int frame, volume::VoxelType target, void* destination) {
    Impl& d = *m_impl;
    const InstanceInfo& info = d.info;
    if (!info.hasPixelData)
        d.fail(frame, "no pixel data");
    if (frame < 0 || frame >= info.numberOfFrames)
        d.fail(frame, "frame index out of range");
    if (info.rows <= 0 || info.columns <= 0)
        d.fail(frame, "Rows or Columns missing or zero");
    if (info.samplesPerPixel != 1)
        d.fail(frame, "colour images (" + info.photometricInterpretation + ") are not supported");
    if (info.bitsAllocated != 8 && info.bitsAllocated != 16)
        d.fail(frame, "unsupported BitsAllocated " + std::to_string(info.bitsAllocated));
    if (target == volume::VoxelType::Float32)
        d.fail(frame, "decoding into float32 is not supported");
    if (!d.loaded)
        d.load(frame);

    const std::size_t pixelCount = std::size_t(info.rows) * std::size_t(info.columns);
    const std::size_t sampleBytes = std::size_t(info.bitsAllocated / 8);
    const void* samples = d.frameSamples(frame, pixelCount * sampleBytes);

    // Stored value: the bits [highBit - bitsStored + 1, highBit] of each sample. Bits outside
    // are not part of the value (overlays, garbage in dcm_qa_12bit) and are dropped.
    int bits = std::clamp(d.bitsStored, 1, info.bitsAllocated);
    int high = d.highBit;
    if (high < bits - 1 || high >= info.bitsAllocated)
        high = bits - 1; // an impossible HighBit: assume the usual low-aligned layout
    const int shift = high - bits + 1;
    const std::uint32_t mask = bits >= 32 ? 0xFFFFFFFFu : ((1u << bits) - 1u);
    const bool isSigned = info.pixelRepresentation == 1;
    const std::int32_t signBit = std::int32_t(1u << (bits - 1));
    const bool invert = info.photometricInterpretation == "MONOCHROME1";
    // MONOCHROME1: the brightest value is the lowest; mirror within the stored range so the
    // volume reads like MONOCHROME2 (min + max - v, i.e. -1 - v for signed values).
    const std::int32_t mirror = isSigned ? -1 : std::int32_t(mask);

    auto storedAt = [&](std::size_t i) -> std::int32_t {
        const std::uint32_t raw = sampleBytes == 2 ? static_cast<const Uint16*>(samples)[i]
                                                   : static_cast<const Uint8*>(samples)[i];
        std::int32_t value = std::int32_t((raw >> shift) & mask);
        if (isSigned && (value & signBit))
            value -= 2 * signBit;
        return invert ? mirror - value : value;
    };

    switch (target) {
    case volume::VoxelType::UInt8: {
        auto* out = static_cast<std::uint8_t*>(destination);
        for (std::size_t i = 0; i < pixelCount; ++i)
            out[i] = clampTo<std::uint8_t>(storedAt(i));
        break;
    }
    case volume::VoxelType::Int16: {
        auto* out = static_cast<std::int16_t*>(destination);
        for (std::size_t i = 0; i < pixelCount; ++i)
            out[i] = clampTo<std::int16_t>(storedAt(i));
        break;
    }
    case volume::VoxelType::UInt16: {
        auto* out = static_cast<std::uint16_t*>(destination);
        for (std::size_t i = 0; i < pixelCount; ++i)
            out[i] = clampTo<std::uint16_t>(storedAt(i));
        break;
    }
    case volume::VoxelType::Float32:
        break;
    }
}

} // namespace lw::dicom
