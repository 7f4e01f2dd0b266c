#include "element_walk.h"

#include <cstdio>
#include <dcmtk/dcmdata/dctag.h>
#include <dcmtk/dcmdata/dcvr.h>
#include <limits>
#include <optional>

namespace lw::dicom {

namespace {

constexpr std::uint32_t kUndefinedLength = 0xFFFFFFFF;
constexpr std::size_t kOpenEnded = std::numeric_limits<std::size_t>::max();

std::uint32_t littleEndian(const std::byte* p, int bytes) {
    std::uint32_t value = 0;
    for (int i = bytes - 1; i >= 0; --i)
        value = value << 8 | std::uint32_t(p[i]);
    return value;
}

// One header as DCMTK's DcmItem::readTagAndLength reads it in explicit VR little endian.
struct Header {
    std::uint16_t group = 0;
    std::uint16_t element = 0;
    std::size_t bytes = 8; // tag, VR and length fields
    std::uint32_t length = 0;
    bool hasVr = true; // items and delimiters have none
    bool isSequence = false;

    bool is(std::uint16_t g, std::uint16_t e) const { return group == g && element == e; }
    bool definedLength() const { return length != kUndefinedLength; }
};

// The header at `at`, or nothing when the bytes end inside it. The length field's width comes
// from DCMTK's own VR table, so an unknown VR ("ZZ") is read with the 4-byte length DCMTK gives
// it, not guessed.
std::optional<Header> readHeader(const std::vector<std::byte>& bytes, std::size_t at) {
    if (bytes.size() - at < 8)
        return std::nullopt;
    const std::byte* p = bytes.data() + at;
    Header header;
    header.group = std::uint16_t(littleEndian(p, 2));
    header.element = std::uint16_t(littleEndian(p + 2, 2));
    header.hasVr = DcmTag(header.group, header.element).getEVR() != EVR_na;
    if (!header.hasVr) {
        header.length = littleEndian(p + 4, 4);
        return header;
    }
    const char vrName[3] = {char(p[4]), char(p[5]), '\0'};
    const DcmVR vr(vrName);
    header.isSequence = vr.getEVR() == EVR_SQ;
    if (!vr.usesExtendedLengthEncoding()) {
        header.length = littleEndian(p + 6, 2);
        return header;
    }
    if (bytes.size() - at < 12)
        return std::nullopt;
    header.bytes = 12;
    header.length = littleEndian(p + 8, 4);
    return header;
}

// The sequences and items the walk is inside, innermost last; each knows where it ends.
class OpenContainers {
public:
    enum class Kind { Sequence, Item, PixelSequence };

    bool topLevel() const { return m_open.empty(); }
    bool inPixelSequence() const {
        return !topLevel() && m_open.back().kind == Kind::PixelSequence;
    }
    void open(Kind kind, std::size_t end) { m_open.push_back({kind, end}); }

    // Containers of defined length end where their length says.
    void closeEndedAt(std::size_t at) {
        while (!topLevel() && m_open.back().end != kOpenEnded && at >= m_open.back().end)
            m_open.pop_back();
    }
    // A delimiter closes only the undefined-length container it belongs to; a stray one is
    // ignored, which keeps the walk at the deeper level (it then checks more, never less).
    void closeByDelimiter(const Header& header) {
        if (topLevel() || m_open.back().end != kOpenEnded)
            return;
        const Kind kind = m_open.back().kind;
        const bool closesItem = header.element == 0xE00D && kind == Kind::Item;
        const bool closesSequence = header.element == 0xE0DD && kind != Kind::Item;
        if (closesItem || closesSequence)
            m_open.pop_back();
    }

private:
    struct Open {
        Kind kind;
        std::size_t end;
    };
    std::vector<Open> m_open;
};

} // namespace

std::string ElementWalk::overrunComplaint(std::size_t available) const {
    char tag[16];
    std::snprintf(tag, sizeof tag, "(%04X,%04X)", unsigned(group), unsigned(element));
    const std::size_t follow = available > valueAt ? available - valueAt : 0;
    return "element " + std::string(tag) + " declares " + std::to_string(declaredEnd - valueAt) +
           " bytes, but only " + std::to_string(follow) + " follow";
}

ElementWalk walkElementHeaders(const std::vector<std::byte>& bytes, bool stopAtPixelData) {
    using Kind = OpenContainers::Kind;
    OpenContainers open;
    std::size_t at = 0;
    while (true) {
        open.closeEndedAt(at);
        const std::optional<Header> header = readHeader(bytes, at);
        if (!header)
            return {};
        if (stopAtPixelData && open.topLevel() && header->hasVr &&
            (header->group > 0x7FE0 || (header->group == 0x7FE0 && header->element >= 0x0010)))
            return {ElementWalk::Stop::TopLevelPixelData};
        const std::size_t valueAt = at + header->bytes;
        const std::size_t containerEnd =
            header->definedLength() ? valueAt + header->length : kOpenEnded;
        if (!header->hasVr && !header->is(0xFFFE, 0xE000)) {
            open.closeByDelimiter(*header);
            at = valueAt;
            continue;
        }
        const bool isItem = !header->hasVr;
        if ((isItem && !open.inPixelSequence()) || header->isSequence) {
            open.open(isItem ? Kind::Item : Kind::Sequence, containerEnd);
            at = valueAt;
            continue;
        }
        if (!header->definedLength()) {
            if (!header->is(0x7FE0, 0x0010) || open.inPixelSequence())
                return {ElementWalk::Stop::Opaque}; // implicit VR inside: DCMTK parses it
            open.open(Kind::PixelSequence, kOpenEnded);
            at = valueAt;
            continue;
        }
        if (header->length > bytes.size() - valueAt)
            return {ElementWalk::Stop::Overrun, header->group, header->element, valueAt,
                    std::uint64_t(valueAt) + header->length};
        at = valueAt + header->length;
    }
}

} // namespace lw::dicom
