#pragma once

// The iso-value control: the volume's histogram (log counts) with the iso-value marked, a
// slider and a spin box in HU, and the presets (bone, skin, ... from the settings). Every change
// is reported at once (isoChanged), dragging included: the review re-extracts off the UI thread
// and a newer value cancels an older one.

#include "lw/volume/volume.h"
#include "settings/review_settings.h"

#include <QWidget>

class QDoubleSpinBox;
class QHBoxLayout;
class QSlider;

namespace lw::gui {

class HistogramView : public QWidget {
    Q_OBJECT
public:
    explicit HistogramView(QWidget* parent = nullptr);
    void setHistogram(const volume::Histogram& histogram);
    void setIso(double iso);
    QSize sizeHint() const override { return {400, 48}; }

signals:
    void isoPicked(double iso);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;

private:
    double valueAt(int x) const;
    volume::Histogram m_histogram;
    double m_iso = 0.0;
};

class IsoControl : public QWidget {
    Q_OBJECT
public:
    explicit IsoControl(QWidget* parent = nullptr);

    // The range and histogram of the volume in real units (HU for CT).
    void setVolumeRange(const volume::ValueRange& range, const volume::Histogram& histogram);
    void setPresets(const QList<IsoPreset>& presets);
    double iso() const { return m_iso; }

public slots:
    void setIso(double iso);

signals:
    void isoChanged(double iso);

private:
    double m_iso = 0.0;
    bool m_updating = false;
    HistogramView* m_histogram = nullptr;
    QSlider* m_slider = nullptr;
    QDoubleSpinBox* m_spin = nullptr;
    QHBoxLayout* m_presetButtons = nullptr;
};

} // namespace lw::gui
