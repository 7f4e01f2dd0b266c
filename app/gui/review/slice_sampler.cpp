#include "review/slice_sampler.h"

#include <QElapsedTimer>
#include <QPointer>
#include <QThreadPool>

namespace lw::gui {
namespace {

double millisecondsOf(const QElapsedTimer& timer) {
    return double(timer.nsecsElapsed()) / 1e6;
}

void sampleInto(SliceResult& result, const volume::Volume& volume, const volume::Volume* drawnCopy,
                const volume::SliceGeometry& geometry, double position,
                std::shared_ptr<const volume::SliceImage> reuse) {
    QElapsedTimer timer;
    timer.start();
    // The rows on every core: a wheel step asks for one slice, and it is what the user waits for.
    result.image = reuse ? std::move(reuse)
                         : std::make_shared<const volume::SliceImage>(
                               volume::sampleSlice(volume, geometry, position));
    result.sampleMs = millisecondsOf(timer);
    timer.restart();
    if (drawnCopy) {
        result.contour =
            volume::isoContour(volume::sampleSlice(*drawnCopy, geometry, position), result.iso);
        result.contourOfDrawnCopy = true;
    } else {
        result.contour = volume::isoContour(*result.image, result.iso);
    }
    result.contourMs = millisecondsOf(timer);
}

} // namespace

SliceSampler::SliceSampler(std::shared_ptr<const volume::Volume> volume,
                           volume::SliceGeometry geometry, QThreadPool& pool, QObject* parent)
    : QObject(parent), m_volume(std::move(volume)), m_geometry(std::move(geometry)), m_pool(pool) {}

void SliceSampler::request(double position, double iso) {
    const Request request{position, iso, std::chrono::steady_clock::now()};
    if (m_running) {
        m_waiting = request; // replaces an older waiting one
        return;
    }
    start(request);
}

void SliceSampler::setDrawnSurface(std::shared_ptr<const volume::Volume> copy, double iso) {
    m_drawnCopy = std::move(copy);
    m_drawnIso = iso;
}

void SliceSampler::start(const Request& request) {
    m_running = true;
    std::shared_ptr<const volume::SliceImage> reuse =
        m_lastImage && m_lastImage->position == request.position ? m_lastImage : nullptr;
    std::shared_ptr<const volume::Volume> drawn =
        contoursDrawnCopy(request.iso) ? m_drawnCopy : nullptr;
    QPointer<SliceSampler> self(this);
    m_pool.start([self, volume = m_volume, drawn, geometry = m_geometry, request, reuse] {
        auto result = std::make_shared<SliceResult>();
        result->iso = request.iso;
        result->requested = request.requested;
        try {
            sampleInto(*result, *volume, drawn.get(), geometry, request.position, reuse);
        } catch (const std::exception& error) {
            result->image.reset();
            result->error = QString::fromLocal8Bit(error.what());
        }
        QMetaObject::invokeMethod(
            self.data(),
            [self, result] {
                if (self)
                    self->finished(result);
            },
            Qt::QueuedConnection);
    });
}

void SliceSampler::finished(std::shared_ptr<const SliceResult> result) {
    m_running = false;
    if (result->image)
        m_lastImage = result->image;
    if (m_waiting) {
        const Request next = *m_waiting;
        m_waiting.reset();
        start(next);
    }
    emit ready(std::move(result));
}

} // namespace lw::gui
