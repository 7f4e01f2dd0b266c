#include "review/iso_control.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QPushButton>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace lw::gui {

HistogramView::HistogramView(QWidget* parent) : QWidget(parent) {
    setObjectName("isoHistogram");
    setMinimumHeight(40);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    setToolTip(tr("Histogram of the volume (log counts); click to set the iso-value"));
}

void HistogramView::setHistogram(const volume::Histogram& histogram) {
    m_histogram = histogram;
    update();
}

void HistogramView::setIso(double iso) {
    m_iso = iso;
    update();
}

double HistogramView::valueAt(int x) const {
    const double span = m_histogram.binWidth * double(m_histogram.counts.size());
    return m_histogram.min + span * double(x) / std::max(1, width() - 1);
}

void HistogramView::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), palette().base());
    const auto& counts = m_histogram.counts;
    if (counts.empty())
        return;
    const double peak = std::log1p(double(*std::max_element(counts.begin(), counts.end())));
    QPainterPath path(QPointF(0, height()));
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const double x = double(i) * width() / double(counts.size());
        const double h = peak > 0 ? std::log1p(double(counts[i])) / peak : 0.0;
        path.lineTo(x, height() * (1.0 - h));
        path.lineTo(double(i + 1) * width() / double(counts.size()), height() * (1.0 - h));
    }
    path.lineTo(width(), height());
    painter.fillPath(path, palette().mid());
    const double span = m_histogram.binWidth * double(counts.size());
    const double x = span > 0 ? (m_iso - m_histogram.min) / span * width() : 0.0;
    painter.setPen(QPen(QColor(200, 40, 40), 2));
    painter.drawLine(QPointF(x, 0), QPointF(x, height()));
}

void HistogramView::mousePressEvent(QMouseEvent* event) {
    emit isoPicked(valueAt(int(event->position().x())));
}

IsoControl::IsoControl(QWidget* parent) : QWidget(parent) {
    m_histogram = new HistogramView;
    m_slider = new QSlider(Qt::Horizontal);
    m_slider->setObjectName("isoSlider");
    m_slider->setToolTip(tr("Iso-value (HU)"));
    m_spin = new QDoubleSpinBox;
    m_spin->setObjectName("isoSpin");
    m_spin->setDecimals(1);
    m_spin->setSuffix(tr(" HU"));
    m_spin->setKeyboardTracking(false);
    m_presetButtons = new QHBoxLayout;

    auto* row = new QHBoxLayout;
    row->addWidget(new QLabel(tr("Iso-value:")));
    row->addWidget(m_slider, 1);
    row->addWidget(m_spin);
    row->addLayout(m_presetButtons);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_histogram);
    layout->addLayout(row);

    connect(m_slider, &QSlider::valueChanged, this, [this](int value) { setIso(value); });
    connect(m_spin, &QDoubleSpinBox::valueChanged, this, [this](double value) { setIso(value); });
    connect(m_histogram, &HistogramView::isoPicked, this, &IsoControl::setIso);
}

void IsoControl::setVolumeRange(const volume::ValueRange& range,
                                const volume::Histogram& histogram) {
    m_updating = true;
    m_slider->setRange(int(std::floor(range.min)), int(std::ceil(range.max)));
    m_spin->setRange(range.min, range.max);
    m_histogram->setHistogram(histogram);
    m_updating = false;
}

void IsoControl::setPresets(const QList<IsoPreset>& presets) {
    while (QLayoutItem* item = m_presetButtons->takeAt(0)) {
        delete item->widget();
        delete item;
    }
    for (const IsoPreset& preset : presets) {
        auto* button = new QPushButton(preset.name);
        button->setObjectName("preset_" + preset.name);
        button->setToolTip(tr("%1 HU").arg(preset.hu));
        connect(button, &QPushButton::clicked, this, [this, hu = preset.hu] { setIso(hu); });
        m_presetButtons->addWidget(button);
    }
}

void IsoControl::setIso(double iso) {
    if (m_updating)
        return;
    iso = std::clamp(iso, m_spin->minimum(), m_spin->maximum());
    m_updating = true;
    m_slider->setValue(int(std::lround(iso)));
    m_spin->setValue(iso);
    m_histogram->setIso(iso);
    m_updating = false;
    if (iso == m_iso)
        return;
    m_iso = iso;
    emit isoChanged(iso);
}

} // namespace lw::gui
