#pragma once

// The language of the user interface: English (the source strings), German or Romanian. It
// follows the system locale unless the settings page fixes one; a choice applies at the next
// start, because widgets already built keep the texts they were given.

#include <QList>
#include <QString>
#include <QStringList>

class QSettings;

namespace lw::gui {

struct UiLanguage {
    QString code;       // empty: follow the system; else "en", "de", "ro"
    QString nativeName; // how the settings page names it, in that language itself
};

// The settings page's choices, "follow the system" first.
QList<UiLanguage> uiLanguages();

// The stored choice: empty when none was made or the stored value is no known language.
QString storedUiLanguage(QSettings& settings);
void storeUiLanguage(QSettings& settings, const QString& code);

// Where linework_<language>.qm files are looked for: beside an installed program
// (<prefix>/share/linework/translations, as the Debian package has it) and beside the program
// in the build tree (<build>/app/gui/translations).
QStringList translationDirectories();

// Installs Linework's translation for `code` (empty: the languages of QLocale(), the system's
// unless a test set another default), and Qt's own for the same language where the system has
// it (qt6-translations-l10n), replacing translations an earlier call installed. Returns the
// language of the translation loaded, e.g. "de", or an empty string when the interface stays
// in English: English chosen, or no translation for the locale's languages.
QString installUiTranslation(const QString& code,
                             const QStringList& directories = translationDirectories());

} // namespace lw::gui
