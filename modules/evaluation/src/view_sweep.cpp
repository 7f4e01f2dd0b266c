#include "lw/evaluation/view_sweep.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace lw::evaluation {

namespace {

double roundToTenth(double degrees) {
    const double rounded = std::round(degrees * 10.0) / 10.0;
    return rounded == 0.0 ? 0.0 : rounded; // no "-0" in names and JSON
}

// The inverse of the camera's eye direction (sin az cos el, -cos az cos el, sin el).
View viewToward(double x, double y, double z) {
    const double degrees = 180.0 / std::numbers::pi;
    const double horizontal = std::hypot(x, y);
    const double length = std::hypot(horizontal, z);
    View view;
    view.elevationDeg = roundToTenth(std::asin(z / length) * degrees);
    // At a pole the azimuth only turns the picture; 0 keeps screen up posterior.
    if (horizontal > 1e-12 * length)
        view.azimuthDeg = roundToTenth(std::atan2(x, -y) * degrees);
    if (view.azimuthDeg <= -180.0)
        view.azimuthDeg += 360.0;
    return view;
}

// Faces first (the six standard views), then edges, then corners: a short sweep (`--views 6`)
// is still meaningful.
std::vector<View> cubeViews() {
    std::vector<View> views;
    for (int nonZero = 1; nonZero <= 3; ++nonZero)
        for (int z = -1; z <= 1; ++z)
            for (int y = -1; y <= 1; ++y)
                for (int x = -1; x <= 1; ++x)
                    if (std::abs(x) + std::abs(y) + std::abs(z) == nonZero)
                        views.push_back(viewToward(x, y, z));
    return views;
}

} // namespace

std::vector<View> viewSweep(int count, std::uint32_t seed) {
    if (count < 1)
        throw core::Error("view sweep", "needs at least one view, got " + std::to_string(count));
    std::vector<View> views = cubeViews();
    views.resize(std::min<std::size_t>(views.size(), std::size_t(count)));
    // Uniform on the sphere: z uniform in [-1, 1], the angle about z uniform (Archimedes). The raw
    // engine output is converted here because std::uniform_real_distribution differs between
    // standard libraries.
    std::mt19937 random(seed);
    const auto unit = [&] { return double(random()) / 4294967296.0; };
    while (int(views.size()) < count) {
        const double z = 2.0 * unit() - 1.0;
        const double angle = 2.0 * std::numbers::pi * unit();
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        views.push_back(viewToward(r * std::cos(angle), r * std::sin(angle), z));
    }
    return views;
}

} // namespace lw::evaluation
