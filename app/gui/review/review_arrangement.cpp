#include "review/review_arrangement.h"

#include "review/review_panel.h"
#include "review/slice_view.h"
#include "review/slice_views.h"

#include <QAction>
#include <QActionGroup>
#include <QComboBox>
#include <QMenu>
#include <QSplitter>
#include <QToolButton>

namespace lw::gui {
namespace {

using volume::SliceOrientation;
constexpr SliceOrientation kOrientations[] = {SliceOrientation::Axial, SliceOrientation::Coronal,
                                              SliceOrientation::Sagittal};

// The chooser's entries, in the order of their keys Alt+1 ... Alt+5.
constexpr ReviewLayoutChoice kChoices[] = {
    {ReviewLayout::Surfaces, SliceOrientation::Axial},
    {ReviewLayout::SurfacesAndSlices, SliceOrientation::Axial},
    {ReviewLayout::SilhouetteAndSlice, SliceOrientation::Axial},
    {ReviewLayout::SilhouetteAndSlice, SliceOrientation::Coronal},
    {ReviewLayout::SilhouetteAndSlice, SliceOrientation::Sagittal}};

QString choiceName(const ReviewLayoutChoice& choice) {
    switch (choice.layout) {
    case ReviewLayout::Surfaces:
        return QObject::tr("3D panels");
    case ReviewLayout::SurfacesAndSlices:
        return QObject::tr("3D panels and slices");
    case ReviewLayout::SilhouetteAndSlice:
        break;
    }
    switch (choice.largeSlice) {
    case SliceOrientation::Axial:
        return QObject::tr("Silhouette and axial slice");
    case SliceOrientation::Coronal:
        return QObject::tr("Silhouette and coronal slice");
    case SliceOrientation::Sagittal:
        break;
    }
    return QObject::tr("Silhouette and sagittal slice");
}

int indexOf(const ReviewLayoutChoice& choice) {
    for (int i = 0; i < int(std::size(kChoices)); ++i)
        if (kChoices[i].layout == choice.layout &&
            (choice.layout != ReviewLayout::SilhouetteAndSlice ||
             kChoices[i].largeSlice == choice.largeSlice))
            return i;
    return 0;
}

// The view bar's lists must not widen the review beyond its old minimum: they show the start of
// a long entry rather than ask for its whole width (the list opens wide enough).
void shrinkable(QComboBox& chooser) {
    chooser.setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    chooser.setMinimumContentsLength(9);
}

void equalSizes(QSplitter& splitter) {
    splitter.setSizes(QList<int>(splitter.count(), 1000));
}

} // namespace

ReviewArrangement::ReviewArrangement(ReviewPanel& iso, ReviewPanel& silhouette, SliceViews& slices,
                                     QObject* parent)
    : QObject(parent), m_iso(iso), m_silhouette(silhouette), m_slices(slices) {
    m_top = new QSplitter(Qt::Horizontal);
    m_top->addWidget(&m_iso);
    m_top->addWidget(&m_silhouette);
    m_top->setChildrenCollapsible(false);
    m_bottom = new QSplitter(Qt::Horizontal);
    m_bottom->setObjectName("sliceRow");
    for (SliceOrientation orientation : kOrientations)
        m_bottom->addWidget(&m_slices.view(orientation));
    m_bottom->setChildrenCollapsible(false);
    m_outer = new QSplitter(Qt::Vertical);
    m_outer->addWidget(m_top);
    m_outer->addWidget(m_bottom);
    m_outer->setChildrenCollapsible(false);
    m_outer->setStretchFactor(0, 3);
    m_outer->setStretchFactor(1, 2);
}

QWidget* ReviewArrangement::widget() const {
    return m_outer;
}

void ReviewArrangement::apply(ReviewLayoutChoice choice) {
    if (m_applied && choice == m_choice)
        return;
    m_choice = choice;
    m_applied = true;
    const bool row = choice.layout == ReviewLayout::SurfacesAndSlices;
    const bool large = choice.layout == ReviewLayout::SilhouetteAndSlice;
    // Every view back in the row, then the large one (if any) beside the silhouette.
    for (int i = 0; i < int(std::size(kOrientations)); ++i) {
        SliceView& view = m_slices.view(kOrientations[i]);
        m_bottom->insertWidget(i, &view);
        view.show();
    }
    if (large)
        m_top->addWidget(&m_slices.view(choice.largeSlice));
    m_iso.setVisible(!large);
    m_bottom->setVisible(row);
    for (SliceOrientation orientation : kOrientations)
        m_slices.setActive(orientation, row || (large && orientation == choice.largeSlice));
    equalSizes(*m_top);
    equalSizes(*m_bottom);
    emit changed(choice);
}

// A button with the layouts' menu: narrow, so the view bar does not widen the review, and the
// menu shows each layout's key. The menu's actions are the shortcuts (scope: the review).
QToolButton* ReviewArrangement::makeLayoutButton(QWidget& scope) {
    auto* button = new QToolButton;
    button->setObjectName("reviewLayout");
    button->setText(tr("Layout"));
    button->setToolTip(tr("Layout of the review (Alt+1 … Alt+5)"));
    button->setPopupMode(QToolButton::InstantPopup);
    auto* menu = new QMenu(button);
    auto* group = new QActionGroup(menu);
    for (int i = 0; i < int(std::size(kChoices)); ++i) {
        auto* action = new QAction(choiceName(kChoices[i]), group);
        action->setObjectName(QStringLiteral("reviewLayout%1").arg(i + 1));
        action->setCheckable(true);
        action->setChecked(i == indexOf(m_choice));
        action->setShortcut(QKeySequence(Qt::ALT | Qt::Key(Qt::Key_1 + i)));
        action->setShortcutContext(Qt::WidgetWithChildrenShortcut);
        connect(action, &QAction::triggered, this, [this, i] { apply(kChoices[i]); });
        menu->addAction(action);
        scope.addAction(action);
    }
    connect(this, &ReviewArrangement::changed, group, [group](ReviewLayoutChoice choice) {
        group->actions().at(indexOf(choice))->setChecked(true);
    });
    button->setMenu(menu);
    return button;
}

QComboBox* ReviewArrangement::makeWindowChooser() {
    auto* chooser = new QComboBox;
    chooser->setObjectName("sliceWindow");
    shrinkable(*chooser);
    chooser->setPlaceholderText(tr("Custom window"));
    for (WindowPreset preset : kWindowPresets) {
        const WindowLevel window = windowPreset(preset);
        chooser->addItem(windowPresetName(preset), int(preset));
        chooser->setItemData(chooser->count() - 1,
                             tr("Window %1, level %2 HU").arg(window.width).arg(window.level),
                             Qt::ToolTipRole);
    }
    chooser->setToolTip(tr("Window and level of the slices (right drag on a slice to adjust)"));
    connect(chooser, &QComboBox::activated, this, [this, chooser](int index) {
        m_slices.applyPreset(WindowPreset(chooser->itemData(index).toInt()));
    });
    connect(&m_slices, &SliceViews::windowLevelChanged, chooser,
            [this, chooser] { showWindowOf(*chooser); });
    showWindowOf(*chooser);
    // The presets are CT windows: other series window their own range by dragging.
    chooser->setEnabled(m_slices.isHounsfield());
    // Shown with the slices only.
    chooser->setVisible(m_choice.layout != ReviewLayout::Surfaces);
    connect(this, &ReviewArrangement::changed, chooser, [chooser](ReviewLayoutChoice choice) {
        chooser->setVisible(choice.layout != ReviewLayout::Surfaces);
    });
    return chooser;
}

void ReviewArrangement::showWindowOf(QComboBox& chooser) const {
    int shown = -1;
    for (int i = 0; i < chooser.count(); ++i)
        if (windowPreset(WindowPreset(chooser.itemData(i).toInt())) == m_slices.windowLevel())
            shown = i;
    chooser.setCurrentIndex(shown);
}

} // namespace lw::gui
