<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="de">
<context>
    <name>QObject</name>
    <message>
        <source>out of memory at iso-value %1 HU: choose a higher iso-value or chunking (settings)</source>
        <translation>Zu wenig Speicher bei Iso-Wert %1 HU: einen höheren Iso-Wert oder die Aufteilung in Blöcke wählen (Einstellungen)</translation>
    </message>
    <message>
        <source>internal error: %1</source>
        <translation>interner Fehler: %1</translation>
    </message>
    <message>
        <source>Bone</source>
        <translation>Knochen</translation>
    </message>
    <message>
        <source>Skin</source>
        <translation>Haut</translation>
    </message>
    <message>
        <source>System language</source>
        <translation>Systemsprache</translation>
    </message>
    <message>
        <source>%1: out of memory rendering %2 x %3 pixels; choose a smaller size</source>
        <translation>%1: zu wenig Speicher zum Rendern von %2 x %3 Pixeln; eine kleinere Größe wählen</translation>
    </message>
    <message>
        <source>Created %1 with Linework %2 — page %3 of %4</source>
        <translation>Erstellt %1 mit Linework %2 — Seite %3 von %4</translation>
    </message>
    <message>
        <source>Annotations and measurements</source>
        <translation>Anmerkungen und Messungen</translation>
    </message>
    <message>
        <source>none</source>
        <translation>keine</translation>
    </message>
    <message>
        <source>#</source>
        <translation>Nr.</translation>
    </message>
    <message>
        <source>Type</source>
        <translation>Typ</translation>
    </message>
    <message>
        <source>Text</source>
        <translation>Text</translation>
    </message>
    <message>
        <source>Measurement</source>
        <translation>Messung</translation>
    </message>
    <message>
        <source>Points (LPS, mm)</source>
        <translation>Punkte (LPS, mm)</translation>
    </message>
    <message>
        <source>Comment</source>
        <translation>Kommentar</translation>
    </message>
    <message>
        <source>(none)</source>
        <translation>(keiner)</translation>
    </message>
    <message>
        <source>Patient</source>
        <translation>Patient</translation>
    </message>
    <message>
        <source>(anonymised)</source>
        <translation>(anonymisiert)</translation>
    </message>
    <message>
        <source>Patient ID</source>
        <translation>Patienten-ID</translation>
    </message>
    <message>
        <source>Birth date, sex</source>
        <translation>Geburtsdatum, Geschlecht</translation>
    </message>
    <message>
        <source>Accession</source>
        <translation>Auftragsnummer</translation>
    </message>
    <message>
        <source>Study</source>
        <translation>Studie</translation>
    </message>
    <message>
        <source>Series</source>
        <translation>Serie</translation>
    </message>
    <message>
        <source>Source</source>
        <translation>Quelle</translation>
    </message>
    <message>
        <source>Rendering</source>
        <translation>Darstellung</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Datum</translation>
    </message>
    <message>
        <source>Linework report</source>
        <translation>Linework-Bericht</translation>
    </message>
    <message>
        <source>Text:</source>
        <translation>Text:</translation>
    </message>
    <message>
        <source>%1 exists. Replace it?</source>
        <translation>%1 existiert bereits. Ersetzen?</translation>
    </message>
    <message>
        <source>%1 holds a Secondary Capture already (%2). Replace it?</source>
        <translation>%1 enthält bereits eine Secondary Capture (%2). Ersetzen?</translation>
    </message>
    <message>
        <source>Exporting %1 at %2 x %3…</source>
        <translation>%1 wird mit %2 x %3 exportiert…</translation>
    </message>
    <message>
        <source>%1: a Secondary Capture joins the source&apos;s study, and %2 is not a DICOM series</source>
        <translation>%1: Eine Secondary Capture gehört zur Studie der Quelle, und %2 ist keine DICOM-Serie</translation>
    </message>
    <message>
        <source>label</source>
        <translation>Beschriftung</translation>
    </message>
    <message>
        <source>arrow</source>
        <translation>Pfeil</translation>
    </message>
    <message>
        <source>ruler</source>
        <translation>Lineal</translation>
    </message>
    <message>
        <source>angle</source>
        <translation>Winkel</translation>
    </message>
    <message>
        <source>3D panels</source>
        <translation>3D-Bereiche</translation>
    </message>
    <message>
        <source>3D panels and slices</source>
        <translation>3D-Bereiche und Schichten</translation>
    </message>
    <message>
        <source>Surface at %1</source>
        <translation>Oberfläche bei %1</translation>
    </message>
    <message>
        <source>Drag: rotate · Shift/middle drag: pan · wheel/right drag: zoom · Ctrl drag: roll · Shift+click: linked cursor</source>
        <translation>Ziehen: drehen · Umschalt- oder Mitteltaste+Ziehen: verschieben · Mausrad oder rechte Taste+Ziehen: zoomen · Strg+Ziehen: rollen · Umschalt+Klick: verknüpfter Cursor</translation>
    </message>
    <message>
        <source>Soft tissue</source>
        <translation>Weichteil</translation>
    </message>
    <message>
        <source>Lung</source>
        <translation>Lunge</translation>
    </message>
    <message>
        <source>Brain</source>
        <translation>Gehirn</translation>
    </message>
    <message>
        <source>%1 · %2 · %3 mm</source>
        <translation>%1 · %2 · %3 mm</translation>
    </message>
    <message>
        <source>%1 mm</source>
        <translation>%1 mm</translation>
    </message>
    <message>
        <source>Axial</source>
        <translation>Axial</translation>
    </message>
    <message>
        <source>Coronal</source>
        <translation>Koronal</translation>
    </message>
    <message>
        <source>Sagittal</source>
        <translation>Sagittal</translation>
    </message>
    <message>
        <source>stored units</source>
        <translation>gespeicherte Einheiten</translation>
    </message>
    <message>
        <source>%1 stored units</source>
        <translation>%1, gespeicherte Einheiten</translation>
    </message>
    <message>
        <source>Silhouette and axial slice</source>
        <translation>Silhouette und axiale Schicht</translation>
    </message>
    <message>
        <source>Silhouette and coronal slice</source>
        <translation>Silhouette und koronale Schicht</translation>
    </message>
    <message>
        <source>Silhouette and sagittal slice</source>
        <translation>Silhouette und sagittale Schicht</translation>
    </message>
    <message>
        <source>Nothing was sent to %1: %2</source>
        <translation>Nichts wurde an %1 gesendet: %2</translation>
    </message>
    <message>
        <source>%1 answered:</source>
        <translation>Antwort von %1:</translation>
    </message>
    <message>
        <source>No PACS node is configured: add one in Settings (%1)</source>
        <translation>Kein PACS-Knoten eingerichtet: einen in den Einstellungen hinzufügen (%1)</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationActions</name>
    <message>
        <source>&amp;Text label</source>
        <translation>&amp;Textbeschriftung</translation>
    </message>
    <message>
        <source>T</source>
        <translation>T</translation>
    </message>
    <message>
        <source>&amp;Arrow</source>
        <translation>&amp;Pfeil</translation>
    </message>
    <message>
        <source>A</source>
        <translation>A</translation>
    </message>
    <message>
        <source>&amp;Ruler</source>
        <translation>&amp;Lineal</translation>
    </message>
    <message>
        <source>R</source>
        <translation>R</translation>
    </message>
    <message>
        <source>An&amp;gle</source>
        <translation>&amp;Winkel</translation>
    </message>
    <message>
        <source>G</source>
        <translation>G</translation>
    </message>
    <message>
        <source>&amp;Cancel tool</source>
        <translation>Werkzeug &amp;abbrechen</translation>
    </message>
    <message>
        <source>&amp;Delete annotation</source>
        <translation>Anmerkung lös&amp;chen</translation>
    </message>
    <message>
        <source>&amp;Edit text…</source>
        <translation>Text &amp;bearbeiten…</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationDocument</name>
    <message>
        <source>Add %1</source>
        <translation>%1 hinzufügen</translation>
    </message>
    <message>
        <source>Delete %1</source>
        <translation>%1 löschen</translation>
    </message>
    <message>
        <source>Move %1 point</source>
        <translation>Punkt verschieben (%1)</translation>
    </message>
    <message>
        <source>Edit %1 text</source>
        <translation>Text bearbeiten (%1)</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationPersistence</name>
    <message>
        <source>Annotations not loaded, and not saved for this series so the stored ones are kept: %1</source>
        <translation>Anmerkungen nicht geladen und für diese Serie nicht gespeichert, damit die gespeicherten erhalten bleiben: %1</translation>
    </message>
    <message>
        <source>Annotations not saved: %1</source>
        <translation>Anmerkungen nicht gespeichert: %1</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationToolController</name>
    <message>
        <source>Text of the %1</source>
        <translation>Text (%1)</translation>
    </message>
    <message>
        <source>A text label needs a text: delete it with Del instead</source>
        <translation>Eine Textbeschriftung braucht einen Text: zum Löschen Entf drücken</translation>
    </message>
    <message>
        <source>Text label: click the point on the surface to label</source>
        <translation>Textbeschriftung: den zu beschriftenden Punkt auf der Oberfläche anklicken</translation>
    </message>
    <message>
        <source>Arrow: click where its tail goes</source>
        <translation>Pfeil: anklicken, wo sein Ende liegen soll</translation>
    </message>
    <message>
        <source>Arrow: click the point it shows (Esc cancels)</source>
        <translation>Pfeil: den Punkt anklicken, auf den er zeigt (Esc bricht ab)</translation>
    </message>
    <message>
        <source>Ruler: click the first point on the surface</source>
        <translation>Lineal: den ersten Punkt auf der Oberfläche anklicken</translation>
    </message>
    <message>
        <source>Ruler: click the second point (Esc cancels)</source>
        <translation>Lineal: den zweiten Punkt anklicken (Esc bricht ab)</translation>
    </message>
    <message>
        <source>Angle: click the end of the first arm</source>
        <translation>Winkel: das Ende des ersten Schenkels anklicken</translation>
    </message>
    <message>
        <source>Angle: click the vertex (Esc cancels)</source>
        <translation>Winkel: den Scheitelpunkt anklicken (Esc bricht ab)</translation>
    </message>
    <message>
        <source>Angle: click the end of the second arm (Esc cancels)</source>
        <translation>Winkel: das Ende des zweiten Schenkels anklicken (Esc bricht ab)</translation>
    </message>
    <message>
        <source>No surface under the pointer: click on the surface</source>
        <translation>Keine Oberfläche unter dem Mauszeiger: auf die Oberfläche klicken</translation>
    </message>
    <message>
        <source>Text label</source>
        <translation>Textbeschriftung</translation>
    </message>
    <message>
        <source>No surface under the pointer: the point stays where it was</source>
        <translation>Keine Oberfläche unter dem Mauszeiger: der Punkt bleibt, wo er war</translation>
    </message>
    <message>
        <source>Click where the first point is: every point of one annotation lies on the same slice, or in 3D (Esc cancels)</source>
        <translation>Klicken Sie dort, wo der erste Punkt liegt: alle Punkte einer Anmerkung liegen auf derselben Schicht oder in 3D (Esc bricht ab)</translation>
    </message>
    <message>
        <source>Not on the slice: the point stays where it was</source>
        <translation>Nicht auf der Schicht: der Punkt bleibt, wo er war</translation>
    </message>
    <message>
        <source>Not on the slice: click on the slice&apos;s image</source>
        <translation>Nicht auf der Schicht: klicken Sie auf das Bild der Schicht</translation>
    </message>
</context>
<context>
    <name>lw::gui::Annotations</name>
    <message>
        <source>text label</source>
        <translation>Textbeschriftung</translation>
    </message>
    <message>
        <source>arrow</source>
        <translation>Pfeil</translation>
    </message>
    <message>
        <source>ruler</source>
        <translation>Lineal</translation>
    </message>
    <message>
        <source>angle</source>
        <translation>Winkel</translation>
    </message>
</context>
<context>
    <name>lw::gui::ExportActions</name>
    <message>
        <source>&amp;Export PNG…</source>
        <translation>PNG &amp;exportieren…</translation>
    </message>
    <message>
        <source>Ctrl+E</source>
        <translation>Ctrl+E</translation>
    </message>
    <message>
        <source>Export &amp;report (PDF)…</source>
        <translation>Beric&amp;ht exportieren (PDF)…</translation>
    </message>
    <message>
        <source>Ctrl+Shift+E</source>
        <translation>Ctrl+Shift+E</translation>
    </message>
    <message>
        <source>Export Secondary &amp;Capture (DICOM)…</source>
        <translation>Secondary &amp;Capture exportieren (DICOM)…</translation>
    </message>
    <message>
        <source>Open a review to export it</source>
        <translation>Eine Befundung öffnen, um sie zu exportieren</translation>
    </message>
    <message>
        <source>Exported %1</source>
        <translation>%1 exportiert</translation>
    </message>
    <message>
        <source>Export failed</source>
        <translation>Export fehlgeschlagen</translation>
    </message>
    <message>
        <source>Export PNG</source>
        <translation>PNG exportieren</translation>
    </message>
    <message>
        <source>PNG images (*.png)</source>
        <translation>PNG-Bilder (*.png)</translation>
    </message>
    <message>
        <source>Export report</source>
        <translation>Bericht exportieren</translation>
    </message>
    <message>
        <source>PDF documents (*.pdf)</source>
        <translation>PDF-Dokumente (*.pdf)</translation>
    </message>
    <message>
        <source>A Secondary Capture joins the source&apos;s study, and %1 is not a DICOM series</source>
        <translation>Eine Secondary Capture gehört zur Studie der Quelle, und %1 ist keine DICOM-Serie</translation>
    </message>
    <message>
        <source>Export Secondary Capture</source>
        <translation>Secondary Capture exportieren</translation>
    </message>
    <message>
        <source>Folder for the Secondary Capture</source>
        <translation>Ordner für die Secondary Capture</translation>
    </message>
    <message>
        <source>a Secondary Capture into %1</source>
        <translation>eine Secondary Capture nach %1</translation>
    </message>
</context>
<context>
    <name>lw::gui::HistogramView</name>
    <message>
        <source>Histogram of the volume (log counts); click to set the iso-value</source>
        <translation>Histogramm des Volumens (logarithmische Häufigkeiten); klicken, um den Iso-Wert zu setzen</translation>
    </message>
</context>
<context>
    <name>lw::gui::IsoControl</name>
    <message>
        <source>Iso-value (HU)</source>
        <translation>Iso-Wert (HU)</translation>
    </message>
    <message>
        <source> HU</source>
        <translation> HU</translation>
    </message>
    <message>
        <source>Iso-value:</source>
        <translation>Iso-Wert:</translation>
    </message>
    <message>
        <source>%1 HU</source>
        <translation>%1 HU</translation>
    </message>
</context>
<context>
    <name>lw::gui::MainWindow</name>
    <message>
        <source>Linework</source>
        <translation>Linework</translation>
    </message>
    <message>
        <source>Studies</source>
        <translation>Studien</translation>
    </message>
    <message>
        <source>Opening cancelled</source>
        <translation>Öffnen abgebrochen</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Abbrechen</translation>
    </message>
    <message>
        <source>&amp;File</source>
        <translation>&amp;Datei</translation>
    </message>
    <message>
        <source>Main</source>
        <translation>Hauptleiste</translation>
    </message>
    <message>
        <source>Import &amp;folder…</source>
        <translation>Ordner &amp;importieren…</translation>
    </message>
    <message>
        <source>Ctrl+I</source>
        <translation>Ctrl+I</translation>
    </message>
    <message>
        <source>Import &amp;DICOMDIR…</source>
        <translation>&amp;DICOMDIR importieren…</translation>
    </message>
    <message>
        <source>Ctrl+Shift+I</source>
        <translation>Ctrl+Shift+I</translation>
    </message>
    <message>
        <source>&amp;Open path without importing…</source>
        <translation>Pfad ohne Import ö&amp;ffnen…</translation>
    </message>
    <message>
        <source>&amp;Settings…</source>
        <translation>Einstellun&amp;gen…</translation>
    </message>
    <message>
        <source>Ctrl+,</source>
        <translation>Ctrl+,</translation>
    </message>
    <message>
        <source>&amp;Close review</source>
        <translation>Befundung &amp;schließen</translation>
    </message>
    <message>
        <source>&amp;Quit</source>
        <translation>&amp;Beenden</translation>
    </message>
    <message>
        <source>&amp;View</source>
        <translation>&amp;Ansicht</translation>
    </message>
    <message>
        <source>&amp;Anterior</source>
        <translation>&amp;Anterior</translation>
    </message>
    <message>
        <source>&amp;Posterior</source>
        <translation>&amp;Posterior</translation>
    </message>
    <message>
        <source>&amp;Left</source>
        <translation>&amp;Links</translation>
    </message>
    <message>
        <source>&amp;Right</source>
        <translation>&amp;Rechts</translation>
    </message>
    <message>
        <source>&amp;Superior</source>
        <translation>&amp;Superior</translation>
    </message>
    <message>
        <source>&amp;Inferior</source>
        <translation>&amp;Inferior</translation>
    </message>
    <message>
        <source>&amp;Reset camera</source>
        <translation>Kamera &amp;zurücksetzen</translation>
    </message>
    <message>
        <source>&amp;Studies</source>
        <translation>S&amp;tudien</translation>
    </message>
    <message>
        <source>Opening %1</source>
        <translation>%1 wird geöffnet</translation>
    </message>
    <message>
        <source>Series %1 has no image files in the database: re-import its folder</source>
        <translation>Serie %1 hat keine Bilddateien in der Datenbank: ihren Ordner erneut importieren</translation>
    </message>
    <message>
        <source>Opening series</source>
        <translation>Serie wird geöffnet</translation>
    </message>
    <message>
        <source>Open a DICOM folder without importing it</source>
        <translation>DICOM-Ordner öffnen, ohne ihn zu importieren</translation>
    </message>
    <message>
        <source>Cannot open</source>
        <translation>Öffnen nicht möglich</translation>
    </message>
    <message>
        <source>&amp;Annotate</source>
        <translation>A&amp;nmerkungen</translation>
    </message>
    <message>
        <source>&amp;Edit</source>
        <translation>&amp;Bearbeiten</translation>
    </message>
    <message>
        <source>&amp;Undo</source>
        <translation>&amp;Rückgängig</translation>
    </message>
    <message>
        <source>Ctrl+Z</source>
        <translation>Ctrl+Z</translation>
    </message>
    <message>
        <source>&amp;Redo</source>
        <translation>&amp;Wiederherstellen</translation>
    </message>
    <message>
        <source>Ctrl+Shift+Z</source>
        <translation>Ctrl+Shift+Z</translation>
    </message>
    <message>
        <source>Ctrl+Y</source>
        <translation>Ctrl+Y</translation>
    </message>
    <message>
        <source>%1 is open already</source>
        <translation>%1 ist bereits geöffnet</translation>
    </message>
    <message>
        <source>Annotations will not be saved: %1</source>
        <translation>Anmerkungen werden nicht gespeichert: %1</translation>
    </message>
    <message>
        <source>PACS</source>
        <translation>PACS</translation>
    </message>
</context>
<context>
    <name>lw::gui::PacsSendAction</name>
    <message>
        <source>Send to &amp;PACS…</source>
        <translation>An &amp;PACS senden…</translation>
    </message>
    <message>
        <source>Store the Secondary Capture and the report (Encapsulated PDF) in the patient&apos;s study on the PACS</source>
        <translation>Die Secondary Capture und den Bericht (Encapsulated PDF) in der Studie des Patienten im PACS speichern</translation>
    </message>
    <message>
        <source>Open a review to send it to the PACS</source>
        <translation>Eine Befundung öffnen, um sie an das PACS zu senden</translation>
    </message>
    <message>
        <source>A send to the PACS is still running</source>
        <translation>Ein Senden an das PACS läuft noch</translation>
    </message>
    <message>
        <source>Send to PACS</source>
        <translation>An PACS senden</translation>
    </message>
    <message>
        <source>Sending to %1…</source>
        <translation>Wird an %1 gesendet…</translation>
    </message>
    <message>
        <source>Sent to %1</source>
        <translation>An %1 gesendet</translation>
    </message>
    <message>
        <source>Sending to %1 failed</source>
        <translation>Senden an %1 fehlgeschlagen</translation>
    </message>
</context>
<context>
    <name>lw::gui::PacsSender</name>
    <message>
        <source>Cannot create a temporary folder for the objects to send: %1</source>
        <translation>Kein temporärer Ordner für die zu sendenden Objekte möglich: %1</translation>
    </message>
    <message>
        <source>Secondary Capture</source>
        <translation>Secondary Capture</translation>
    </message>
    <message>
        <source>Report (Encapsulated PDF)</source>
        <translation>Bericht (Encapsulated PDF)</translation>
    </message>
    <message>
        <source>A send to the PACS is still running</source>
        <translation>Ein Senden an das PACS läuft noch</translation>
    </message>
    <message>
        <source>An anonymised export cannot be sent to the PACS because it would no longer belong to the patient&apos;s study</source>
        <translation>Ein anonymisierter Export kann nicht an das PACS gesendet werden, weil er nicht mehr zur Studie des Patienten gehören würde</translation>
    </message>
    <message>
        <source>Only a review of a DICOM series can be sent to the PACS: %1 has no study to join</source>
        <translation>Nur die Befundung einer DICOM-Serie kann an das PACS gesendet werden: %1 gehört zu keiner Studie</translation>
    </message>
</context>
<context>
    <name>lw::gui::PacsSettingsPage</name>
    <message>
        <source>Where the workstation receives a C-MOVE&apos;s images; the PACS must list this AE title with this host and port</source>
        <translation>Hier empfängt die Workstation die Bilder eines C-MOVE; das PACS muss diesen AE-Titel mit diesem Host und Port kennen</translation>
    </message>
    <message>
        <source>Workstation AE title:</source>
        <translation>AE-Titel der Workstation:</translation>
    </message>
    <message>
        <source>Storage port (C-MOVE):</source>
        <translation>Empfangsport (C-MOVE):</translation>
    </message>
    <message>
        <source>Name</source>
        <translation>Name</translation>
    </message>
    <message>
        <source>Called AE title</source>
        <translation>Gerufener AE-Titel</translation>
    </message>
    <message>
        <source>Host</source>
        <translation>Host</translation>
    </message>
    <message>
        <source>Port</source>
        <translation>Port</translation>
    </message>
    <message>
        <source>PACS nodes:</source>
        <translation>PACS-Knoten:</translation>
    </message>
    <message>
        <source>Saved in %1</source>
        <translation>Gespeichert in %1</translation>
    </message>
    <message>
        <source>Add</source>
        <translation>Hinzufügen</translation>
    </message>
    <message>
        <source>Remove</source>
        <translation>Entfernen</translation>
    </message>
    <message>
        <source>Test</source>
        <translation>Testen</translation>
    </message>
    <message>
        <source>Sends a C-ECHO to the selected node</source>
        <translation>Sendet ein C-ECHO an den gewählten Knoten</translation>
    </message>
    <message>
        <source>Not saved: %1</source>
        <translation>Nicht gespeichert: %1</translation>
    </message>
    <message>
        <source>node %1</source>
        <translation>Knoten %1</translation>
    </message>
    <message>
        <source>Select a node to test</source>
        <translation>Wählen Sie einen Knoten zum Testen</translation>
    </message>
    <message>
        <source>A test runs</source>
        <translation>Ein Test läuft</translation>
    </message>
    <message>
        <source>Testing %1…</source>
        <translation>Teste %1…</translation>
    </message>
    <message>
        <source>Test: %1</source>
        <translation>Test: %1</translation>
    </message>
    <message>
        <source>Test failed: %1</source>
        <translation>Test fehlgeschlagen: %1</translation>
    </message>
    <message>
        <source>Retrieve by</source>
        <translation>Abrufen per</translation>
    </message>
    <message>
        <source>C-GET</source>
        <translation>C-GET</translation>
    </message>
    <message>
        <source>C-MOVE</source>
        <translation>C-MOVE</translation>
    </message>
    <message>
        <source>C-MOVE sends the images to the storage port above: the PACS must list this workstation&apos;s AE title with its host and that port</source>
        <translation>C-MOVE sendet die Bilder an den Speicherport oben: Das PACS muss den AE-Titel dieser Workstation mit ihrem Host und diesem Port kennen</translation>
    </message>
</context>
<context>
    <name>lw::gui::PictureExportDialog</name>
    <message>
        <source>Both panels side by side</source>
        <translation>Beide Bereiche nebeneinander</translation>
    </message>
    <message>
        <source>Iso-surface panel</source>
        <translation>Isoflächen-Bereich</translation>
    </message>
    <message>
        <source>Silhouette panel</source>
        <translation>Silhouetten-Bereich</translation>
    </message>
    <message>
        <source> px</source>
        <translation> px</translation>
    </message>
    <message>
        <source>Picture:</source>
        <translation>Bild:</translation>
    </message>
    <message>
        <source>Size of each panel:</source>
        <translation>Größe jedes Bereichs:</translation>
    </message>
    <message>
        <source>The panels are rendered again at this size; lines, annotations and text grow with it.</source>
        <translation>Die Bereiche werden in dieser Größe neu gerendert; Linien, Anmerkungen und Text wachsen mit.</translation>
    </message>
</context>
<context>
    <name>lw::gui::RemotePanel</name>
    <message>
        <source>Retrieve</source>
        <translation>Abrufen</translation>
    </message>
    <message>
        <source>The PACS to query (Settings → PACS)</source>
        <translation>Das abzufragende PACS (Einstellungen → PACS)</translation>
    </message>
    <message>
        <source>Patient name (DOE^J*)</source>
        <translation>Patientenname (DOE^J*)</translation>
    </message>
    <message>
        <source>Patient ID</source>
        <translation>Patienten-ID</translation>
    </message>
    <message>
        <source>Dates YYYYMMDD-YYYYMMDD</source>
        <translation>Daten JJJJMMTT-JJJJMMTT</translation>
    </message>
    <message>
        <source>Modality in the study (empty: any)</source>
        <translation>Modalität in der Studie (leer: alle)</translation>
    </message>
    <message>
        <source>Search PACS</source>
        <translation>PACS durchsuchen</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Abbrechen</translation>
    </message>
    <message>
        <source>The PACS nodes cannot be read: %1</source>
        <translation>Die PACS-Knoten sind nicht lesbar: %1</translation>
    </message>
    <message>
        <source>no PACS: Settings → PACS</source>
        <translation>kein PACS: Einstellungen → PACS</translation>
    </message>
    <message>
        <source>Choose a PACS node (Settings → PACS adds one)</source>
        <translation>Wählen Sie einen PACS-Knoten (Einstellungen → PACS fügt einen hinzu)</translation>
    </message>
    <message>
        <source>Dates: %1</source>
        <translation>Daten: %1</translation>
    </message>
    <message>
        <source>Searching %1…</source>
        <translation>Durchsuche %1…</translation>
    </message>
    <message>
        <source>Studies found on %1: %2</source>
        <translation>Gefundene Studien auf %1: %2</translation>
    </message>
    <message>
        <source>Query cancelled</source>
        <translation>Abfrage abgebrochen</translation>
    </message>
    <message>
        <source>Query of %1 failed: %2</source>
        <translation>Abfrage von %1 fehlgeschlagen: %2</translation>
    </message>
    <message>
        <source>Series query failed: %1</source>
        <translation>Abfrage der Serien fehlgeschlagen: %1</translation>
    </message>
    <message>
        <source>Retrieve series and open</source>
        <translation>Serie abrufen und öffnen</translation>
    </message>
    <message>
        <source>Retrieve study</source>
        <translation>Studie abrufen</translation>
    </message>
    <message>
        <source>%1 is no longer a PACS node</source>
        <translation>%1 ist kein PACS-Knoten mehr</translation>
    </message>
    <message>
        <source>A retrieve is running: wait for it or cancel it</source>
        <translation>Ein Abruf läuft: warten Sie oder brechen Sie ihn ab</translation>
    </message>
    <message>
        <source>Retrieving from %1…</source>
        <translation>Abruf von %1…</translation>
    </message>
    <message>
        <source>Retrieving from %1: %2 of %3 images</source>
        <translation>Abruf von %1: %2 von %3 Bildern</translation>
    </message>
    <message>
        <source>%1 of %2 images are here (%3 were already)</source>
        <translation>%1 von %2 Bildern sind hier (%3 waren es schon)</translation>
    </message>
    <message>
        <source>Retrieve cancelled: %1; a new retrieve fetches the others</source>
        <translation>Abruf abgebrochen: %1; ein neuer Abruf holt die übrigen</translation>
    </message>
    <message>
        <source>Retrieved from %1: %2</source>
        <translation>Abgerufen von %1: %2</translation>
    </message>
    <message>
        <source>Retrieve from %1 failed: %2</source>
        <translation>Abruf von %1 fehlgeschlagen: %2</translation>
    </message>
</context>
<context>
    <name>lw::gui::RemoteStudyModel</name>
    <message>
        <source>On %1: double-click to retrieve and open</source>
        <translation>Auf %1: Doppelklick ruft ab und öffnet</translation>
    </message>
    <message>
        <source>On %1: expand for its series, Retrieve in the context menu</source>
        <translation>Auf %1: aufklappen für die Serien, Abrufen im Kontextmenü</translation>
    </message>
    <message>
        <source>Remote: %1</source>
        <translation>Entfernt: %1</translation>
    </message>
    <message>
        <source>Modality</source>
        <translation>Modalität</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Datum</translation>
    </message>
    <message>
        <source>Images</source>
        <translation>Bilder</translation>
    </message>
    <message>
        <source>Description</source>
        <translation>Beschreibung</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReportExportDialog</name>
    <message>
        <source>Export report</source>
        <translation>Bericht exportieren</translation>
    </message>
    <message>
        <source>Findings, comparison, recommendation…</source>
        <translation>Befund, Vergleich, Empfehlung…</translation>
    </message>
    <message>
        <source>Anonymise (leave out the patient&apos;s name, ID, birth date, sex and the accession number)</source>
        <translation>Anonymisieren (Name, ID, Geburtsdatum und Geschlecht des Patienten sowie die Auftragsnummer weglassen)</translation>
    </message>
    <message>
        <source>Comment:</source>
        <translation>Kommentar:</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReviewArrangement</name>
    <message>
        <source>Layout of the review (Alt+1 … Alt+5)</source>
        <translation>Anordnung der Befundung (Alt+1 … Alt+5)</translation>
    </message>
    <message>
        <source>Custom window</source>
        <translation>Eigenes Fenster</translation>
    </message>
    <message>
        <source>Window %1, level %2 HU</source>
        <translation>Fenster %1, Zentrum %2 HU</translation>
    </message>
    <message>
        <source>Window and level of the slices (right drag on a slice to adjust)</source>
        <translation>Fenster und Zentrum der Schichten (mit der rechten Maustaste auf einer Schicht ziehen, um sie anzupassen)</translation>
    </message>
    <message>
        <source>Layout</source>
        <translation>Anordnung</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReviewPanel</name>
    <message>
        <source>OpenGL failed: %1</source>
        <translation>OpenGL-Fehler: %1</translation>
    </message>
    <message>
        <source>Out of memory uploading the surface to OpenGL</source>
        <translation>Zu wenig Speicher beim Hochladen der Oberfläche in OpenGL</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReviewWidget</name>
    <message>
        <source>Rendering the surface at %1 HU…</source>
        <translation>Oberfläche bei %1 HU wird gerendert…</translation>
    </message>
    <message>
        <source>A</source>
        <translation>A</translation>
    </message>
    <message>
        <source>P</source>
        <translation>P</translation>
    </message>
    <message>
        <source>L</source>
        <translation>L</translation>
    </message>
    <message>
        <source>R</source>
        <translation>R</translation>
    </message>
    <message>
        <source>S</source>
        <translation>S</translation>
    </message>
    <message>
        <source>I</source>
        <translation>I</translation>
    </message>
    <message>
        <source>Anterior</source>
        <translation>Anterior</translation>
    </message>
    <message>
        <source>Posterior</source>
        <translation>Posterior</translation>
    </message>
    <message>
        <source>Left</source>
        <translation>Links</translation>
    </message>
    <message>
        <source>Right</source>
        <translation>Rechts</translation>
    </message>
    <message>
        <source>Superior</source>
        <translation>Superior</translation>
    </message>
    <message>
        <source>Inferior</source>
        <translation>Inferior</translation>
    </message>
    <message>
        <source>%1 view</source>
        <translation>Ansicht %1</translation>
    </message>
    <message>
        <source>Reset</source>
        <translation>Zurücksetzen</translation>
    </message>
    <message>
        <source>Reset the camera (Home)</source>
        <translation>Kamera zurücksetzen (Pos1)</translation>
    </message>
    <message>
        <source>No surface at %1 HU</source>
        <translation>Keine Oberfläche bei %1 HU</translation>
    </message>
    <message>
        <source>Method %1 · %2 · mode %3 · %4</source>
        <translation>Methode %1 · %2 · Modus %3 · %4</translation>
    </message>
    <message>
        <source>L (%1-cell bricks)</source>
        <translation>L (Blöcke mit %1 Zellen)</translation>
    </message>
    <message>
        <source> · marching cubes %1 ms</source>
        <translation> · Marching Cubes %1 ms</translation>
    </message>
    <message>
        <source> · GL iso %1 ms, silhouette %2 ms</source>
        <translation> · GL-Iso %1 ms, Silhouette %2 ms</translation>
    </message>
    <message>
        <source> · silhouette: extract %1, segments %2, visibility %3, draw %4 ms</source>
        <translation> · Silhouette: Extraktion %1, Segmente %2, Sichtbarkeit %3, Zeichnen %4 ms</translation>
    </message>
    <message>
        <source> · GL iso %1 ms</source>
        <translation> · GL-Iso %1 ms</translation>
    </message>
    <message>
        <source> · iso shaded on the CPU %1 ms</source>
        <translation> · Iso auf der CPU schattiert %1 ms</translation>
    </message>
    <message>
        <source> · GL iso on the worker %1 ms</source>
        <translation> · GL-Iso im Hintergrund-Thread %1 ms</translation>
    </message>
    <message>
        <source> · %1 triangles · %2 segments</source>
        <translation> · %1 Dreiecke · %2 Segmente</translation>
    </message>
    <message>
        <source> · voxels split %1×%2×%3</source>
        <translation> · Voxel geteilt %1×%2×%3</translation>
    </message>
    <message>
        <source> · iso shaded from the device&apos;s mesh %1 ms</source>
        <translation> · Iso aus dem Netz auf dem Grafikprozessor schattiert %1 ms</translation>
    </message>
    <message>
        <source>Linked cursor at %1</source>
        <translation>Verknüpfter Cursor bei %1</translation>
    </message>
    <message>
        <source>No surface under the pointer: Shift+click on the surface</source>
        <translation>Keine Oberfläche unter dem Mauszeiger: mit Umschalt+Klick auf die Oberfläche klicken</translation>
    </message>
</context>
<context>
    <name>lw::gui::SendToPacsDialog</name>
    <message>
        <source>Send to PACS</source>
        <translation>An PACS senden</translation>
    </message>
    <message>
        <source>PACS:</source>
        <translation>PACS:</translation>
    </message>
    <message>
        <source>The Secondary Capture and the report (as DICOM Encapsulated PDF) join the patient&apos;s study.</source>
        <translation>Die Secondary Capture und der Bericht (als DICOM Encapsulated PDF) kommen in die Studie des Patienten.</translation>
    </message>
</context>
<context>
    <name>lw::gui::SettingsDialog</name>
    <message>
        <source>Linework settings</source>
        <translation>Linework-Einstellungen</translation>
    </message>
    <message>
        <source>Method</source>
        <translation>Methode</translation>
    </message>
    <message>
        <source>Appearance</source>
        <translation>Darstellung</translation>
    </message>
    <message>
        <source>Iso presets</source>
        <translation>Iso-Vorgaben</translation>
    </message>
    <message>
        <source>Silhouette method:</source>
        <translation>Silhouettenmethode:</translation>
    </message>
    <message>
        <source>Off: whole volume (S)</source>
        <translation>Aus: ganzes Volumen (S)</translation>
    </message>
    <message>
        <source>Auto: chunked above the memory budget</source>
        <translation>Automatisch: in Blöcken oberhalb des Speicherbudgets</translation>
    </message>
    <message>
        <source>Fixed brick size (L)</source>
        <translation>Feste Blockgröße (L)</translation>
    </message>
    <message>
        <source>Chunking:</source>
        <translation>Aufteilung in Blöcke:</translation>
    </message>
    <message>
        <source> cells per brick</source>
        <translation> Zellen pro Block</translation>
    </message>
    <message>
        <source>Brick size:</source>
        <translation>Blockgröße:</translation>
    </message>
    <message>
        <source> MiB</source>
        <translation> MiB</translation>
    </message>
    <message>
        <source>Memory budget:</source>
        <translation>Speicherbudget:</translation>
    </message>
    <message>
        <source>Automatic (free memory less a margin)</source>
        <translation>Automatisch (freier Speicher abzüglich einer Reserve)</translation>
    </message>
    <message>
        <source>Device memory a CUDA frame may use. Above it the volume streams through the GPU in slabs; below what one slab needs, the frame is drawn on the CPU.</source>
        <translation>Gerätespeicher, den ein CUDA-Bild belegen darf. Darüber wird das Volumen in Schichtblöcken durch die GPU geleitet; reicht er nicht für einen Schichtblock, wird das Bild auf der CPU gezeichnet.</translation>
    </message>
    <message>
        <source>GPU memory budget:</source>
        <translation>GPU-Speicherbudget:</translation>
    </message>
    <message>
        <source>a: extract when the iso-value changes</source>
        <translation>a: bei Änderung des Iso-Werts extrahieren</translation>
    </message>
    <message>
        <source>b: extract every frame</source>
        <translation>b: in jedem Bild extrahieren</translation>
    </message>
    <message>
        <source>Mode:</source>
        <translation>Modus:</translation>
    </message>
    <message>
        <source>Hide occluded silhouette lines</source>
        <translation>Verdeckte Silhouettenlinien ausblenden</translation>
    </message>
    <message>
        <source>Visibility:</source>
        <translation>Sichtbarkeit:</translation>
    </message>
    <message>
        <source>Test along each segment (method 2), not only its ends</source>
        <translation>Entlang jedes Segments prüfen (Methode 2), nicht nur an seinen Enden</translation>
    </message>
    <message>
        <source> px</source>
        <translation> px</translation>
    </message>
    <message>
        <source>Keep every line pixel</source>
        <translation>Jedes Linienpixel behalten</translation>
    </message>
    <message>
        <source>Line fragments with fewer pixels are dropped: the speckle that noise on nearly flat surfaces draws. Contours are longer.</source>
        <translation>Linienstücke mit weniger Pixeln werden verworfen: die Sprenkel, die Rauschen auf fast ebenen Flächen zeichnet. Konturen sind länger.</translation>
    </message>
    <message>
        <source>Drop strokes under:</source>
        <translation>Striche verwerfen unter:</translation>
    </message>
    <message>
        <source>CPU</source>
        <translation>CPU</translation>
    </message>
    <message>
        <source>CUDA</source>
        <translation>CUDA</translation>
    </message>
    <message>
        <source>Auto</source>
        <translation>Automatisch</translation>
    </message>
    <message>
        <source>Back-end:</source>
        <translation>Backend:</translation>
    </message>
    <message>
        <source>CUDA is not available: %1</source>
        <translation>CUDA ist nicht verfügbar: %1</translation>
    </message>
    <message>
        <source>Line width:</source>
        <translation>Linienbreite:</translation>
    </message>
    <message>
        <source>Line colour:</source>
        <translation>Linienfarbe:</translation>
    </message>
    <message>
        <source>Background:</source>
        <translation>Hintergrund:</translation>
    </message>
    <message>
        <source>Draw the silhouette over the iso-surface panel too</source>
        <translation>Silhouette auch über dem Isoflächen-Bereich zeichnen</translation>
    </message>
    <message>
        <source>Overlay:</source>
        <translation>Überlagerung:</translation>
    </message>
    <message>
        <source>Perspective</source>
        <translation>Perspektivisch</translation>
    </message>
    <message>
        <source>Orthographic</source>
        <translation>Orthografisch</translation>
    </message>
    <message>
        <source>Projection:</source>
        <translation>Projektion:</translation>
    </message>
    <message>
        <source>Auto: on the render thread with CUDA or software OpenGL, else in the panels</source>
        <translation>Automatisch: im Render-Thread mit CUDA oder Software-OpenGL, sonst in den Bereichen</translation>
    </message>
    <message>
        <source>In the panels&apos; own OpenGL context</source>
        <translation>Im eigenen OpenGL-Kontext der Bereiche</translation>
    </message>
    <message>
        <source>On the render thread (keeps the window responsive)</source>
        <translation>Im Render-Thread (das Fenster bleibt reaktionsfähig)</translation>
    </message>
    <message>
        <source>Draw with OpenGL:</source>
        <translation>Mit OpenGL zeichnen:</translation>
    </message>
    <message>
        <source>This display&apos;s OpenGL: %1%2</source>
        <translation>OpenGL dieses Bildschirms: %1%2</translation>
    </message>
    <message>
        <source> (software)</source>
        <translation> (Software)</translation>
    </message>
    <message>
        <source>This display offers no OpenGL 4.5 core context</source>
        <translation>Dieser Bildschirm bietet keinen OpenGL-4.5-Core-Kontext</translation>
    </message>
    <message>
        <source>Language:</source>
        <translation>Sprache:</translation>
    </message>
    <message>
        <source>A new language applies the next time Linework starts.</source>
        <translation>Eine neue Sprache gilt ab dem nächsten Start von Linework.</translation>
    </message>
    <message>
        <source>Name</source>
        <translation>Name</translation>
    </message>
    <message>
        <source>Iso-value (HU)</source>
        <translation>Iso-Wert (HU)</translation>
    </message>
    <message>
        <source>Add</source>
        <translation>Hinzufügen</translation>
    </message>
    <message>
        <source>Remove</source>
        <translation>Entfernen</translation>
    </message>
    <message>
        <source>Preset %1</source>
        <translation>Vorgabe %1</translation>
    </message>
    <message>
        <source>Choose a colour</source>
        <translation>Farbe wählen</translation>
    </message>
    <message>
        <source>Close the surface where the scan ends</source>
        <translation>Oberfläche am Ende des Scans schließen</translation>
    </message>
    <message>
        <source>Where the first or last slice cuts bone, the cut face becomes part of the surface and its edge is drawn as a line.</source>
        <translation>Wo die erste oder letzte Schicht Knochen schneidet, wird die Schnittfläche Teil der Oberfläche und ihr Rand als Linie gezeichnet.</translation>
    </message>
    <message>
        <source>Volume border:</source>
        <translation>Volumenrand:</translation>
    </message>
    <message>
        <source>Suggestive contours</source>
        <translation>Suggestive Konturen</translation>
    </message>
    <message>
        <source>Also draw where the surface almost turns away from the view (concave folds, necks), beside the silhouette. On thick-slice CT they follow the slice steps.</source>
        <translation>Zeichnet neben der Silhouette auch, wo sich die Oberfläche fast vom Blick abwendet (konkave Falten, Einschnürungen). Bei CT mit dicken Schichten folgen sie den Schichtstufen.</translation>
    </message>
    <message>
        <source>Smooth the normals (noisy scans)</source>
        <translation>Normalen glätten (verrauschte Scans)</translation>
    </message>
    <message>
        <source>Normals from differences averaged over the neighbouring voxels (Sobel): fewer specks on noisy, thin-slice scans. Thick slices are smoothed within the slice only.</source>
        <translation>Normalen aus über die Nachbarvoxel gemittelten Differenzen (Sobel): weniger Sprenkel bei verrauschten Dünnschicht-Scans. Dicke Schichten werden nur innerhalb der Schicht geglättet.</translation>
    </message>
    <message>
        <source>Normals:</source>
        <translation>Normalen:</translation>
    </message>
    <message>
        <source>Finer triangles on thick slices and coarse grids</source>
        <translation>Feinere Dreiecke bei dicken Schichten und groben Rastern</translation>
    </message>
    <message>
        <source>Splits the cells of a coarse axis (thick slices, a coarse grid) by linear interpolation, so the triangles follow the same surface closely and the lines lie on the shaded outline. No value is invented; costs some speed on such series.</source>
        <translation>Teilt die Zellen einer groben Achse (dicke Schichten, ein grobes Raster) durch lineare Interpolation, sodass die Dreiecke derselben Oberfläche eng folgen und die Linien auf dem schattierten Umriss liegen. Es wird kein Wert erfunden; kostet bei solchen Serien etwas Geschwindigkeit.</translation>
    </message>
    <message>
        <source>Surface:</source>
        <translation>Oberfläche:</translation>
    </message>
    <message>
        <source>Hidden lines, thin, dashed and grey</source>
        <translation>Verdeckte Linien, dünn, gestrichelt und grau</translation>
    </message>
    <message>
        <source>The technical-illustration convention: the parts of the silhouette behind the surface, under the visible lines</source>
        <translation>Wie in technischen Zeichnungen: die Teile der Silhouette hinter der Oberfläche, unter den sichtbaren Linien</translation>
    </message>
    <message>
        <source>Smooth across thick slices</source>
        <translation>Glatt über dicke Schichten hinweg</translation>
    </message>
    <message>
        <source>Where the slices are three or more pixels apart, the surface between them joins the outlines of neighbouring slices smoothly (shape-based interpolation) instead of drawing straight lines between their grey values, so a skull drawn from a thick-slice series shows no terraces. Off: straight lines between the slices.</source>
        <translation>Wo die Schichten drei oder mehr Pixel auseinanderliegen, verbindet die Oberfläche zwischen ihnen die Umrisse benachbarter Schichten glatt (formbasierte Interpolation), statt gerade Linien zwischen ihren Grauwerten zu ziehen; so zeigt ein Schädel aus einer Serie mit dicken Schichten keine Terrassen. Aus: gerade Linien zwischen den Schichten.</translation>
    </message>
    <message>
        <source>Iso contour on slices:</source>
        <translation>Iso-Kontur auf Schichten:</translation>
    </message>
</context>
<context>
    <name>lw::gui::SliceView</name>
    <message>
        <source>%1 %2</source>
        <translation>%1 %2</translation>
    </message>
    <message>
        <source>W %1 · L %2</source>
        <translation>F %1 · Z %2</translation>
    </message>
</context>
<context>
    <name>lw::gui::SliceViews</name>
    <message>
        <source>%1 %2 · %3</source>
        <translation>%1 %2 · %3</translation>
    </message>
</context>
<context>
    <name>lw::gui::StudyBrowser</name>
    <message>
        <source>any</source>
        <translation>beliebig</translation>
    </message>
    <message>
        <source>The study database cannot be opened: %1</source>
        <translation>Die Studiendatenbank kann nicht geöffnet werden: %1</translation>
    </message>
    <message>
        <source>Import folder…</source>
        <translation>Ordner importieren…</translation>
    </message>
    <message>
        <source>Import DICOMDIR…</source>
        <translation>DICOMDIR importieren…</translation>
    </message>
    <message>
        <source>Remove from database</source>
        <translation>Aus der Datenbank entfernen</translation>
    </message>
    <message>
        <source>Removes the selected series from the database; the files on disk are kept</source>
        <translation>Entfernt die gewählten Serien aus der Datenbank; die Dateien auf dem Datenträger bleiben erhalten</translation>
    </message>
    <message>
        <source>Search patient, ID, description…</source>
        <translation>Patient, ID, Beschreibung suchen…</translation>
    </message>
    <message>
        <source>From</source>
        <translation>Von</translation>
    </message>
    <message>
        <source>to</source>
        <translation>bis</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Abbrechen</translation>
    </message>
    <message>
        <source>The study database cannot be read: %1</source>
        <translation>Die Studiendatenbank kann nicht gelesen werden: %1</translation>
    </message>
    <message>
        <source>Cannot import %1: the study database is not open (%2)</source>
        <translation>%1 kann nicht importiert werden: Die Studiendatenbank ist nicht geöffnet (%2)</translation>
    </message>
    <message>
        <source>%1 will be imported after the current import</source>
        <translation>%1 wird nach dem laufenden Import importiert</translation>
    </message>
    <message>
        <source>Importing %1</source>
        <translation>%1 wird importiert</translation>
    </message>
    <message>
        <source>Importing %1…</source>
        <translation>%1 wird importiert…</translation>
    </message>
    <message>
        <source>Import a DICOM folder</source>
        <translation>DICOM-Ordner importieren</translation>
    </message>
    <message>
        <source>Import a DICOMDIR</source>
        <translation>DICOMDIR importieren</translation>
    </message>
    <message>
        <source>DICOMDIR (DICOMDIR dicomdir);;All files (*)</source>
        <translation>DICOMDIR (DICOMDIR dicomdir);;Alle Dateien (*)</translation>
    </message>
    <message>
        <source>Cancelling…</source>
        <translation>Wird abgebrochen…</translation>
    </message>
    <message>
        <source>Import of %1 cancelled; the database is unchanged</source>
        <translation>Import von %1 abgebrochen; die Datenbank ist unverändert</translation>
    </message>
    <message>
        <source>Imported %1: %2 new, %3 updated series from %4 files</source>
        <translation>%1 importiert: %2 neue, %3 aktualisierte Serien aus %4 Dateien</translation>
    </message>
    <message>
        <source>… and %1 more</source>
        <translation>… und %1 weitere</translation>
    </message>
    <message>
        <source>%1. %2 file(s) could not be used:
%3</source>
        <translation>%1. %2 Datei(en) konnten nicht verwendet werden:
%3</translation>
    </message>
    <message>
        <source>%1: no DICOM series found</source>
        <translation>%1: keine DICOM-Serie gefunden</translation>
    </message>
    <message>
        <source>Import of %1 failed: %2</source>
        <translation>Import von %1 fehlgeschlagen: %2</translation>
    </message>
    <message>
        <source>Import failed: %1</source>
        <translation>Import fehlgeschlagen: %1</translation>
    </message>
    <message numerus="yes">
        <source>Remove %n series from the study database?

The files on disk are kept; you can import them again.</source>
        <translation>
            <numerusform>%n Serie aus der Studiendatenbank entfernen?

Die Dateien auf dem Datenträger bleiben erhalten; Sie können sie erneut importieren.</numerusform>
            <numerusform>%n Serien aus der Studiendatenbank entfernen?

Die Dateien auf dem Datenträger bleiben erhalten; Sie können sie erneut importieren.</numerusform>
        </translation>
    </message>
    <message>
        <source>Cannot remove the series: %1</source>
        <translation>Die Serien können nicht entfernt werden: %1</translation>
    </message>
    <message numerus="yes">
        <source>Removed %n series from the database (files on disk kept)</source>
        <translation>
            <numerusform>%n Serie aus der Datenbank entfernt (Dateien auf dem Datenträger erhalten)</numerusform>
            <numerusform>%n Serien aus der Datenbank entfernt (Dateien auf dem Datenträger erhalten)</numerusform>
        </translation>
    </message>
    <message>
        <source>The files of series &quot;%1&quot; are missing (%2): import its folder again or remove it</source>
        <translation>Die Dateien der Serie „%1“ fehlen (%2): ihren Ordner erneut importieren oder sie entfernen</translation>
    </message>
    <message>
        <source>none referenced</source>
        <translation>keine verzeichnet</translation>
    </message>
    <message>
        <source>%1 of %2 files of series &quot;%3&quot; are missing</source>
        <translation>%1 von %2 Dateien der Serie „%3“ fehlen</translation>
    </message>
    <message numerus="yes">
        <source>%n series selected</source>
        <translation>
            <numerusform>%n Serie ausgewählt</numerusform>
            <numerusform>%n Serien ausgewählt</numerusform>
        </translation>
    </message>
    <message>
        <source>no thumbnail</source>
        <translation>keine Vorschau</translation>
    </message>
    <message>
        <source>Description</source>
        <translation>Beschreibung</translation>
    </message>
    <message>
        <source>Modality</source>
        <translation>Modalität</translation>
    </message>
    <message>
        <source>Series number</source>
        <translation>Seriennummer</translation>
    </message>
    <message>
        <source>Study date</source>
        <translation>Studiendatum</translation>
    </message>
    <message>
        <source>Slices</source>
        <translation>Schichten</translation>
    </message>
    <message>
        <source>Files</source>
        <translation>Dateien</translation>
    </message>
    <message>
        <source>Dimensions</source>
        <translation>Abmessungen</translation>
    </message>
    <message>
        <source>Spacing</source>
        <translation>Voxelabstand</translation>
    </message>
    <message>
        <source>Gantry tilt</source>
        <translation>Gantry-Neigung</translation>
    </message>
    <message>
        <source>Slice gaps</source>
        <translation>Schichtabstände</translation>
    </message>
    <message>
        <source>uneven, %1 to %2 mm</source>
        <translation>ungleichmäßig, %1 bis %2 mm</translation>
    </message>
    <message>
        <source>even (%1 mm)</source>
        <translation>gleichmäßig (%1 mm)</translation>
    </message>
    <message>
        <source>Missing slices</source>
        <translation>Fehlende Schichten</translation>
    </message>
    <message>
        <source>Volumes</source>
        <translation>Volumen</translation>
    </message>
    <message>
        <source>Imported from</source>
        <translation>Importiert aus</translation>
    </message>
    <message>
        <source>Imported at</source>
        <translation>Importiert am</translation>
    </message>
    <message>
        <source>Series UID</source>
        <translation>Serien-UID</translation>
    </message>
    <message>
        <source>Warnings</source>
        <translation>Warnungen</translation>
    </message>
    <message>
        <source>Files that could not be used</source>
        <translation>Nicht verwendbare Dateien</translation>
    </message>
</context>
<context>
    <name>lw::gui::StudyTreeModel</name>
    <message>
        <source>Patient / study / series</source>
        <translation>Patient / Studie / Serie</translation>
    </message>
    <message>
        <source>Modality</source>
        <translation>Modalität</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Datum</translation>
    </message>
    <message>
        <source>Slices</source>
        <translation>Schichten</translation>
    </message>
    <message>
        <source>Dimensions</source>
        <translation>Abmessungen</translation>
    </message>
    <message>
        <source>Spacing (mm)</source>
        <translation>Voxelabstand (mm)</translation>
    </message>
    <message>
        <source>Warnings</source>
        <translation>Warnungen</translation>
    </message>
    <message>
        <source>%1: %2</source>
        <translation>%1: %2</translation>
    </message>
    <message>
        <source>(no description)</source>
        <translation>(keine Beschreibung)</translation>
    </message>
    <message>
        <source>(no name)</source>
        <translation>(kein Name)</translation>
    </message>
    <message>
        <source>Study %1</source>
        <translation>Studie %1</translation>
    </message>
</context>
<context>
    <name>lw::gui::VolumeLoader</name>
    <message>
        <source>out of memory while loading the volume</source>
        <translation>zu wenig Speicher beim Laden des Volumens</translation>
    </message>
</context>
<context>
    <name>lw::render::SilhouetteMethod</name>
    <message>
        <source>Method 1: marching cubes + geometry shader</source>
        <translation>Methode 1: Marching Cubes + Geometry-Shader</translation>
    </message>
    <message>
        <source>Method 2: silhouette only + ray-cast visibility</source>
        <translation>Methode 2: nur Silhouette + Sichtbarkeit per Raycasting</translation>
    </message>
    <message>
        <source>Method 3: own z-buffer rasterizer</source>
        <translation>Methode 3: eigener Z-Buffer-Rasterisierer</translation>
    </message>
</context>
<context>
    <name>main</name>
    <message>
        <source>Iso-surface and silhouette review of CT series</source>
        <translation>Isoflächen- und Silhouettenbefundung von CT-Serien</translation>
    </message>
    <message>
        <source>DICOM folder, DICOMDIR, file, volume or phantom:N to review at once</source>
        <translation>DICOM-Ordner, DICOMDIR, Datei, Volumen oder phantom:N, sofort zu befunden</translation>
    </message>
    <message>
        <source>Iso-value in HU.</source>
        <translation>Iso-Wert in HU.</translation>
    </message>
    <message>
        <source>Series instance UID.</source>
        <translation>Series Instance UID.</translation>
    </message>
    <message>
        <source>Study database file.</source>
        <translation>Datei der Studiendatenbank.</translation>
    </message>
</context>
</TS>
