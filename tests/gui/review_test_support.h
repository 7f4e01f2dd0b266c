#pragma once

// What the review tests share: a phantom opened as the loader opens it, settings for a method
// and where its GL runs, and waiting for the worker to settle.

#include "review/review_widget.h"
#include "review/volume_loader.h"

#include <QElapsedTimer>
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
    QElapsedTimer timer;
    timer.start();
    while (timer.elapsed() < timeoutMs) {
        QTest::qWait(20);
        if (!review.isBusy() && review.status().framesShown >= frames)
            return true;
    }
    return false;
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
