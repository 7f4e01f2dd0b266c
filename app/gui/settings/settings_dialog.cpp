#include "settings/settings_dialog.h"

#include "lw/core/error.h"
#include "lw/render/silhouette_methods.h"
#include "review/review_panel.h"
#include "settings/ui_language.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QSettings>
#include <QSpinBox>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>

namespace lw::gui {
namespace {

void showColour(QPushButton* button, const QColor& colour) {
    button->setText(colour.name());
    button->setStyleSheet(QStringLiteral("background-color: %1; color: %2")
                              .arg(colour.name(), colour.lightness() < 128 ? "white" : "black"));
}

// Why CUDA cannot be chosen on this machine, or an empty string when it can.
QString cudaUnavailableReason() {
    try {
        render::resolveBackend(render::Backend::Cuda);
        return {};
    } catch (const core::Error& error) {
        return QString::fromStdString(error.what());
    }
}

} // namespace

SettingsDialog::SettingsDialog(const ReviewSettings& settings, QWidget* parent)
    : QDialog(parent), m_settings(settings) {
    setWindowTitle(tr("Linework settings"));
    setObjectName("settingsDialog");
    m_tabs = new QTabWidget(this);
    m_tabs->addTab(makeMethodPage(), tr("Method"));
    m_tabs->addTab(makeAppearancePage(), tr("Appearance"));
    m_tabs->addTab(makePresetPage(), tr("Iso presets"));

    auto* buttons =
        new QDialogButtonBox(QDialogButtonBox::Close | QDialogButtonBox::RestoreDefaults);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::accept);
    connect(buttons->button(QDialogButtonBox::RestoreDefaults), &QPushButton::clicked, this,
            [this] {
                setSettings(ReviewSettings{});
                readControls();
                showLanguage(QString()); // follow the system again
            });
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(m_tabs);
    layout->addWidget(buttons);
    showSettings();
}

void SettingsDialog::addPage(QWidget* page, const QString& title) {
    m_tabs->addTab(page, title);
}

void SettingsDialog::setSettings(const ReviewSettings& settings) {
    m_settings = settings;
    showSettings();
}

QWidget* SettingsDialog::makeMethodPage() {
    auto* page = new QWidget;
    auto* form = new QFormLayout(page);

    auto* methods = new QVBoxLayout;
    m_method = new QButtonGroup(page);
    for (const render::SilhouetteMethodInfo& info : render::silhouetteMethods()) {
        auto* button = new QRadioButton(methodName(info.method));
        button->setObjectName(QStringLiteral("method%1").arg(info.number));
        m_method->addButton(button, int(info.method));
        methods->addWidget(button);
    }
    form->addRow(tr("Silhouette method:"), methods);

    addMemoryRows(form);

    m_mode = new QComboBox;
    m_mode->setObjectName("mode");
    m_mode->addItems({tr("a: extract when the iso-value changes"), tr("b: extract every frame")});
    form->addRow(tr("Mode:"), m_mode);
    m_visibility = new QCheckBox(tr("Hide occluded silhouette lines"));
    form->addRow(tr("Visibility:"), m_visibility);
    m_alongSegment = new QCheckBox(tr("Test along each segment (method 2), not only its ends"));
    form->addRow(QString(), m_alongSegment);
    m_minStroke = new QSpinBox;
    m_minStroke->setObjectName("minStroke");
    m_minStroke->setRange(0, 1000);
    m_minStroke->setSuffix(tr(" px"));
    m_minStroke->setSpecialValueText(tr("Keep every line pixel"));
    m_minStroke->setToolTip(tr("Line fragments with fewer pixels are dropped: the speckle that "
                               "noise on nearly flat surfaces draws. Contours are longer."));
    form->addRow(tr("Drop strokes under:"), m_minStroke);
    m_closeAtBorder = new QCheckBox(tr("Close the surface where the scan ends"));
    m_closeAtBorder->setObjectName("closeAtBorder");
    m_closeAtBorder->setToolTip(tr("Where the first or last slice cuts bone, the cut face becomes "
                                   "part of the surface and its edge is drawn as a line."));
    form->addRow(tr("Volume border:"), m_closeAtBorder);
    m_suggestive = new QCheckBox(tr("Suggestive contours"));
    m_suggestive->setObjectName("suggestive");
    m_suggestive->setToolTip(tr("Also draw where the surface almost turns away from the view "
                                "(concave folds, necks), beside the silhouette. On thick-slice "
                                "CT they follow the slice steps."));
    form->addRow(QString(), m_suggestive);
    m_smoothNormals = new QCheckBox(tr("Smooth the normals (noisy scans)"));
    m_smoothNormals->setObjectName("smoothNormals");
    m_smoothNormals->setToolTip(
        tr("Normals from differences averaged over the neighbouring voxels (Sobel): fewer "
           "specks on noisy, thin-slice scans. Thick slices are smoothed within the slice only."));
    form->addRow(tr("Normals:"), m_smoothNormals);
    m_oversample = new QCheckBox(tr("Finer triangles on thick slices and coarse grids"));
    m_oversample->setObjectName("oversample");
    m_oversample->setToolTip(
        tr("Splits the cells of a coarse axis (thick slices, a coarse grid) by linear "
           "interpolation, so the triangles follow the same surface closely and the lines lie "
           "on the shaded outline. No value is invented; costs some speed on such series."));
    form->addRow(tr("Surface:"), m_oversample);
    m_smoothThickSlices = new QCheckBox(tr("Smooth across thick slices"));
    m_smoothThickSlices->setObjectName("smoothThickSlices");
    m_smoothThickSlices->setToolTip(
        tr("Where the slices are three or more pixels apart, the surface between them joins "
           "the outlines of neighbouring slices smoothly (shape-based interpolation) instead of "
           "drawing straight lines between their grey values, so a skull drawn from a "
           "thick-slice series shows no terraces. Off: straight lines between the slices."));
    form->addRow(QString(), m_smoothThickSlices);

    addBackendRows(form, page);

    connect(m_method, &QButtonGroup::idClicked, this, [this] { readControls(); });
    connect(m_backend, &QButtonGroup::idClicked, this, [this] { readControls(); });
    for (QComboBox* box : {m_chunking, m_mode})
        connect(box, &QComboBox::currentIndexChanged, this, [this] { readControls(); });
    for (QSpinBox* box : {m_brickCells, m_memoryBudget, m_gpuMemoryBudget, m_minStroke})
        connect(box, &QSpinBox::valueChanged, this, [this] { readControls(); });
    for (QCheckBox* box : {m_visibility, m_alongSegment, m_closeAtBorder, m_smoothNormals,
                           m_oversample, m_smoothThickSlices, m_suggestive})
        connect(box, &QCheckBox::toggled, this, [this] { readControls(); });
    return page;
}

// Chunking, brick size and the host and device memory budgets.
void SettingsDialog::addMemoryRows(QFormLayout* form) {
    m_chunking = new QComboBox;
    m_chunking->setObjectName("chunking");
    m_chunking->addItems({tr("Off: whole volume (S)"), tr("Auto: chunked above the memory budget"),
                          tr("Fixed brick size (L)")});
    form->addRow(tr("Chunking:"), m_chunking);
    m_brickCells = new QSpinBox;
    m_brickCells->setObjectName("brickCells");
    m_brickCells->setRange(8, 1024);
    m_brickCells->setSuffix(tr(" cells per brick"));
    form->addRow(tr("Brick size:"), m_brickCells);
    m_memoryBudget = new QSpinBox;
    m_memoryBudget->setRange(64, 1 << 20);
    m_memoryBudget->setSingleStep(256);
    m_memoryBudget->setSuffix(tr(" MiB"));
    form->addRow(tr("Memory budget:"), m_memoryBudget);
    m_gpuMemoryBudget = new QSpinBox;
    m_gpuMemoryBudget->setObjectName("gpuMemoryBudget");
    m_gpuMemoryBudget->setRange(0, 1 << 20);
    m_gpuMemoryBudget->setSingleStep(256);
    m_gpuMemoryBudget->setSuffix(tr(" MiB"));
    m_gpuMemoryBudget->setSpecialValueText(tr("Automatic (free memory less a margin)"));
    m_gpuMemoryBudget->setToolTip(tr("Device memory a CUDA frame may use. Above it the volume "
                                     "streams through the GPU in slabs; below what one slab "
                                     "needs, the frame is drawn on the CPU."));
    form->addRow(tr("GPU memory budget:"), m_gpuMemoryBudget);
}

// CPU, CUDA or Auto; CUDA greyed out with the reason where it is not available.
void SettingsDialog::addBackendRows(QFormLayout* form, QWidget* page) {
    auto* backends = new QHBoxLayout;
    m_backend = new QButtonGroup(page);
    const QStringList names{tr("CPU"), tr("CUDA"), tr("Auto")};
    for (auto backend : {render::Backend::Cpu, render::Backend::Cuda, render::Backend::Auto}) {
        auto* button = new QRadioButton(names[int(backend)]);
        m_backend->addButton(button, int(backend));
        backends->addWidget(button);
    }
    form->addRow(tr("Back-end:"), backends);
    m_backendNote = new QLabel;
    m_backendNote->setWordWrap(true);
    const QString reason = cudaUnavailableReason();
    if (!reason.isEmpty()) {
        m_backend->button(int(render::Backend::Cuda))->setEnabled(false);
        m_backend->button(int(render::Backend::Cuda))->setToolTip(reason);
        m_backendNote->setText(tr("CUDA is not available: %1").arg(reason));
    }
    form->addRow(QString(), m_backendNote);
}

QWidget* SettingsDialog::makeAppearancePage() {
    auto* page = new QWidget;
    auto* form = new QFormLayout(page);
    m_lineWidth = new QDoubleSpinBox;
    m_lineWidth->setRange(1.0, 8.0);
    m_lineWidth->setSingleStep(0.5);
    m_lineWidth->setSuffix(tr(" px"));
    form->addRow(tr("Line width:"), m_lineWidth);
    m_lineColour = new QPushButton;
    form->addRow(tr("Line colour:"), m_lineColour);
    m_hiddenLines = new QCheckBox(tr("Hidden lines, thin, dashed and grey"));
    m_hiddenLines->setObjectName("hiddenLines");
    m_hiddenLines->setToolTip(tr("The technical-illustration convention: the parts of the "
                                 "silhouette behind the surface, under the visible lines"));
    form->addRow(QString(), m_hiddenLines);
    m_background = new QPushButton;
    form->addRow(tr("Background:"), m_background);
    m_contourColour = new QPushButton;
    m_contourColour->setObjectName("contourColour");
    form->addRow(tr("Iso contour on slices:"), m_contourColour);
    m_silhouetteOnIso = new QCheckBox(tr("Draw the silhouette over the iso-surface panel too"));
    form->addRow(tr("Overlay:"), m_silhouetteOnIso);
    m_projection = new QComboBox;
    m_projection->addItems({tr("Perspective"), tr("Orthographic")});
    form->addRow(tr("Projection:"), m_projection);
    m_panelGl = new QComboBox;
    m_panelGl->setObjectName("panelGl");
    m_panelGl->addItems(
        {tr("Auto: on the render thread with CUDA or software OpenGL, else in the panels"),
         tr("In the panels' own OpenGL context"),
         tr("On the render thread (keeps the window responsive)")});
    form->addRow(tr("Draw with OpenGL:"), m_panelGl);
    const GlInfo& gl = displayGlInfo();
    auto* glNote =
        new QLabel(gl.available ? tr("This display's OpenGL: %1%2")
                                      .arg(gl.renderer, gl.software ? tr(" (software)") : QString())
                                : tr("This display offers no OpenGL 4.5 core context"));
    glNote->setWordWrap(true);
    form->addRow(QString(), glNote);

    m_language = new QComboBox;
    m_language->setObjectName("language");
    for (const UiLanguage& language : uiLanguages())
        m_language->addItem(language.nativeName, language.code);
    form->addRow(tr("Language:"), m_language);
    auto* languageNote = new QLabel(tr("A new language applies the next time Linework starts."));
    languageNote->setWordWrap(true);
    form->addRow(QString(), languageNote);
    {
        QSettings store;
        showLanguage(storedUiLanguage(store));
    }
    connect(m_language, &QComboBox::currentIndexChanged, this, [this] {
        QSettings store;
        storeUiLanguage(store, m_language->currentData().toString());
    });

    connect(m_lineWidth, &QDoubleSpinBox::valueChanged, this, [this] { readControls(); });
    connect(m_silhouetteOnIso, &QCheckBox::toggled, this, [this] { readControls(); });
    connect(m_hiddenLines, &QCheckBox::toggled, this, [this] { readControls(); });
    connect(m_projection, &QComboBox::currentIndexChanged, this, [this] { readControls(); });
    connect(m_panelGl, &QComboBox::currentIndexChanged, this, [this] { readControls(); });
    connect(m_lineColour, &QPushButton::clicked, this,
            [this] { pickColour(m_settings.lineColour, m_lineColour); });
    connect(m_background, &QPushButton::clicked, this,
            [this] { pickColour(m_settings.background, m_background); });
    connect(m_contourColour, &QPushButton::clicked, this,
            [this] { pickColour(m_settings.contourColour, m_contourColour); });
    return page;
}

QWidget* SettingsDialog::makePresetPage() {
    auto* page = new QWidget;
    auto* layout = new QVBoxLayout(page);
    m_presets = new QTableWidget(0, 2);
    m_presets->setObjectName("presetTable");
    m_presets->setHorizontalHeaderLabels({tr("Name"), tr("Iso-value (HU)")});
    m_presets->horizontalHeader()->setStretchLastSection(true);
    layout->addWidget(m_presets);
    auto* buttons = new QHBoxLayout;
    auto* add = new QPushButton(tr("Add"));
    auto* remove = new QPushButton(tr("Remove"));
    buttons->addWidget(add);
    buttons->addWidget(remove);
    buttons->addStretch();
    layout->addLayout(buttons);
    connect(add, &QPushButton::clicked, this, [this] {
        m_settings.presets.append({tr("Preset %1").arg(m_settings.presets.size() + 1), 0.0});
        showSettings();
        readControls();
    });
    connect(remove, &QPushButton::clicked, this, [this] {
        const int row = m_presets->currentRow();
        if (row >= 0 && m_settings.presets.size() > 1) {
            m_settings.presets.removeAt(row);
            showSettings();
            readControls();
        }
    });
    connect(m_presets, &QTableWidget::cellChanged, this, [this] { readControls(); });
    return page;
}

void SettingsDialog::showSettings() {
    m_updating = true;
    m_method->button(int(m_settings.method))->setChecked(true);
    m_chunking->setCurrentIndex(int(m_settings.chunking));
    m_brickCells->setValue(m_settings.fixedBrickCells);
    m_memoryBudget->setValue(m_settings.memoryBudgetMiB);
    m_gpuMemoryBudget->setValue(m_settings.gpuMemoryBudgetMiB);
    m_mode->setCurrentIndex(m_settings.mode == render::ExtractionMode::EveryFrameB ? 1 : 0);
    m_visibility->setChecked(m_settings.visibility);
    m_alongSegment->setChecked(m_settings.testAlongSegment);
    m_minStroke->setValue(m_settings.minStrokePixels);
    m_closeAtBorder->setChecked(m_settings.closeAtBorder);
    m_smoothNormals->setChecked(m_settings.gradientStencil == render::GradientStencil::Smoothed);
    m_oversample->setChecked(m_settings.oversampling == render::Oversampling::Auto);
    m_smoothThickSlices->setChecked(m_settings.thickSlices == render::ThickSlices::Smooth);
    m_suggestive->setChecked(m_settings.suggestiveContours);
    m_backend->button(int(m_settings.backend))->setChecked(true);
    m_lineWidth->setValue(m_settings.lineWidth);
    showColour(m_lineColour, m_settings.lineColour);
    m_hiddenLines->setChecked(m_settings.hiddenLines);
    showColour(m_background, m_settings.background);
    showColour(m_contourColour, m_settings.contourColour);
    m_silhouetteOnIso->setChecked(m_settings.silhouetteOnIso);
    m_projection->setCurrentIndex(m_settings.projection == render::Projection::Orthographic);
    m_panelGl->setCurrentIndex(int(m_settings.panelGl));
    m_presets->setRowCount(int(m_settings.presets.size()));
    for (int row = 0; row < m_settings.presets.size(); ++row) {
        m_presets->setItem(row, 0, new QTableWidgetItem(m_settings.presets[row].name));
        m_presets->setItem(row, 1,
                           new QTableWidgetItem(QString::number(m_settings.presets[row].hu)));
    }
    updateEnabledControls();
    m_updating = false;
}

void SettingsDialog::readControls() {
    if (m_updating)
        return;
    ReviewSettings s = m_settings;
    s.method = render::SilhouetteMethod(m_method->checkedId());
    s.chunking = Chunking(m_chunking->currentIndex());
    s.fixedBrickCells = m_brickCells->value();
    s.memoryBudgetMiB = m_memoryBudget->value();
    s.gpuMemoryBudgetMiB = m_gpuMemoryBudget->value();
    s.mode = m_mode->currentIndex() == 1 ? render::ExtractionMode::EveryFrameB
                                         : render::ExtractionMode::CachedA;
    s.visibility = m_visibility->isChecked();
    s.testAlongSegment = m_alongSegment->isChecked();
    s.minStrokePixels = m_minStroke->value();
    s.closeAtBorder = m_closeAtBorder->isChecked();
    s.gradientStencil = m_smoothNormals->isChecked() ? render::GradientStencil::Smoothed
                                                     : render::GradientStencil::Central;
    s.oversampling =
        m_oversample->isChecked() ? render::Oversampling::Auto : render::Oversampling::Off;
    s.thickSlices = m_smoothThickSlices->isChecked() ? render::ThickSlices::Smooth
                                                     : render::ThickSlices::Linear;
    s.suggestiveContours = m_suggestive->isChecked();
    s.backend = render::Backend(m_backend->checkedId());
    s.lineWidth = m_lineWidth->value();
    s.silhouetteOnIso = m_silhouetteOnIso->isChecked();
    s.hiddenLines = m_hiddenLines->isChecked();
    s.projection = m_projection->currentIndex() == 1 ? render::Projection::Orthographic
                                                     : render::Projection::Perspective;
    s.panelGl = PanelGl(m_panelGl->currentIndex());
    QList<IsoPreset> presets;
    for (int row = 0; row < m_presets->rowCount(); ++row) {
        const QTableWidgetItem* name = m_presets->item(row, 0);
        const QTableWidgetItem* value = m_presets->item(row, 1);
        bool ok = false;
        const double hu = value ? value->text().toDouble(&ok) : 0.0;
        if (name && ok && !name->text().trimmed().isEmpty())
            presets.append({name->text().trimmed(), hu});
    }
    if (!presets.isEmpty())
        s.presets = presets;
    updateEnabledControls();
    if (s == m_settings)
        return;
    m_settings = s;
    QSettings store;
    m_settings.save(store);
    emit settingsChanged(m_settings);
}

void SettingsDialog::pickColour(QColor& colour, QPushButton* button) {
    const QColor chosen = QColorDialog::getColor(colour, this, tr("Choose a colour"));
    if (!chosen.isValid())
        return;
    colour = chosen;
    showColour(button, chosen);
    QSettings store;
    m_settings.save(store);
    emit settingsChanged(m_settings);
}

void SettingsDialog::showLanguage(const QString& code) {
    m_language->setCurrentIndex(std::max(0, m_language->findData(code)));
}

void SettingsDialog::updateEnabledControls() {
    m_brickCells->setEnabled(m_chunking->currentIndex() == int(Chunking::Fixed));
    m_memoryBudget->setEnabled(m_chunking->currentIndex() == int(Chunking::Auto));
    m_gpuMemoryBudget->setEnabled(m_backend->checkedId() != int(render::Backend::Cpu) &&
                                  cudaUnavailableReason().isEmpty());
    m_alongSegment->setEnabled(m_method->checkedId() == 2 && m_visibility->isChecked());
    m_hiddenLines->setEnabled(m_visibility->isChecked()); // without visibility none is hidden
}

} // namespace lw::gui
