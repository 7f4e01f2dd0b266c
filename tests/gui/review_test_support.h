#pragma once

// What the review tests share: a phantom opened as the loader opens it, settings for a method
// and where its GL runs, waiting for the worker to settle and for the slices to show.

#include "gui_test_support.h"
#include "review/review_widget.h"
#include "review/slice_view.h"
#include "review/slice_views.h"
#include "review/volume_loader.h"

#include <QTest>
#include <cstdint>

namespace lw::test {

inline gui::ReviewSource phantomSource(const QString& spec, double iso) {
    gui::LoadRequest request;
    request.path = spec;
    request.iso = iso;
    return gui::VolumeLoader::load(request, nullptr);
}

// Waits until the worker is idle and at least `frames` results have been shown.
inline bool waitSettled(gui::ReviewWidget& review, std::uint64_t frames = 1,
                        int timeoutMs = 60000) {
    return waitUntil([&] { return !review.isBusy() && review.status().framesShown >= frames; },
                     timeoutMs);
}

// Whether the active slice view of `orientation` shows the slice it asks for, at the slices'
// iso-value (an inactive view counts as shown).
inline bool showsCurrentSlice(gui::ReviewWidget& review, volume::SliceOrientation orientation) {
    if (!review.slices().isActive(orientation))
        return true;
    const gui::SliceView& view = review.slices().view(orientation);
    const gui::SliceResult* slice = view.slice();
    return slice && slice->image && slice->image->position == view.position() &&
           slice->iso == review.slices().iso();
}

// Waits until no slice is being sampled and every active slice view shows its current slice.
inline bool waitSlices(gui::ReviewWidget& review, int timeoutMs = 30000) {
    return waitUntil(
        [&] {
            return !review.slices().isBusy() &&
                   showsCurrentSlice(review, volume::SliceOrientation::Axial) &&
                   showsCurrentSlice(review, volume::SliceOrientation::Coronal) &&
                   showsCurrentSlice(review, volume::SliceOrientation::Sagittal);
        },
        timeoutMs);
}

inline gui::ReviewSettings settingsFor(int method, gui::Chunking chunking,
                                       gui::PanelGl panelGl = gui::PanelGl::Auto) {
    gui::ReviewSettings settings;
    settings.panelGl = panelGl;
    settings.method = render::SilhouetteMethod(method);
    settings.chunking = chunking;
    settings.fixedBrickCells = 16;
    // The tests' 64^3 phantom as loaded: its baseline and counts are of its own grid (under the
    // default, Auto, its unit cells are coarse enough to be split; oversamplingRefinesTheMesh).
    settings.oversampling = render::Oversampling::Off;
    return settings;
}

} // namespace lw::test
