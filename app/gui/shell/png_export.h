#pragma once

// Exporting the review as a PNG at a resolution independent of the window: the panels are
// re-rendered at that size (ReviewWidget::renderPanels), not scaled, and written atomically
// (a temporary file renamed over the target), so a failed export never leaves half a file.

#include <QDialog>
#include <QSize>
#include <QString>

class QComboBox;
class QWidget;
class QSpinBox;

namespace lw::gui {

class ReviewWidget;

enum class ExportLayout { SideBySide, IsoPanel, SilhouettePanel };

// Renders `review` with panels of `panelSize` in `layout` and writes it to `path`. Returns an
// empty string on success, otherwise the reason naming the file (nothing is written then).
// Where the panels do not need their own GL contexts (software GL) the rendering runs off the
// UI thread, with a progress dialog over `progressParent` when it takes longer than a moment.
QString exportReviewPng(ReviewWidget& review, const QString& path, QSize panelSize,
                        ExportLayout layout, QWidget* progressParent = nullptr);

// What to export and at which size (the file is asked for afterwards).
class PngExportDialog : public QDialog {
    Q_OBJECT
public:
    PngExportDialog(QSize panelSize, QWidget* parent = nullptr);
    QSize panelSize() const;
    ExportLayout layout() const;

private:
    QComboBox* m_layout = nullptr;
    QSpinBox* m_width = nullptr;
    QSpinBox* m_height = nullptr;
};

} // namespace lw::gui
