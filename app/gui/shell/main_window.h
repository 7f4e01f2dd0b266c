#pragma once

// The workstation's window: the study browser as the first tab, one tab per open review, the
// menus and toolbar, a progress bar with Cancel for opening a volume, and the settings page.
// It only wires these together; each part lives in its own class. The Edit menu's undo and redo
// act on the current review's annotations (one QUndoGroup), the Annotate menu shows its tools,
// and the reviews of DICOM series keep their annotations in the study database.

#include "settings/review_settings.h"

#include <QMainWindow>
#include <future>
#include <memory>
#include <optional>

class QLabel;
class QMenu;
class QProgressBar;
class QPushButton;
class QTabWidget;
class QUndoGroup;

namespace lw::gui {

class ExportActions;
class PacsSendAction;
class ReviewWidget;
class SettingsDialog;
class StudyBrowser;
class VolumeLoader;
struct LoadRequest;
struct ReviewSource;

struct MainWindowOptions {
    QString databasePath; // empty: the study database in the user's data directory
};

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(const MainWindowOptions& options = {}, QWidget* parent = nullptr);
    ~MainWindow() override;

    StudyBrowser& browser() { return *m_browser; }
    ReviewWidget* currentReview() const;
    QList<ReviewWidget*> reviews() const;
    // The open review of a DICOM series, or null (phantoms and volume files have no UID).
    ReviewWidget* reviewOfSeries(const QString& seriesUid) const;
    const ReviewSettings& settings() const { return m_settings; }
    bool isLoading() const;
    QString lastError() const { return m_lastError; }

public slots:
    // Opens a folder, DICOMDIR, file or phantom:N directly in a review (not via the database).
    void openPath(const QString& path, std::optional<double> iso = std::nullopt,
                  const QString& seriesUid = {});
    // Opens a series stored in the study database.
    void openSeries(const QString& seriesUid);
    void chooseAndOpenPath();
    // The File menu's exports (PNG, PDF report, Secondary Capture) of the current review.
    ExportActions& exports() { return *m_exports; }
    PacsSendAction& pacsSend() { return *m_pacsSend; }
    void showSettings();
    void applySettings(const lw::gui::ReviewSettings& settings);
    void cancelLoading();

signals:
    void reviewOpened(lw::gui::ReviewWidget* review);
    void loadFailed(const QString& reason);
    // An open that was cancelled, or replaced by a newer one, has ended and nothing of it was
    // shown (no review, no error).
    void loadDiscarded();

protected:
    void closeEvent(QCloseEvent* event) override;
    // Folders and files dropped anywhere on the window are imported (the browser shows them).
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void createActions();
    void createViewMenu();
    void createEditMenu();
    void fillAnnotateMenu();
    void reviewBecameCurrent();
    void startLoading(LoadRequest request, const QString& what);
    void showReview(std::shared_ptr<ReviewSource> source);
    void keepAnnotations(ReviewWidget& review);
    void showLoadError(const QString& reason);
    void setLoadingVisible(bool visible);

    ReviewSettings m_settings;
    QTabWidget* m_tabs = nullptr;
    StudyBrowser* m_browser = nullptr;
    VolumeLoader* m_loader = nullptr;
    SettingsDialog* m_settingsDialog = nullptr;
    QProgressBar* m_progress = nullptr;
    QPushButton* m_cancel = nullptr;
    QLabel* m_loadingLabel = nullptr;
    QString m_loadingWhat;
    QString m_lastError;
    ExportActions* m_exports = nullptr;
    PacsSendAction* m_pacsSend = nullptr;
    QUndoGroup* m_undoGroup = nullptr;
    QMenu* m_annotateMenu = nullptr;
    // The CUDA probe, started with the window on a background thread: its first call creates the
    // device's context (0.3-0.5 s on an H200), which otherwise fell on the UI thread when the
    // first review opened. Loads wait for it before they hand their volume over
    // (LoadRequest::gpuProbe): a study opened at start arrives sooner. Waited for on destruction.
    std::shared_future<void> m_cudaProbe;
};

} // namespace lw::gui
