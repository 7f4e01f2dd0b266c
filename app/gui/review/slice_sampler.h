#pragma once

// Samples one orientation's slices and their iso contour off the UI thread. One request runs at
// a time and only the newest waiting one is kept: a wheel spun faster than slices are sampled
// skips the positions in between, and the last one asked for is the one shown. A new iso-value
// at the position on screen reuses its sampled image (marching squares only).
//
// The contour is of the surface the 3D panels draw: where they draw a resampled copy (the
// shape-based field of thick slices, a finer grid) and it is of the request's iso-value, the
// copy is sampled on the same pixels and contoured; otherwise the grey image is. Between slices
// of a thick series the two differ by millimetres, and a point picked on the surface should lie
// on the slice's contour.
//
//   UI thread   SliceViews::request ──► SliceSampler (one running, one waiting)
//                    ▲                       │ pool thread: sampleSlice + isoContour
//                    └──── ready(result) ◄───┘ queued back to the UI thread

#include "lw/volume/slice_contour.h"
#include "lw/volume/slice_plane.h"

#include <QObject>
#include <QString>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

class QThreadPool;

namespace lw::gui {

struct SliceResult {
    std::shared_ptr<const volume::SliceImage> image;
    std::vector<volume::ContourSegment> contour; // image pixel coordinates
    double iso = 0.0;
    bool contourOfDrawnCopy = false; // the contour is the drawn copy's (setDrawnSurface)
    QString error;                   // why there is no image (out of memory), else empty
    double sampleMs = 0.0;           // 0 where the image was reused
    double contourMs = 0.0;
    std::chrono::steady_clock::time_point requested;
};

class SliceSampler : public QObject {
    Q_OBJECT
public:
    SliceSampler(std::shared_ptr<const volume::Volume> volume, volume::SliceGeometry geometry,
                 QThreadPool& pool, QObject* parent = nullptr);

    const volume::SliceGeometry& geometry() const { return m_geometry; }
    void request(double position, double iso);
    // The copy the 3D panels draw at `iso` (null: they draw the volume as loaded).
    void setDrawnSurface(std::shared_ptr<const volume::Volume> copy, double iso);
    bool contoursDrawnCopy(double iso) const { return m_drawnCopy && m_drawnIso == iso; }
    bool isBusy() const { return m_running || m_waiting.has_value(); }

signals:
    void ready(std::shared_ptr<const lw::gui::SliceResult> result);

private:
    struct Request {
        double position = 0.0;
        double iso = 0.0;
        std::chrono::steady_clock::time_point requested;
    };
    void start(const Request& request);
    void finished(std::shared_ptr<const SliceResult> result);

    std::shared_ptr<const volume::Volume> m_volume;
    volume::SliceGeometry m_geometry;
    QThreadPool& m_pool;
    bool m_running = false;
    std::optional<Request> m_waiting;
    std::shared_ptr<const volume::SliceImage> m_lastImage; // reused for a new iso-value
    std::shared_ptr<const volume::Volume> m_drawnCopy;
    double m_drawnIso = 0.0;
};

} // namespace lw::gui
