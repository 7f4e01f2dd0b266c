#pragma once

// Where the review's panels sit: the two 3D panels and the three slice views in the layouts of
// settings/review_layout.h, the view bar's layout and window chooser, and the layouts' keys
// (Alt+1 ... Alt+5, as its menu lists them). Only the slices a layout shows are sampled.

#include "settings/review_layout.h"

#include <QObject>

class QComboBox;
class QSplitter;
class QToolButton;
class QWidget;

namespace lw::gui {

class ReviewPanel;
class SliceViews;

class ReviewArrangement : public QObject {
    Q_OBJECT
public:
    ReviewArrangement(ReviewPanel& iso, ReviewPanel& silhouette, SliceViews& slices,
                      QObject* parent = nullptr);

    QWidget* widget() const; // the splitters, for the review's layout
    ReviewLayoutChoice choice() const { return m_choice; }
    void apply(ReviewLayoutChoice choice);
    // The view bar's controls, kept in step with apply() and the slices' window: the layouts'
    // menu, whose actions' keys work while the focus is inside `scope` (the review), and the
    // window presets (shown with the slices).
    QToolButton* makeLayoutButton(QWidget& scope);
    QComboBox* makeWindowChooser();

signals:
    void changed(lw::gui::ReviewLayoutChoice choice);

private:
    void showWindowOf(QComboBox& chooser) const;

    ReviewPanel& m_iso;
    ReviewPanel& m_silhouette;
    SliceViews& m_slices;
    QSplitter* m_outer = nullptr; // 3D panels above, slices below
    QSplitter* m_top = nullptr;
    QSplitter* m_bottom = nullptr;
    ReviewLayoutChoice m_choice;
    bool m_applied = false;
};

} // namespace lw::gui
