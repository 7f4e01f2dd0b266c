// linework: the workstation. `linework [PATH] [--iso HU] [--series UID] [--database FILE]`
// opens the study browser and, with PATH, a review of that folder, DICOMDIR, file or
// phantom:N at once.
#include "review/review_panel.h"
#include "settings/ui_language.h"
#include "shell/main_window.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QSettings>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

namespace {

// --help and --version only print, so they run on a QCoreApplication and need no display: they
// work on a server or in a fresh container checking the installed package.
bool onlyPrints(int argc, char* argv[]) {
    for (int i = 1; i < argc; ++i)
        for (const char* option : {"-h", "--help", "--help-all", "-?", "-v", "--version"})
            if (std::strcmp(argv[i], option) == 0)
                return true;
    return false;
}

} // namespace

int main(int argc, char* argv[]) {
    lw::gui::requestCoreProfileFormat();
    const std::unique_ptr<QCoreApplication> app =
        onlyPrints(argc, argv) ? std::make_unique<QCoreApplication>(argc, argv)
                               : std::make_unique<QApplication>(argc, argv);
    QApplication::setOrganizationName("Linework");
    QApplication::setApplicationName("linework");
    QApplication::setApplicationVersion(LINEWORK_VERSION);
    {
        // Before any text is made, the command line's help included: the language chosen on
        // the settings page, else the system's.
        QSettings store;
        lw::gui::installUiTranslation(lw::gui::storedUiLanguage(store));
    }

    QCommandLineParser parser;
    parser.setApplicationDescription(
        QApplication::translate("main", "Iso-surface and silhouette review of CT series"));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument("path",
                                 QApplication::translate("main",
                                                         "DICOM folder, DICOMDIR, file, volume or "
                                                         "phantom:N to review at once"),
                                 "[path]");
    const QCommandLineOption iso("iso", QApplication::translate("main", "Iso-value in HU."), "HU");
    const QCommandLineOption series("series",
                                    QApplication::translate("main", "Series instance UID."), "UID");
    const QCommandLineOption database(
        "database", QApplication::translate("main", "Study database file."), "FILE");
    parser.addOptions({iso, series, database});
    parser.process(*app); // exits with 0 for --help/--version and 1 for unknown options

    std::optional<double> isoValue;
    if (parser.isSet(iso)) {
        bool ok = false;
        isoValue = parser.value(iso).toDouble(&ok);
        if (!ok) {
            std::fprintf(stderr, "linework: --iso %s: not a number\n",
                         qPrintable(parser.value(iso)));
            return 2;
        }
    }
    if (parser.positionalArguments().size() > 1) {
        std::fprintf(stderr, "linework: expects at most one path\n");
        return 2;
    }

    lw::gui::MainWindowOptions options;
    options.databasePath = parser.value(database);
    lw::gui::MainWindow window(options);
    window.show();
    if (!parser.positionalArguments().isEmpty())
        window.openPath(parser.positionalArguments().front(), isoValue, parser.value(series));
    return QApplication::exec();
}
