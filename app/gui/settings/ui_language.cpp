#include "settings/ui_language.h"

#include "lw/core/log.h"

#include <QCoreApplication>
#include <QDir>
#include <QLibraryInfo>
#include <QLocale>
#include <QPointer>
#include <QSettings>
#include <QTranslator>
#include <memory>

namespace lw::gui {
namespace {

constexpr core::LogCategory kLog("lw.gui");

constexpr const char* kLanguageKey = "general/language";

// The translators installed by the last call, so the next one can replace them.
QList<QPointer<QTranslator>>& installedTranslators() {
    static QList<QPointer<QTranslator>> translators;
    return translators;
}

void removeInstalledTranslators() {
    for (const QPointer<QTranslator>& translator : installedTranslators())
        if (translator) {
            QCoreApplication::removeTranslator(translator);
            delete translator;
        }
    installedTranslators().clear();
}

// Loads `prefix`_<language>.qm for the first of `locale`'s UI languages found in `directories`.
QTranslator* loadTranslator(const QLocale& locale, const QString& prefix,
                            const QStringList& directories) {
    auto translator = std::make_unique<QTranslator>(QCoreApplication::instance());
    for (const QString& directory : directories)
        if (translator->load(locale, prefix, QStringLiteral("_"), directory))
            return translator.release();
    return nullptr;
}

bool isKnownLanguage(const QString& code) {
    for (const UiLanguage& language : uiLanguages())
        if (language.code == code)
            return true;
    return false;
}

} // namespace

QList<UiLanguage> uiLanguages() {
    return {{QString(), QObject::tr("System language")},
            {QStringLiteral("en"), QStringLiteral("English")},
            {QStringLiteral("de"), QStringLiteral("Deutsch")},
            {QStringLiteral("ro"), QStringLiteral("Română")}};
}

QString storedUiLanguage(QSettings& settings) {
    const QString code = settings.value(kLanguageKey).toString();
    return isKnownLanguage(code) ? code : QString();
}

void storeUiLanguage(QSettings& settings, const QString& code) {
    if (code.isEmpty())
        settings.remove(kLanguageKey);
    else
        settings.setValue(kLanguageKey, code);
}

QStringList translationDirectories() {
    const QString programDir = QCoreApplication::applicationDirPath();
    return {QDir::cleanPath(programDir + "/../share/linework/translations"),
            programDir + "/translations"};
}

QString installUiTranslation(const QString& code, const QStringList& directories) {
    removeInstalledTranslators();
    if (code == QLatin1String("en"))
        return {}; // the source strings are English
    const QLocale locale = code.isEmpty() ? QLocale() : QLocale(code);
    QTranslator* linework = loadTranslator(locale, QStringLiteral("linework"), directories);
    if (!linework) {
        // Not an error: a system in French gets the English interface.
        if (!code.isEmpty())
            kLog.warning("no Linework translation for " + code.toStdString() + " in " +
                         directories.join(", ").toStdString());
        return {};
    }
    QCoreApplication::installTranslator(linework);
    installedTranslators().append(linework);
    // Qt's own strings (Close, Cancel, Restore Defaults, the file dialogs) in the language
    // Linework loaded, which may be the second of the locale's languages.
    const QString language = linework->language().section(QLatin1Char('_'), 0, 0);
    if (QTranslator* qt = loadTranslator(QLocale(language), QStringLiteral("qt"),
                                         {QLibraryInfo::path(QLibraryInfo::TranslationsPath)})) {
        QCoreApplication::installTranslator(qt);
        installedTranslators().append(qt);
    }
    kLog.debug("interface language " + language.toStdString() + " from " +
               linework->filePath().toStdString());
    return language;
}

} // namespace lw::gui
