#pragma once

// Internal to lw::dicom: a walk over the element headers of an Explicit VR Little Endian data set
// held in memory (an inflated deflated data set), reading each header exactly as DCMTK will.
// DCMTK allocates an element's declared length before it reads the value, even when the bytes
// in memory end long before (4 GB from a 16 KB file): the walk finds such an element first.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lw::dicom {

// Where a walk stopped, and why.
struct ElementWalk {
    enum class Stop {
        End,              // every header visited (the bytes may end inside the last header)
        Overrun,          // an element declares more bytes than follow its header
        Opaque,           // a value of undefined length DCMTK reads as implicit VR: not followed
        TopLevelPixelData // the first top-level element at or past (7FE0,0010): DCMTK stops here
    };
    Stop stop = Stop::End;
    // Overrun: the element's tag, where its value starts, and where it would end.
    std::uint16_t group = 0;
    std::uint16_t element = 0;
    std::size_t valueAt = 0;
    std::uint64_t declaredEnd = 0;

    // "element (GGGG,EEEE) declares N bytes, but only M follow" for an overrun in `available`.
    std::string overrunComplaint(std::size_t available) const;
};

// Visits every element, item and delimiter header of `bytes` in order, entering sequences and
// items (a pixel sequence's items are values), and stops at the first element whose declared
// length runs past the end of `bytes`. With `stopAtPixelData` it stops where DCMTK's
// readUntilTag(PixelData) stops, so a header read never asks for the pixels.
ElementWalk walkElementHeaders(const std::vector<std::byte>& bytes, bool stopAtPixelData);

} // namespace lw::dicom
