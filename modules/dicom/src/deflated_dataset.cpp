#include "deflated_dataset.h"

#include "dicom_dcmtk.h"
#include "element_walk.h"
#include "lw/core/error.h"

#include <algorithm>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcistrmb.h>
#include <dcmtk/dcmdata/dcistrmf.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <optional>
#include <string>
#include <zlib.h>

namespace lw::dicom {

namespace {

// Meta groups are small; longer values there are not read (they are never needed).
constexpr Uint32 kMetaMaxReadLength = 4096;
// The first inflated prefix a header read tries; grown fourfold while the header is longer.
constexpr std::size_t kFirstHeaderPrefix = std::size_t(64) << 10;

// Reads the meta group from `stream`; true when it names the deflated syntax, then `stream`
// stands where the deflated data set begins.
bool readMetaNamingDeflate(DcmInputStream& stream, DcmMetaInfo& meta) {
    meta.transferInit();
    const OFCondition status = meta.read(stream, EXS_Unknown, EGL_noChange, kMetaMaxReadLength);
    meta.transferEnd();
    return status.good() && getString(meta, DCM_TransferSyntaxUID) ==
                                UID_DeflatedExplicitVRLittleEndianTransferSyntax;
}

// Raw deflate (RFC 1951, as the transfer syntax specifies), inflated on demand so that a reader
// takes only as much as it needs and never more than its bound.
class RawInflater {
public:
    RawInflater(const std::byte* data, std::size_t size, std::string subject)
        : m_subject(std::move(subject)) {
        m_stream.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(data));
        m_stream.avail_in = uInt(std::min<std::size_t>(size, 1u << 30));
        m_remainingInput = size - m_stream.avail_in;
        if (inflateInit2(&m_stream, -MAX_WBITS) != Z_OK)
            throw core::Error(m_subject, "cannot start inflating the deflated data set");
    }
    ~RawInflater() { inflateEnd(&m_stream); }
    RawInflater(const RawInflater&) = delete;
    RawInflater& operator=(const RawInflater&) = delete;

    bool ended() const { return m_ended; }

    // Inflates into `out` until it holds `target` bytes or the stream ends.
    void inflateTo(std::vector<std::byte>& out, std::size_t target) {
        while (!m_ended && out.size() < target) {
            const std::size_t before = out.size();
            const std::size_t chunk = std::min<std::size_t>(target - before, 1u << 24);
            out.resize(before + chunk);
            m_stream.next_out = reinterpret_cast<Bytef*>(out.data() + before);
            m_stream.avail_out = uInt(chunk);
            if (m_stream.avail_in == 0 && m_remainingInput > 0)
                refillInput();
            const int status = inflate(&m_stream, Z_NO_FLUSH);
            out.resize(before + (chunk - m_stream.avail_out));
            if (status == Z_STREAM_END)
                m_ended = true;
            else if (status == Z_BUF_ERROR && m_stream.avail_in == 0 && m_remainingInput == 0)
                m_ended = true; // no end marker: DCMTK accepts a stream cut after the last element
            else if (status != Z_OK && status != Z_BUF_ERROR)
                throw core::Error(m_subject, std::string("corrupt deflated data set: ") +
                                                 (m_stream.msg ? m_stream.msg : "inflate failed"));
        }
    }

private:
    void refillInput() {
        const std::size_t next = std::min<std::size_t>(m_remainingInput, 1u << 30);
        m_stream.avail_in = uInt(next);
        m_remainingInput -= next;
    }

    z_stream m_stream{};
    std::size_t m_remainingInput = 0;
    bool m_ended = false;
    std::string m_subject;
};

// Parses `bytes` as an explicit VR little endian data set, stopping in front of the pixel data
// when `stopAtPixelData`. Returns the condition and how many bytes were consumed. Unless
// `complete`, the bytes are a prefix: DCMTK then answers EC_StreamNotifyClient where they end
// inside an element (with the end of stream set it would call that an invalid stream, which
// could not be told from damage).
OFCondition parseDataset(const std::vector<std::byte>& bytes, DcmDataset& dataset,
                         bool stopAtPixelData, bool complete, std::size_t& consumed) {
    dataset.clear();
    DcmInputBufferStream stream;
    stream.setBuffer(bytes.data(), offile_off_t(bytes.size()));
    if (complete)
        stream.setEos();
    dataset.transferInit();
    const OFCondition status =
        dataset.readUntilTag(stream, EXS_LittleEndianExplicit, EGL_noChange, DCM_MaxReadLength,
                             stopAtPixelData ? DCM_PixelData : DCM_UndefinedTagKey);
    dataset.transferEnd();
    consumed = std::size_t(stream.tell());
    return status;
}

// DCMTK stops right after the header (tag, VR, reserved, 32-bit length) of the first top-level
// element at or past (7FE0,0010); when that element is the pixel data, its declared length.
std::optional<std::uint64_t> pixelDataHeaderBefore(const std::vector<std::byte>& bytes,
                                                   std::size_t end) {
    if (end < 12 || end > bytes.size())
        return std::nullopt;
    const auto* header = reinterpret_cast<const unsigned char*>(bytes.data() + end - 12);
    const bool isPixelData =
        header[0] == 0xE0 && header[1] == 0x7F && header[2] == 0x10 && header[3] == 0x00;
    if (!isPixelData)
        return std::nullopt;
    return std::uint64_t(header[8]) | std::uint64_t(header[9]) << 8 |
           std::uint64_t(header[10]) << 16 | std::uint64_t(header[11]) << 24;
}

// How many inflated bytes the elements in front of the pixel data need: more than `bytes` holds
// when one of them declares a value running past the prefix. DCMTK allocates a declared length
// before reading the value, so a prefix is parsed only once it holds every value it declares
// (4 GB from a 16 KB file otherwise). Throws when the stream ended short of a declaration or
// the declaration is past the import limit.
std::size_t bytesTheHeaderDeclares(const std::vector<std::byte>& bytes, bool streamEnded,
                                   const std::string& subject, const core::ImportLimits& limits) {
    const ElementWalk walk = walkElementHeaders(bytes, true);
    if (walk.stop != ElementWalk::Stop::Overrun)
        return bytes.size();
    if (streamEnded)
        throw core::Error(subject,
                          "damaged deflated data set: " + walk.overrunComplaint(bytes.size()));
    limits.checkBytes(std::size_t(walk.declaredEnd), subject,
                      "an element of the deflated data set in front of the pixel data");
    return std::size_t(walk.declaredEnd);
}

// Inflates until the data set parses up to its pixel data (or to its end), growing the
// inflated prefix fourfold each time, at most limits.maxBytes: the header of a deflated file is
// read without inflating its pixels. Returns how many inflated bytes the header took.
std::size_t inflateHeader(RawInflater& inflater, std::vector<std::byte>& bytes, DcmDataset& dataset,
                          DeflatedRead& result, const std::string& subject,
                          const core::ImportLimits& limits) {
    std::size_t target = std::min(kFirstHeaderPrefix, limits.maxBytes);
    for (;;) {
        inflater.inflateTo(bytes, target);
        const std::size_t declared =
            bytesTheHeaderDeclares(bytes, inflater.ended(), subject, limits);
        if (declared > bytes.size()) {
            target = declared;
            continue;
        }
        std::size_t consumed = 0;
        const OFCondition status = parseDataset(bytes, dataset, true, inflater.ended(), consumed);
        // A prefix ends inside an element (DCMTK: "notify client"); any other failure is damage
        // that more bytes cannot mend, so a bomb behind a broken header is not inflated first.
        if (status.bad() && status != EC_StreamNotifyClient)
            throw core::Error(subject,
                              std::string("cannot parse the deflated data set: ") + status.text());
        if (status.good() || inflater.ended()) {
            if (status.bad())
                throw core::Error(subject,
                                  "the deflated data set ends before its last element (truncated)");
            result.pixelDataLength = pixelDataHeaderBefore(bytes, consumed);
            result.pixelDataSkipped = result.pixelDataLength.has_value();
            return consumed;
        }
        if (bytes.size() >= limits.maxBytes)
            limits.checkBytes(bytes.size() + 1, subject,
                              "the deflated data set in front of the pixel data");
        target = std::min(target * 4, limits.maxBytes);
    }
}

// The whole data set, inflated no further than the header's share plus what it declares.
void inflateWhole(RawInflater& inflater, std::vector<std::byte>& bytes, std::size_t headerBytes,
                  std::optional<std::size_t> expectedPixelBytes, const std::string& subject,
                  const core::ImportLimits& limits) {
    const std::size_t bound =
        expectedPixelBytes
            ? std::min(limits.maxBytes, headerBytes + core::inflateBound(*expectedPixelBytes))
            : limits.maxBytes;
    inflater.inflateTo(bytes, bound);
    if (inflater.ended())
        return;
    // One byte more tells a stream that ends exactly at the bound from one that goes on.
    std::vector<std::byte> probe;
    inflater.inflateTo(probe, 1);
    if (!probe.empty())
        throw core::Error(
            subject, "the deflated data set inflates to more than " + std::to_string(bound >> 20) +
                         " MB, more than its header declares or the import limit allows");
}

} // namespace

bool isDeflatedFile(const std::string& path) {
    DcmInputFileStream stream(OFFilename(path.c_str()));
    if (stream.status().bad())
        return false;
    DcmMetaInfo meta;
    return readMetaNamingDeflate(stream, meta);
}

std::optional<DeflatedRead> readIfDeflated(const std::vector<std::byte>& fileBytes,
                                           DcmFileFormat& file, bool headerOnly,
                                           std::optional<std::size_t> expectedPixelBytes,
                                           const std::string& subject,
                                           const core::ImportLimits& limits) {
    if (fileBytes.empty())
        return std::nullopt;
    file.clear();
    DcmInputBufferStream metaStream;
    metaStream.setBuffer(fileBytes.data(), offile_off_t(fileBytes.size()));
    metaStream.setEos();
    if (!readMetaNamingDeflate(metaStream, *file.getMetaInfo()))
        return std::nullopt;
    const std::size_t datasetStart = std::size_t(metaStream.tell());

    RawInflater inflater(fileBytes.data() + datasetStart, fileBytes.size() - datasetStart, subject);
    std::vector<std::byte> bytes;
    DcmDataset& dataset = *file.getDataset();
    DeflatedRead result;
    const std::size_t headerBytes =
        inflateHeader(inflater, bytes, dataset, result, subject, limits);
    if (headerOnly)
        return result;

    inflateWhole(inflater, bytes, headerBytes, expectedPixelBytes, subject, limits);
    // The rule DCMTK does not apply to data sets in memory: no value longer than the bytes left.
    const ElementWalk walk = walkElementHeaders(bytes, false);
    if (walk.stop == ElementWalk::Stop::Overrun)
        throw core::Error(subject,
                          "damaged deflated data set: " + walk.overrunComplaint(bytes.size()));
    std::size_t consumed = 0;
    const OFCondition status = parseDataset(bytes, dataset, false, true, consumed);
    if (status.bad()) {
        const std::string detail =
            status == EC_StreamNotifyClient
                ? "the deflated data set ends before its last element (truncated)"
                : std::string("cannot parse the deflated data set: ") + status.text();
        throw core::Error(subject, detail);
    }
    return DeflatedRead{};
}

} // namespace lw::dicom
