#pragma once

// The review's slice panels in its exports, when its layout shows them: each slice as the view
// shows it now (its image under the window, fitted and centred on black, its iso contour) with
// the annotations its slice shows burned in (report::burnInSliceAnnotations), joined to the
// picture of the 3D panels the way the review lays them out:
//
//   SurfacesAndSlices: the 3D picture above,        SilhouetteAndSlice: the large slice to
//   the axial, coronal and sagittal slices below     the right of the 3D picture, as large as
//   (square, a third of its width each)              one of its panels
//
// The slices are raster images in every format (the PDF's vector lines are the silhouette's
// alone): a slice is a picture of voxels, and its contour is drawn at the export's size.

#include "lw/annotation/annotation.h"

#include <QColor>
#include <QImage>
#include <QSize>
#include <vector>

namespace lw::gui {

class ReviewWidget;
class SliceView;

// The slice `view` shows, fitted into `size` (the view's zoom and pan left out: the whole slice).
QImage renderSlicePanel(const SliceView& view, QSize size,
                        const std::vector<annotation::Annotation>& annotations);

struct SlicePanels {
    std::vector<QImage> images; // left to right
    bool below = false;         // below the 3D picture (else to its right)
};

// The slices `review`'s layout shows, for a 3D picture of `pictureSize` made of panels of
// `panelSize`; none in the Surfaces layout or before a slice has arrived.
SlicePanels slicePanelsOf(ReviewWidget& review, QSize panelSize, QSize pictureSize,
                          const std::vector<annotation::Annotation>& annotations);

// The 3D picture with the slice panels joined (the picture alone when there are none); the 3D
// picture stays at the top-left, so pixel positions in it stay valid.
QImage withSlicePanels(const QImage& picture, const SlicePanels& slices, QColor background);

} // namespace lw::gui
