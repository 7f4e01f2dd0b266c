#pragma once

// What the slice views draw, in Qt terms: window/level (the grey ramp over real values, HU for
// CT) and its standard presets, a resampled slice as a grey QImage under a window, and the
// text of a patient point as radiologists read it.

#include "lw/volume/slice_plane.h"

#include <QImage>
#include <QString>
#include <glm/glm.hpp>

namespace lw::gui {

// The grey ramp: values below level - width/2 black, above level + width/2 white.
struct WindowLevel {
    double width = 400.0;
    double level = 40.0;
    friend bool operator==(const WindowLevel&, const WindowLevel&) = default;
};

// Radiopaedia's standard CT windows (W/L in HU): bone 1800/400, soft tissue 400/40,
// lung 1500/-600, brain 80/40.
enum class WindowPreset { Bone, SoftTissue, Lung, Brain };
constexpr WindowPreset kWindowPresets[] = {WindowPreset::Bone, WindowPreset::SoftTissue,
                                           WindowPreset::Lung, WindowPreset::Brain};
WindowLevel windowPreset(WindowPreset preset);
QString windowPresetName(WindowPreset preset); // translated

// The slice's values under `window` as 8-bit grey; NaN (outside the volume) black.
QImage windowedImage(const volume::SliceImage& slice, WindowLevel window);

// "R 12.5 · A 3.0 · S 40.2 mm": LPS millimetres with the side each value lies on.
QString patientPointText(glm::dvec3 patient);
// The plane's position along its normal with the side it lies on ("S 12.5 mm" for axial).
QString slicePositionText(volume::SliceOrientation orientation, double position);
QString sliceOrientationTitle(volume::SliceOrientation orientation); // translated "Axial", ...

} // namespace lw::gui
