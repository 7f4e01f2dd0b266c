#pragma once

// How the review arranges its panels, chosen on its view bar (not on the settings page) and
// remembered in QSettings ("review/layout", "review/largeSlice") for the next review:
//
//   Surfaces             SurfacesAndSlices             SilhouetteAndSlice
//   +-------+-------+    +-------+-------+             +-----------+-----------+
//   |  iso  | silh. |    |  iso  | silh. |             | silhouette|  one large|
//   |       |       |    +----+----+-----+             |           |  slice    |
//   +-------+-------+    | ax | co | sag |             +-----------+-----------+
//                        +----+----+-----+

#include "lw/volume/slice_plane.h"

class QSettings;

namespace lw::gui {

enum class ReviewLayout { Surfaces, SurfacesAndSlices, SilhouetteAndSlice };

struct ReviewLayoutChoice {
    ReviewLayout layout = ReviewLayout::Surfaces;
    volume::SliceOrientation largeSlice = volume::SliceOrientation::Axial; // SilhouetteAndSlice

    static ReviewLayoutChoice load(QSettings& settings);
    void save(QSettings& settings) const;
    friend bool operator==(const ReviewLayoutChoice&, const ReviewLayoutChoice&) = default;
};

} // namespace lw::gui
