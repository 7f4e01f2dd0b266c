#pragma once

// Burning annotations into a rendered panel: the anchors are projected through the camera the
// panel was rendered with, and lines, arrow heads and text are drawn with QPainter at a size
// that scales with the image (an export at 4x the window has 4x thicker lines and larger text,
// so the picture looks the same printed at any resolution).

#include "lw/annotation/annotation.h"
#include "lw/annotation/annotation_projection.h"
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

// Draws one annotation already projected into the painter's pixel coordinates (a slice panel's:
// annotation::projectAnnotation through its patient-to-pixel mapping), as drawAnnotation does.
void drawProjectedAnnotation(QPainter& painter, const annotation::ProjectedAnnotation& projected,
                             double scale, const OverlayStyle& style = {});

// The slice a slice panel shows, and where its pixels are in patient coordinates.
struct SlicePanelFrame {
    annotation::SliceOrientation orientation = annotation::SliceOrientation::Axial;
    double positionMm = 0.0;            // annotation::slicePositionOf of the plane
    double spacingMm = 1.0;             // between the view's slices
    annotation::PatientToPixel toPixel; // the panel's pixel for a patient point
};

// Draws over a slice panel the annotations that show on its slice (annotation::showsOnSlice:
// those placed on it or within half a spacing of it, and 3D ones lying in that slab).
void burnInSliceAnnotations(QImage& panel, const std::vector<annotation::Annotation>& annotations,
                            const SlicePanelFrame& slice, const OverlayStyle& style = {});

// How many pixels one reference pixel is in an image of `height` (lines and text scale by it).
double overlayScale(int height, const OverlayStyle& style = {});

} // namespace lw::report
