#pragma once

// Method 2's visibility answers by point, for one chunk of segments on one thread: neighbouring
// segments meet end to end at bit-identical points (silhouetteSegment computes an edge's crossing
// alike from both triangles), so each point would otherwise cast its ray twice. Open addressing
// on the point's bits; the answer of a point is the rule's, so the memo changes no image. The
// CUDA back-end does the same with a table on the device.

#include "lw/kernels/point_hash.h"

#include <bit>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::render {

class PointVisibilityMemo {
public:
    // Empties the memo for up to `points` points (storage kept between frames).
    void reset(std::size_t points) {
        std::size_t slots = 64;
        while (slots < 2 * points)
            slots *= 2;
        m_entries.assign(slots, Entry{});
        m_mask = slots - 1;
    }

    // The memo's answer for `p`, or visibleOf(p) computed once and kept.
    template <typename VisibleOf> bool visible(glm::vec3 p, VisibleOf&& visibleOf) {
        const Key key{std::bit_cast<std::uint32_t>(p.x), std::bit_cast<std::uint32_t>(p.y),
                      std::bit_cast<std::uint32_t>(p.z)};
        for (std::size_t slot = hash(key) & m_mask;; slot = (slot + 1) & m_mask) {
            Entry& entry = m_entries[slot];
            if (entry.state == kEmpty) {
                entry.key = key;
                entry.state = visibleOf(glm::dvec3(p)) ? kVisible : kHidden;
                return entry.state == kVisible;
            }
            if (entry.key == key)
                return entry.state == kVisible;
        }
    }

private:
    struct Key {
        std::uint32_t x = 0, y = 0, z = 0;
        friend bool operator==(const Key&, const Key&) = default;
    };
    static constexpr std::uint8_t kEmpty = 0, kVisible = 1, kHidden = 2;
    struct Entry {
        Key key;
        std::uint8_t state = kEmpty;
    };
    static std::size_t hash(const Key& k) {
        return std::size_t(kernels::pointBitsHash(k.x, k.y, k.z));
    }

    std::vector<Entry> m_entries;
    std::size_t m_mask = 0;
};

} // namespace lw::render
