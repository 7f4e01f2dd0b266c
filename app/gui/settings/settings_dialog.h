#pragma once

// The settings page: every change is applied at once to the open review (settingsChanged) and
// stored in QSettings; Close keeps what is set, "Restore defaults" resets it. The interface
// language is stored too but applies at the next start (settings/ui_language.h).

#include "settings/review_settings.h"

#include <QDialog>

class QButtonGroup;
class QCheckBox;
class QComboBox;
class QFormLayout;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QTabWidget;

namespace lw::gui {

class SettingsDialog : public QDialog {
    Q_OBJECT
public:
    explicit SettingsDialog(const ReviewSettings& settings, QWidget* parent = nullptr);

    ReviewSettings settings() const { return m_settings; }
    void setSettings(const ReviewSettings& settings);
    // A page that keeps its own storage (the PACS nodes: pacs/pacs_settings_page.h), as a tab.
    void addPage(QWidget* page, const QString& title);

signals:
    void settingsChanged(const lw::gui::ReviewSettings& settings);

private:
    QWidget* makeMethodPage();
    void addMemoryRows(QFormLayout* form);
    void addBackendRows(QFormLayout* form, QWidget* page);
    QWidget* makeAppearancePage();
    QWidget* makePresetPage();
    void showSettings();
    void readControls();
    void pickColour(QColor& colour, QPushButton* button);
    void updateEnabledControls();
    void showLanguage(const QString& code);

    ReviewSettings m_settings;
    bool m_updating = false;
    QTabWidget* m_tabs = nullptr;
    QButtonGroup* m_method = nullptr;
    QComboBox* m_chunking = nullptr;
    QSpinBox* m_brickCells = nullptr;
    QSpinBox* m_memoryBudget = nullptr;
    QSpinBox* m_gpuMemoryBudget = nullptr;
    QSpinBox* m_minStroke = nullptr;
    QCheckBox* m_closeAtBorder = nullptr;
    QCheckBox* m_smoothNormals = nullptr;
    QCheckBox* m_oversample = nullptr;
    QCheckBox* m_smoothThickSlices = nullptr;
    QComboBox* m_mode = nullptr;
    QCheckBox* m_visibility = nullptr;
    QCheckBox* m_alongSegment = nullptr;
    QCheckBox* m_suggestive = nullptr;
    QDoubleSpinBox* m_lineWidth = nullptr;
    QPushButton* m_lineColour = nullptr;
    QCheckBox* m_hiddenLines = nullptr;
    QPushButton* m_background = nullptr;
    QPushButton* m_contourColour = nullptr;
    QCheckBox* m_silhouetteOnIso = nullptr;
    QComboBox* m_projection = nullptr;
    QComboBox* m_panelGl = nullptr;
    QComboBox* m_language = nullptr;
    QButtonGroup* m_backend = nullptr;
    QLabel* m_backendNote = nullptr;
    QTableWidget* m_presets = nullptr;
};

} // namespace lw::gui
