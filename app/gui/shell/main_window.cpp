#include "shell/main_window.h"

#include "annotate/annotation_actions.h"
#include "annotate/annotation_document.h"
#include "browser/study_browser.h"
#include "lw/core/error.h"
#include "lw/core/thread_priority.h"
#include "lw/render/renderer_factory.h"
#include "pacs/pacs_locations.h"
#include "pacs/pacs_settings_page.h"
#include "pacs/remote_panel.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "review/volume_loader.h"
#include "settings/settings_dialog.h"
#include "shell/annotation_persistence.h"
#include "shell/export_actions.h"
#include "shell/pacs_send_action.h"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QKeySequence>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QSettings>
#include <QStatusBar>
#include <QTabBar>
#include <QTabWidget>
#include <QToolBar>
#include <QUndoGroup>
#include <QUrl>

namespace lw::gui {

MainWindow::MainWindow(const MainWindowOptions& options, QWidget* parent) : QMainWindow(parent) {
    setObjectName("mainWindow");
    setWindowTitle(tr("Linework"));
    setAcceptDrops(true);
    QSettings store;
    m_settings = ReviewSettings::load(store);
    // Which OpenGL this display gives decides how reviews draw; ask before the window shows,
    // not when the first review opens.
    displayGlInfo();
    if (m_settings.backend != render::Backend::Cpu) {
        const auto probe = [] {
            core::lowerCurrentThreadToBackground();
            render::cudaAvailability(); // probed once per process; later calls read the answer
        };
        m_cudaProbe = std::async(std::launch::async, probe).share();
    }

    m_tabs = new QTabWidget;
    m_tabs->setObjectName("mainTabs");
    m_tabs->setTabsClosable(true);
    m_tabs->setDocumentMode(true);
    const QString databasePath = options.databasePath.isEmpty()
                                     ? studydb::StudyDatabase::defaultPath()
                                     : options.databasePath;
    m_browser = new StudyBrowser(databasePath);
    m_tabs->addTab(m_browser, tr("Studies"));
    setCentralWidget(m_tabs);
    connect(m_tabs, &QTabWidget::tabCloseRequested, this, [this](int index) {
        if (index == 0)
            return; // the browser stays
        QWidget* page = m_tabs->widget(index);
        m_tabs->removeTab(index);
        page->deleteLater();
    });
    // The browser's own close button would remove it: hide it.
    m_tabs->tabBar()->setTabButton(0, QTabBar::RightSide, nullptr);

    m_loader = new VolumeLoader(this);
    connect(m_loader, &VolumeLoader::progress, this,
            [this](double fraction, const QString& message) {
                m_progress->setValue(int(fraction * 1000));
                m_loadingLabel->setText(m_loadingWhat +
                                        (message.isEmpty() ? QString() : ": " + message));
            });
    connect(m_loader, &VolumeLoader::loaded, this, &MainWindow::showReview);
    connect(m_loader, &VolumeLoader::failed, this, &MainWindow::showLoadError);
    connect(m_loader, &VolumeLoader::cancelled, this, [this] {
        setLoadingVisible(false);
        statusBar()->showMessage(tr("Opening cancelled"), 5000);
    });
    connect(m_loader, &VolumeLoader::discarded, this, &MainWindow::loadDiscarded);
    connect(m_browser, &StudyBrowser::openSeriesRequested, this, &MainWindow::openSeries);
    connect(m_browser, &StudyBrowser::statusMessage, this,
            [this](const QString& message) { statusBar()->showMessage(message, 8000); });

    m_loadingLabel = new QLabel;
    m_progress = new QProgressBar;
    m_progress->setObjectName("openProgress");
    m_progress->setRange(0, 1000);
    m_progress->setMaximumWidth(240);
    m_cancel = new QPushButton(tr("Cancel"));
    m_cancel->setObjectName("cancelOpenButton");
    connect(m_cancel, &QPushButton::clicked, this, &MainWindow::cancelLoading);
    statusBar()->addPermanentWidget(m_loadingLabel);
    statusBar()->addPermanentWidget(m_progress);
    statusBar()->addPermanentWidget(m_cancel);
    setLoadingVisible(false);

    m_undoGroup = new QUndoGroup(this);
    m_exports = new ExportActions(*this, [this] { return currentReview(); });
    // The node file beside the study database, as modules/pacs's default is beside the default
    // database (a test's temporary database gets its own).
    m_pacsSend = new PacsSendAction(
        *this, [this] { return currentReview(); },
        [this] { return pacsLocationsBeside(m_browser->databasePath()).nodeFile; });
    createActions();
    createEditMenu();
    createViewMenu();
    m_annotateMenu = menuBar()->addMenu(tr("&Annotate"));
    connect(m_tabs, &QTabWidget::currentChanged, this, &MainWindow::reviewBecameCurrent);
    reviewBecameCurrent();
    resize(1400, 900);
    // Where the user left the window last time.
    restoreGeometry(store.value("window/geometry").toByteArray());
    restoreState(store.value("window/state").toByteArray());
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    if (event->mimeData()->hasUrls())
        event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
    bool any = false;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile()) {
            m_browser->importPath(url.toLocalFile());
            any = true;
        }
    if (any) {
        m_tabs->setCurrentIndex(0);
        event->acceptProposedAction();
    }
}

void MainWindow::closeEvent(QCloseEvent* event) {
    QSettings store;
    store.setValue("window/geometry", saveGeometry());
    store.setValue("window/state", saveState());
    QMainWindow::closeEvent(event);
}

MainWindow::~MainWindow() {
    // Reviews save their annotations through the browser's database: they go first.
    for (ReviewWidget* review : reviews())
        delete review;
}

void MainWindow::createActions() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    QToolBar* toolbar = addToolBar(tr("Main"));
    toolbar->setObjectName("mainToolbar");
    auto add = [&](const QString& text, const QKeySequence& key, auto slot, bool onToolbar) {
        QAction* action = file->addAction(text);
        action->setShortcut(key);
        connect(action, &QAction::triggered, this, slot);
        if (onToolbar)
            toolbar->addAction(action);
        return action;
    };
    add(
        tr("Import &folder…"), QKeySequence(tr("Ctrl+I")),
        [this] { m_browser->chooseFolderToImport(); }, true)
        ->setObjectName("importFolderAction");
    add(
        tr("Import &DICOMDIR…"), QKeySequence(tr("Ctrl+Shift+I")),
        [this] { m_browser->chooseDicomdirToImport(); }, true);
    add(
        tr("&Open path without importing…"), QKeySequence::Open, [this] { chooseAndOpenPath(); },
        true);
    file->addSeparator();
    for (QAction* action : {m_exports->pngAction(), m_exports->reportAction(),
                            m_exports->secondaryCaptureAction(), m_pacsSend->action()})
        file->addAction(action);
    toolbar->addAction(m_exports->pngAction());
    toolbar->addAction(m_exports->reportAction());
    toolbar->addAction(m_pacsSend->action());
    connect(file, &QMenu::aboutToShow, m_pacsSend, &PacsSendAction::refresh);
    file->addSeparator();
    add(
        tr("&Settings…"), QKeySequence(tr("Ctrl+,")), [this] { showSettings(); }, true);
    file->addSeparator();
    add(
        tr("&Close review"), QKeySequence::Close,
        [this] {
            const int index = m_tabs->currentIndex();
            if (index > 0)
                emit m_tabs->tabCloseRequested(index);
        },
        false);
    add(
        tr("&Quit"), QKeySequence::Quit, [] { QApplication::closeAllWindows(); }, false);
}

void MainWindow::createEditMenu() {
    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QAction* undo = m_undoGroup->createUndoAction(this, tr("&Undo"));
    undo->setObjectName("undoAction");
    undo->setShortcut(QKeySequence(tr("Ctrl+Z")));
    QAction* redo = m_undoGroup->createRedoAction(this, tr("&Redo"));
    redo->setObjectName("redoAction");
    redo->setShortcuts({QKeySequence(tr("Ctrl+Shift+Z")), QKeySequence(tr("Ctrl+Y"))});
    edit->addAction(undo);
    edit->addAction(redo);
}

// The Annotate menu lists the current review's own actions: their keys work while the focus is
// in that review (each review has its own tools and selection).
void MainWindow::fillAnnotateMenu() {
    m_annotateMenu->clear();
    ReviewWidget* review = currentReview();
    m_annotateMenu->setEnabled(review != nullptr);
    if (!review)
        return;
    const AnnotationActions& actions = review->annotationActions();
    m_annotateMenu->addActions(actions.toolActions());
    m_annotateMenu->addSeparator();
    m_annotateMenu->addActions(
        {actions.editTextAction(), actions.deleteAction(), actions.cancelAction()});
}

void MainWindow::reviewBecameCurrent() {
    ReviewWidget* review = currentReview();
    m_undoGroup->setActiveStack(review ? &review->annotations().undoStack() : nullptr);
    fillAnnotateMenu();
    m_pacsSend->refresh();
}

void MainWindow::createViewMenu() {
    QMenu* view = menuBar()->addMenu(tr("&View"));
    const std::pair<StandardView, QString> views[] = {
        {StandardView::Anterior, tr("&Anterior")}, {StandardView::Posterior, tr("&Posterior")},
        {StandardView::Left, tr("&Left")},         {StandardView::Right, tr("&Right")},
        {StandardView::Superior, tr("&Superior")}, {StandardView::Inferior, tr("&Inferior")}};
    int key = Qt::Key_1;
    for (const auto& [standard, name] : views) {
        QAction* action = view->addAction(name);
        action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key(key++)));
        connect(action, &QAction::triggered, this, [this, standard = standard] {
            if (ReviewWidget* review = currentReview())
                review->setStandardView(standard);
        });
    }
    view->addSeparator();
    QAction* reset = view->addAction(tr("&Reset camera"));
    reset->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_0));
    connect(reset, &QAction::triggered, this, [this] {
        if (ReviewWidget* review = currentReview())
            review->resetCamera();
    });
    QAction* browser = view->addAction(tr("&Studies"));
    browser->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_B));
    connect(browser, &QAction::triggered, this, [this] { m_tabs->setCurrentIndex(0); });
}

ReviewWidget* MainWindow::currentReview() const {
    return qobject_cast<ReviewWidget*>(m_tabs->currentWidget());
}

QList<ReviewWidget*> MainWindow::reviews() const {
    QList<ReviewWidget*> result;
    for (int i = 0; i < m_tabs->count(); ++i)
        if (auto* review = qobject_cast<ReviewWidget*>(m_tabs->widget(i)))
            result.append(review);
    return result;
}

ReviewWidget* MainWindow::reviewOfSeries(const QString& seriesUid) const {
    for (ReviewWidget* review : reviews())
        if (!seriesUid.isEmpty() && review->source().seriesUid == seriesUid)
            return review;
    return nullptr;
}

bool MainWindow::isLoading() const {
    return m_loader->isRunning();
}

void MainWindow::openPath(const QString& path, std::optional<double> iso,
                          const QString& seriesUid) {
    LoadRequest request;
    request.path = path;
    request.seriesUid = seriesUid;
    request.iso = iso.value_or(m_settings.presets.value(0).hu);
    startLoading(request, tr("Opening %1").arg(path));
}

void MainWindow::openSeries(const QString& seriesUid) {
    QStringList files;
    try {
        files = m_browser->database().seriesFiles(seriesUid);
    } catch (const core::Error& error) {
        return showLoadError(QString::fromStdString(error.what()));
    }
    if (files.isEmpty())
        return showLoadError(tr("Series %1 has no image files in the database: re-import its "
                                "folder")
                                 .arg(seriesUid));
    LoadRequest request;
    request.files = files;
    request.seriesUid = seriesUid;
    request.iso = m_settings.presets.value(0).hu;
    startLoading(request, tr("Opening series"));
}

void MainWindow::chooseAndOpenPath() {
    const QString folder =
        QFileDialog::getExistingDirectory(this, tr("Open a DICOM folder without importing it"));
    if (!folder.isEmpty())
        openPath(folder);
}

void MainWindow::startLoading(LoadRequest request, const QString& what) {
    m_loadingWhat = what;
    m_loadingLabel->setText(what);
    m_progress->setValue(0);
    setLoadingVisible(true);
    request.gpuProbe = m_cudaProbe; // the review opened asks for the device at once
    m_loader->start(request);
}

void MainWindow::cancelLoading() {
    m_loader->cancel();
    setLoadingVisible(false);
}

void MainWindow::setLoadingVisible(bool visible) {
    m_loadingLabel->setVisible(visible);
    m_progress->setVisible(visible);
    m_cancel->setVisible(visible);
}

void MainWindow::showReview(std::shared_ptr<ReviewSource> source) {
    setLoadingVisible(false);
    // One review per series: two would each save their own list of annotations over the other's.
    if (ReviewWidget* open = reviewOfSeries(source->seriesUid)) {
        m_tabs->setCurrentWidget(open);
        statusBar()->showMessage(tr("%1 is open already").arg(open->source().title), 8000);
        emit reviewOpened(open);
        return;
    }
    auto* review = new ReviewWidget(std::move(*source), m_settings);
    m_undoGroup->addStack(&review->annotations().undoStack());
    if (!review->source().seriesUid.isEmpty())
        keepAnnotations(*review);
    const QString title = review->source().title;
    const int index = m_tabs->addTab(review, title.left(40));
    m_tabs->setTabToolTip(index, title);
    m_tabs->setCurrentIndex(index);
    review->isoPanel().setFocus(); // the annotation keys work at once

    emit reviewOpened(review);
}

void MainWindow::keepAnnotations(ReviewWidget& review) {
    try {
        new AnnotationPersistence(m_browser->database(), review);
    } catch (const core::Error& error) {
        review.setStorageProblem(
            tr("Annotations will not be saved: %1").arg(QString::fromStdString(error.what())));
    }
}

void MainWindow::showLoadError(const QString& reason) {
    setLoadingVisible(false);
    m_lastError = reason;
    statusBar()->showMessage(reason, 15000);
    emit loadFailed(reason);
    // Not modal while tests drive the window; a person sees the message box.
    auto* box =
        new QMessageBox(QMessageBox::Warning, tr("Cannot open"), reason, QMessageBox::Ok, this);
    box->setObjectName("loadErrorBox");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

void MainWindow::showSettings() {
    if (!m_settingsDialog) {
        m_settingsDialog = new SettingsDialog(m_settings, this);
        connect(m_settingsDialog, &SettingsDialog::settingsChanged, this,
                &MainWindow::applySettings);
        auto* pacsPage =
            new PacsSettingsPage(pacsLocationsBeside(m_browser->databasePath()).nodeFile);
        m_settingsDialog->addPage(pacsPage, tr("PACS"));
        // The browser's node list follows what Settings saved.
        connect(pacsPage, &PacsSettingsPage::saved, &m_browser->remote(),
                &RemotePanel::reloadNodes);
        // So does "Send to PACS" (disabled while no node is set up).
        connect(pacsPage, &PacsSettingsPage::saved, m_pacsSend, &PacsSendAction::refresh);
    }
    m_settingsDialog->setSettings(m_settings);
    m_settingsDialog->show();
    m_settingsDialog->raise();
}

void MainWindow::applySettings(const ReviewSettings& settings) {
    m_settings = settings;
    for (ReviewWidget* review : reviews())
        review->applySettings(settings);
}

} // namespace lw::gui
