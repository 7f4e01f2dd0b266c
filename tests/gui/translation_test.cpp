// The interface languages: the .qm files the build made load, and German and Romanian labels
// appear in the real main window and settings page; the system locale chooses the language
// unless the settings page fixed one (stored, applied at the next start); a locale without a
// translation, or a missing file, keeps the English source strings; the built program's
// --help speaks the system's language and needs no display.
#include "gui_test_support.h"
#include "settings/settings_dialog.h"
#include "settings/ui_language.h"
#include "shell/main_window.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QLabel>
#include <QLocale>
#include <QMenuBar>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QTabWidget>
#include <QtTest>

using namespace lw::gui;

namespace {

// The .qm files of the build (translations/CMakeLists.txt), not the installed ones.
const QStringList kBuiltTranslations{QStringLiteral(LINEWORK_TRANSLATIONS_DIR)};

QStringList menuTitles(MainWindow& window) {
    QStringList titles;
    for (const QAction* action : window.menuBar()->actions())
        titles.append(action->text());
    return titles;
}

QStringList labelTexts(const QWidget& widget) {
    QStringList texts;
    for (const QLabel* label : widget.findChildren<QLabel*>())
        texts.append(label->text());
    return texts;
}

QStringList tabTexts(const QTabWidget& tabs) {
    QStringList texts;
    for (int i = 0; i < tabs.count(); ++i)
        texts.append(tabs.tabText(i));
    return texts;
}

// The study database in a temporary folder, never the user's.
MainWindowOptions isolatedOptions(const QTemporaryDir& dir) {
    return {.databasePath = dir.filePath("studies.sqlite")};
}

} // namespace

class TranslationTest : public QObject {
    Q_OBJECT
private slots:
    void init();
    void cleanup();
    void germanLabelsInTheMainWindowAndSettingsPage();
    void romanianLabelsInTheMainWindowAndSettingsPage();
    void systemLocaleChoosesTheLanguage_data();
    void systemLocaleChoosesTheLanguage();
    void englishOrAMissingFileKeepsTheSourceStrings();
    void settingsPageStoresTheChoice();
    void builtProgramHelpFollowsTheLocaleWithoutADisplay();

private:
    QLocale m_defaultLocale;
};

void TranslationTest::init() {
    m_defaultLocale = QLocale();
    QSettings().clear();
}

void TranslationTest::cleanup() {
    installUiTranslation(QStringLiteral("en"), kBuiltTranslations); // removes what a test loaded
    QLocale::setDefault(m_defaultLocale);
}

void TranslationTest::germanLabelsInTheMainWindowAndSettingsPage() {
    QCOMPARE(installUiTranslation(QStringLiteral("de"), kBuiltTranslations), QStringLiteral("de"));
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(menuTitles(window),
             (QStringList{"&Datei", "&Bearbeiten", "&Ansicht", "A&nmerkungen"}));
    auto* import = window.findChild<QAction*>("importFolderAction");
    QVERIFY(import);
    QCOMPARE(import->text(), QStringLiteral("Ordner &importieren…"));
    auto* tabs = window.findChild<QTabWidget*>("mainTabs");
    QVERIFY(tabs);
    QCOMPARE(tabs->tabText(0), QStringLiteral("Studien"));
    QCOMPARE(window.settings().presets.front().name, QStringLiteral("Knochen"));

    window.showSettings();
    auto* dialog = window.findChild<SettingsDialog*>();
    QVERIFY(dialog);
    QVERIFY(QTest::qWaitForWindowExposed(dialog));
    QCOMPARE(dialog->windowTitle(), QStringLiteral("Linework-Einstellungen"));
    auto* pages = dialog->findChild<QTabWidget*>();
    QVERIFY(pages);
    QCOMPARE(tabTexts(*pages), (QStringList{"Methode", "Darstellung", "Iso-Vorgaben", "PACS"}));
    const QStringList labels = labelTexts(*dialog);
    for (const char* german :
         {"Silhouettenmethode:", "Aufteilung in Blöcke:", "Sprache:", "AE-Titel der Workstation:",
          "PACS-Knoten:", "Eine neue Sprache gilt ab dem nächsten Start von Linework."})
        QVERIFY2(labels.contains(QString::fromUtf8(german)), german);
}

void TranslationTest::romanianLabelsInTheMainWindowAndSettingsPage() {
    QCOMPARE(installUiTranslation(QStringLiteral("ro"), kBuiltTranslations), QStringLiteral("ro"));
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QCOMPARE(menuTitles(window), (QStringList{"&Fișier", "&Editare", "&Vizualizare", "&Adnotări"}));
    SettingsDialog dialog(ReviewSettings{});
    QCOMPARE(dialog.windowTitle(), QStringLiteral("Setări Linework"));
    QVERIFY(labelTexts(dialog).contains(QStringLiteral("Metoda siluetei:")));
    QVERIFY(labelTexts(dialog).contains(QStringLiteral("Împărțire în blocuri:")));
}

void TranslationTest::systemLocaleChoosesTheLanguage_data() {
    QTest::addColumn<QString>("locale");
    QTest::addColumn<QString>("language");
    QTest::addColumn<QString>("fileMenu");
    QTest::addRow("German (Austria)") << "de_AT"
                                      << "de"
                                      << "&Datei";
    QTest::addRow("Romanian (Moldova)") << "ro_MD"
                                        << "ro"
                                        << "&Fișier";
    QTest::addRow("French: no translation") << "fr_FR"
                                            << ""
                                            << "&File";
    QTest::addRow("English") << "en_GB"
                             << ""
                             << "&File";
}

void TranslationTest::systemLocaleChoosesTheLanguage() {
    QFETCH(QString, locale);
    QFETCH(QString, language);
    QFETCH(QString, fileMenu);
    // QLocale() is the system's locale unless set otherwise: what "follow the system" reads.
    QLocale::setDefault(QLocale(locale));
    QCOMPARE(installUiTranslation(QString(), kBuiltTranslations), language);
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QCOMPARE(menuTitles(window).front(), fileMenu);
}

void TranslationTest::englishOrAMissingFileKeepsTheSourceStrings() {
    QLocale::setDefault(QLocale(QStringLiteral("de_DE")));
    QCOMPARE(installUiTranslation(QStringLiteral("en"), kBuiltTranslations), QString());
    QTemporaryDir dir;
    {
        MainWindow window(isolatedOptions(dir));
        QCOMPARE(menuTitles(window).front(), QStringLiteral("&File"));
    }
    // German chosen but no file where the program looks: English, not empty labels.
    QTemporaryDir empty;
    QCOMPARE(installUiTranslation(QStringLiteral("de"), {empty.path()}), QString());
    MainWindow window(isolatedOptions(dir));
    QCOMPARE(menuTitles(window).front(), QStringLiteral("&File"));
}

void TranslationTest::settingsPageStoresTheChoice() {
    QSettings store;
    QCOMPARE(storedUiLanguage(store), QString());
    {
        SettingsDialog dialog(ReviewSettings{});
        auto* language = dialog.findChild<QComboBox*>("language");
        QVERIFY(language);
        QCOMPARE(language->currentIndex(), 0); // the system's
        QCOMPARE(language->count(), 4);
        QCOMPARE(language->itemText(3), QStringLiteral("Română"));
        language->setCurrentIndex(language->findData(QStringLiteral("ro")));
    }
    store.sync();
    QCOMPARE(storedUiLanguage(store), QStringLiteral("ro"));

    SettingsDialog reopened(ReviewSettings{});
    auto* language = reopened.findChild<QComboBox*>("language");
    QCOMPARE(language->currentData().toString(), QStringLiteral("ro"));
    // What main() does at the next start.
    QCOMPARE(installUiTranslation(storedUiLanguage(store), kBuiltTranslations),
             QStringLiteral("ro"));

    auto* buttons = reopened.findChild<QDialogButtonBox*>();
    buttons->button(QDialogButtonBox::RestoreDefaults)->click();
    QCOMPARE(language->currentIndex(), 0);
    store.sync();
    QCOMPARE(storedUiLanguage(store), QString());

    store.setValue("general/language", "xx"); // no such language: follow the system
    QCOMPARE(storedUiLanguage(store), QString());
}

void TranslationTest::builtProgramHelpFollowsTheLocaleWithoutADisplay() {
    QTemporaryDir config;
    QProcessEnvironment environment = QProcessEnvironment::systemEnvironment();
    environment.remove("DISPLAY");
    environment.remove("WAYLAND_DISPLAY");
    environment.remove("LANGUAGE");
    environment.insert("XDG_CONFIG_HOME", config.path());
    environment.insert("LC_ALL", "de_DE.UTF-8");
    QProcess program;
    program.setProcessEnvironment(environment);
    program.start(QStringLiteral(LINEWORK_GUI_PROGRAM), {"--help"});
    QVERIFY(program.waitForFinished(30000));
    const QString help = QString::fromUtf8(program.readAllStandardOutput());
    QCOMPARE(program.exitCode(), 0);
    QVERIFY2(help.contains(QString::fromUtf8("Isoflächen- und Silhouettenbefundung von CT-Serien")),
             qPrintable(help + program.readAllStandardError()));
    QVERIFY2(help.contains(QStringLiteral("Iso-Wert in HU.")), qPrintable(help));

    program.start(QStringLiteral(LINEWORK_GUI_PROGRAM), {"--version"});
    QVERIFY(program.waitForFinished(30000));
    QCOMPARE(program.exitCode(), 0);
    QVERIFY(QString::fromUtf8(program.readAllStandardOutput()).startsWith("linework "));
}

LW_GUI_TEST_MAIN(TranslationTest)
#include "translation_test.moc"
