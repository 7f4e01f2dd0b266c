#include "dicom_dcmtk.h"
#include "dicom_file.h"

#include "lw/core/error.h"
#include "lw/core/log.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcpixel.h>
#include <dcmtk/dcmdata/dcpixseq.h>
#include <dcmtk/dcmdata/dcpxitem.h>
#include <dcmtk/dcmdata/dcrledrg.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/dcmjpeg/djdecode.h>
#include <dcmtk/dcmjpls/djdecode.h>

#ifdef LINEWORK_HAVE_GDCM
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmTrace.h>
#endif

#include <dlfcn.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mutex>
#include <sstream>

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

void ensureDecoders() { static DecoderRegistration registration; }

bool isJpeg2000(const std::string& uid) {
    return uid == "1.2.840.10008.1.2.4.90" || uid == "1.2.840.10008.1.2.4.91" ||
           uid == "1.2.840.10008.1.2.4.92" || uid == "1.2.840.10008.1.2.4.93";
}

// Precision and signedness of the first component, from the SIZ marker of a JPEG 2000
// codestream (raw or inside a JP2 box). The DICOM header can disagree with it (pydicom's
// 693_* and J2K_pixelrep_mismatch files); the codestream is what the decoder produced.
struct CodestreamPrecision {
    int bits = 0;
    bool isSigned = false;
};

std::optional<CodestreamPrecision> jpeg2000Precision(const Uint8* data, std::size_t size) {
    // SIZ: FF51, Lsiz, Rsiz, Xsiz..YTOsiz (8 x 4 bytes), Csiz, then Ssiz per component.
    constexpr std::size_t kSsizOffset = 2 + 2 + 2 + 8 * 4 + 2;
    for (std::size_t i = 0; i + 3 < size && i < 4096; ++i) {
        if (data[i] == 0xFF && data[i + 1] == 0x4F && data[i + 2] == 0xFF && data[i + 3] == 0x51) {
            const std::size_t siz = i + 2;
            if (siz + kSsizOffset >= size)
                return std::nullopt;
            const Uint8 ssiz = data[siz + kSsizOffset];
            return CodestreamPrecision{int(ssiz & 0x7F) + 1, (ssiz & 0x80) != 0};
        }
    }
    return std::nullopt;
}

#ifdef LINEWORK_HAVE_GDCM
// GDCM's global state (dictionaries, codec registry) is not documented as thread-safe for
// concurrent readers; JPEG 2000 files are rare enough that serialising them costs little.
std::mutex& gdcmMutex() {
    static std::mutex mutex;
    return mutex;
}
#endif

bool isJpegLs(const std::string& uid) {
    return uid == "1.2.840.10008.1.2.4.80" || uid == "1.2.840.10008.1.2.4.81";
}

// DCMTK 3.6.7 ships its own CharLS (libdcmtkcharls) and GDCM links the system CharLS 2; both
// export JpegLsDecode with different ABIs, and the dynamic linker binds every caller to
// whichever library was loaded first (link order). DCMTK's JPEG-LS codec is only safe when
// the symbol resolves to DCMTK's copy; otherwise GDCM (which then has its own) decodes JPEG-LS.
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

} // namespace

struct FrameDecoder::Impl {
    InstanceInfo info;
    core::ImportLimits limits;
    DcmFileFormat file;
    std::vector<std::byte> inflated; // gzip-wrapped files: the DICOM bytes
    bool loaded = false;

    // The whole pixel data in native form (after decompression where needed), host order.
    const Uint8* bytes8 = nullptr;
    const Uint16* words16 = nullptr;
    std::size_t byteLength = 0;
    std::vector<char> jpeg2000Buffer; // GDCM's output, owned here

    int bitsStored = 0; // effective: may follow the codestream where the header is wrong
    int highBit = 0;

    std::string where(int frame) const {
        return info.path + " (frame " + std::to_string(frame + 1) + " of " + std::to_string(info.numberOfFrames) + ")";
    }

    [[noreturn]] void fail(int frame, const std::string& reason) const { throw core::Error(where(frame), reason); }

    // What the header declares for the whole pixel data: a deflated data set may inflate to
    // little more than this (the header read checked it against the limits already).
    std::size_t declaredPixelBytes() const {
        return core::checkedProduct({std::size_t(std::max(info.rows, 0)), std::size_t(std::max(info.columns, 0)),
                                     std::size_t(std::max(info.numberOfFrames, 1)),
                                     std::size_t(std::max(info.samplesPerPixel, 1)),
                                     std::size_t(std::max(1, (info.bitsAllocated + 7) / 8))},
                                    info.path, "the pixel data the header declares");
    }

    void load(int frame);
    void loadJpeg2000(int frame, DcmPixelData& pixelData, E_TransferSyntax xfer);
    void loadWithGdcm(int frame);
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
    const std::string syntaxUid = info.transferSyntaxUid.empty() ? xferInfo.getXferID() : info.transferSyntaxUid;
    if (xferInfo.isEncapsulated() || isJpeg2000(syntaxUid)) {
        if (isJpeg2000(syntaxUid)) {
            loadJpeg2000(frame, *pixelData, xfer);
            loaded = true;
            return;
        }
        if (isJpegLs(syntaxUid) && !dcmtkJpegLsIsSafe()) {
            loadWithGdcm(frame);
            loaded = true;
            return;
        }
        // Decompress the whole object once: a multi-frame file is decoded a single time, and
        // DCMTK assembles frames split over several fragments itself.
        const OFCondition status = ds.chooseRepresentation(EXS_LittleEndianExplicit, nullptr);
        if (status.bad() || !ds.canWriteXfer(EXS_LittleEndianExplicit))
            fail(frame, "cannot decode " + std::string(xferInfo.getXferName()) + " (" + syntaxUid + ")" +
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

void FrameDecoder::Impl::loadJpeg2000(int frame, DcmPixelData& pixelData, E_TransferSyntax xfer) {
    // The codestream's own precision: where it disagrees with BitsStored, the header is the
    // one that is wrong (pydicom's 693_* files), and masking to it would cut off real bits.
    DcmPixelSequence* sequence = nullptr;
    if (pixelData.getEncapsulatedRepresentation(xfer, nullptr, sequence).good() && sequence &&
        sequence->card() > 1) {
        DcmPixelItem* item = nullptr;
        Uint8* fragment = nullptr;
        if (sequence->getItem(item, 1).good() && item && item->getUint8Array(fragment).good() && fragment) {
            if (auto precision = jpeg2000Precision(fragment, item->getLength())) {
                if (precision->bits != info.bitsStored) {
                    kLog.warning(info.path + ": BitsStored " + std::to_string(info.bitsStored) +
                                 " disagrees with the JPEG 2000 precision " + std::to_string(precision->bits) +
                                 "; using the codestream's");
                    bitsStored = precision->bits;
                    highBit = precision->bits - 1;
                }
                if (precision->isSigned != (info.pixelRepresentation == 1))
                    kLog.warning(info.path + ": PixelRepresentation disagrees with the JPEG 2000 codestream; "
                                             "values are read as the header says");
            }
        }
    }
    loadWithGdcm(frame);
}

void FrameDecoder::Impl::loadWithGdcm(int frame) {
#ifdef LINEWORK_HAVE_GDCM
    std::lock_guard lock(gdcmMutex());
    // GDCM prints its warnings (missing spacing, corrected bit depths) to stderr; the ones that
    // matter come back as a failed read and are reported with the file name.
    static const bool quiet = [] {
        gdcm::Trace::SetDebug(false);
        gdcm::Trace::SetWarning(false);
        gdcm::Trace::SetError(false);
        return true;
    }();
    (void)quiet;
    gdcm::ImageReader reader;
    std::istringstream memory;
    if (inflated.empty()) {
        reader.SetFileName(info.path.c_str());
    } else {
        memory.str(std::string(reinterpret_cast<const char*>(inflated.data()), inflated.size()));
        reader.SetStream(memory);
    }
    if (!reader.Read())
        fail(frame, "GDCM cannot read the file");
    const gdcm::Image& image = reader.GetImage();
    jpeg2000Buffer.resize(image.GetBufferLength());
    if (jpeg2000Buffer.empty() || !image.GetBuffer(jpeg2000Buffer.data()))
        fail(frame, "decoding " + info.transferSyntaxUid + " with GDCM failed");
    byteLength = jpeg2000Buffer.size();
    if (image.GetPixelFormat().GetBitsAllocated() != unsigned(info.bitsAllocated))
        fail(frame, "GDCM returned " + std::to_string(image.GetPixelFormat().GetBitsAllocated()) +
                        "-bit samples where BitsAllocated is " + std::to_string(info.bitsAllocated));
    if (info.bitsAllocated == 16)
        words16 = reinterpret_cast<const Uint16*>(jpeg2000Buffer.data());
    else
        bytes8 = reinterpret_cast<const Uint8*>(jpeg2000Buffer.data());
#else
    fail(frame, info.transferSyntaxUid + " is not supported in this build (GDCM was not found)");
#endif
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
    const std::size_t frameBytes = pixelCount * sampleBytes;
    const std::size_t needed = (std::size_t(frame) + 1) * frameBytes;
    if (d.byteLength < needed)
        d.fail(frame, "pixel data truncated: " + std::to_string(d.byteLength) + " bytes where " +
                          std::to_string(needed) + " are needed");

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
        const std::uint32_t raw = sampleBytes == 2 ? std::uint32_t(d.words16[std::size_t(frame) * pixelCount + i])
                                                   : std::uint32_t(d.bytes8[std::size_t(frame) * frameBytes + i]);
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
    case volume::VoxelType::Float32: break;
    }
}

} // namespace lw::dicom
