#include "lw/core/image.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace lw::core {

namespace {

void checkSize(int width, int height) {
    if (width < 0 || height < 0)
        throw Error("image",
                    "invalid size " + std::to_string(width) + "x" + std::to_string(height));
}

template <typename T> void flipRowsOf(std::vector<T>& pixels, int width, int height) {
    for (int top = 0, bottom = height - 1; top < bottom; ++top, --bottom)
        std::swap_ranges(pixels.begin() + std::ptrdiff_t(top) * width,
                         pixels.begin() + std::ptrdiff_t(top + 1) * width,
                         pixels.begin() + std::ptrdiff_t(bottom) * width);
}

} // namespace

ImageRgba8::ImageRgba8(int width, int height, Rgba8 fill) {
    checkSize(width, height);
    m_width = width;
    m_height = height;
    m_pixels.assign(std::size_t(width) * std::size_t(height), fill);
}

void ImageRgba8::fill(Rgba8 colour) {
    std::fill(m_pixels.begin(), m_pixels.end(), colour);
}

void ImageRgba8::flipRows() {
    flipRowsOf(m_pixels, m_width, m_height);
}

ImageFloat::ImageFloat(int width, int height, float fill) {
    checkSize(width, height);
    m_width = width;
    m_height = height;
    m_pixels.assign(std::size_t(width) * std::size_t(height), fill);
}

void ImageFloat::fill(float value) {
    std::fill(m_pixels.begin(), m_pixels.end(), value);
}

void ImageFloat::flipRows() {
    flipRowsOf(m_pixels, m_width, m_height);
}

ImageRgba8 ImageFloat::toGrey(float low, float high, Rgba8 invalid) const {
    ImageRgba8 out(m_width, m_height);
    const float range = high - low;
    for (std::size_t i = 0; i < m_pixels.size(); ++i) {
        const float v = m_pixels[i];
        if (!std::isfinite(v)) {
            out.pixels()[i] = invalid;
            continue;
        }
        const float t = range != 0.0f ? std::clamp((v - low) / range, 0.0f, 1.0f) : 0.0f;
        const auto grey = static_cast<std::uint8_t>(std::lround(t * 255.0f));
        out.pixels()[i] = {grey, grey, grey, 255};
    }
    return out;
}

} // namespace lw::core
