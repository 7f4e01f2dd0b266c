#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace lw::core {

struct Rgba8 {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;
    std::uint8_t a = 0;

    friend bool operator==(const Rgba8&, const Rgba8&) = default;
};
static_assert(sizeof(Rgba8) == 4,
              "Rgba8 must pack to 4 bytes so pixel rows can be handed to GL and PNG as-is");

// An 8-bit RGBA image, row-major with the top row first (the order PNG and screens use; GL
// read-backs come bottom-up and need flipRows()).
class ImageRgba8 {
public:
    ImageRgba8() = default;
    // Throws Error for negative sizes.
    ImageRgba8(int width, int height, Rgba8 fill = {0, 0, 0, 0});

    int width() const { return m_width; }
    int height() const { return m_height; }
    bool isEmpty() const { return m_pixels.empty(); }
    std::size_t pixelCount() const { return m_pixels.size(); }
    bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < m_width && y < m_height; }

    Rgba8& at(int x, int y) {
        return m_pixels[std::size_t(y) * std::size_t(m_width) + std::size_t(x)];
    }
    const Rgba8& at(int x, int y) const {
        return m_pixels[std::size_t(y) * std::size_t(m_width) + std::size_t(x)];
    }
    Rgba8* row(int y) { return m_pixels.data() + std::size_t(y) * std::size_t(m_width); }
    const Rgba8* row(int y) const {
        return m_pixels.data() + std::size_t(y) * std::size_t(m_width);
    }

    std::vector<Rgba8>& pixels() { return m_pixels; }
    const std::vector<Rgba8>& pixels() const { return m_pixels; }
    // Interleaved RGBA bytes (width * height * 4), for glReadPixels and the PNG writer.
    std::uint8_t* bytes() { return reinterpret_cast<std::uint8_t*>(m_pixels.data()); }
    const std::uint8_t* bytes() const {
        return reinterpret_cast<const std::uint8_t*>(m_pixels.data());
    }

    void fill(Rgba8 colour);
    // Reverses the row order (GL's origin is the bottom-left corner).
    void flipRows();

    friend bool operator==(const ImageRgba8&, const ImageRgba8&) = default;

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<Rgba8> m_pixels;
};

// A single-channel float image (depth buffers, distance maps), same layout as ImageRgba8.
class ImageFloat {
public:
    ImageFloat() = default;
    ImageFloat(int width, int height, float fill = 0.0f);

    int width() const { return m_width; }
    int height() const { return m_height; }
    bool isEmpty() const { return m_pixels.empty(); }
    bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < m_width && y < m_height; }

    float& at(int x, int y) {
        return m_pixels[std::size_t(y) * std::size_t(m_width) + std::size_t(x)];
    }
    float at(int x, int y) const {
        return m_pixels[std::size_t(y) * std::size_t(m_width) + std::size_t(x)];
    }
    std::vector<float>& pixels() { return m_pixels; }
    const std::vector<float>& pixels() const { return m_pixels; }

    void fill(float value);
    void flipRows();

    // Maps [low, high] linearly to grey 0..255 (clamped; NaN and infinities become `invalid`),
    // so a depth buffer can be looked at or stored as a PNG.
    ImageRgba8 toGrey(float low, float high, Rgba8 invalid = {0, 0, 0, 255}) const;

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<float> m_pixels;
};

} // namespace lw::core
