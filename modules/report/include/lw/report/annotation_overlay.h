#pragma once

// Burning annotations into a rendered panel: the anchors are projected through the camera the
// panel was rendered with, and lines, arrow heads and text are drawn with QPainter at a size
// that scales with the image (an export at 4x the window has 4x thicker lines and larger text,
// so the picture looks the same printed at any resolution).

#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"

#include <QColor>
#include <QImage>
#include <QPainter>
#include <vector>

namespace lw::report {

struct OverlayStyle {
    QColor colour{230, 80, 0};       // orange: visible on the white page and the grey surface
    QColor halo{255, 255, 255, 200}; // behind text, so it reads over lines and surface
    double referenceHeight = 512.0;  // image height at which the sizes below apply
    double lineWidth = 2.0;          // px at the reference height
    double fontPixelSize = 16.0;     // px at the reference height
};

// Draws `annotations` over `panel`, which was rendered with `camera` (same viewport size).
// Annotations with an anchor behind the eye are skipped.
void burnInAnnotations(QImage& panel, const std::vector<annotation::Annotation>& annotations,
                       const render::Camera& camera, const OverlayStyle& style = {});

// Draws one annotation with `painter` in the camera's pixel coordinates, sizes multiplied by
// `scale`: the same shapes the burn-in makes, for the workstation's live overlay.
void drawAnnotation(QPainter& painter, const annotation::Annotation& annotation,
                    const render::Camera& camera, double scale, const OverlayStyle& style = {});

// How many pixels one reference pixel is in an image of `height` (lines and text scale by it).
double overlayScale(int height, const OverlayStyle& style = {});

} // namespace lw::report
