<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="ro">
<context>
    <name>QObject</name>
    <message>
        <source>out of memory at iso-value %1 HU: choose a higher iso-value or chunking (settings)</source>
        <translation>memorie insuficientă la valoarea izo %1 HU: alegeți o valoare izo mai mare sau împărțirea în blocuri (setări)</translation>
    </message>
    <message>
        <source>internal error: %1</source>
        <translation>eroare internă: %1</translation>
    </message>
    <message>
        <source>Bone</source>
        <translation>Os</translation>
    </message>
    <message>
        <source>Skin</source>
        <translation>Piele</translation>
    </message>
    <message>
        <source>System language</source>
        <translation>Limba sistemului</translation>
    </message>
    <message>
        <source>%1: out of memory rendering %2 x %3 pixels; choose a smaller size</source>
        <translation>%1: memorie insuficientă pentru randarea a %2 x %3 pixeli; alegeți o dimensiune mai mică</translation>
    </message>
    <message>
        <source>Created %1 with Linework %2 — page %3 of %4</source>
        <translation>Creat %1 cu Linework %2 — pagina %3 din %4</translation>
    </message>
    <message>
        <source>Annotations and measurements</source>
        <translation>Adnotări și măsurători</translation>
    </message>
    <message>
        <source>none</source>
        <translation>niciuna</translation>
    </message>
    <message>
        <source>#</source>
        <translation>Nr.</translation>
    </message>
    <message>
        <source>Type</source>
        <translation>Tip</translation>
    </message>
    <message>
        <source>Text</source>
        <translation>Text</translation>
    </message>
    <message>
        <source>Measurement</source>
        <translation>Măsurătoare</translation>
    </message>
    <message>
        <source>Points (LPS, mm)</source>
        <translation>Puncte (LPS, mm)</translation>
    </message>
    <message>
        <source>Comment</source>
        <translation>Comentariu</translation>
    </message>
    <message>
        <source>(none)</source>
        <translation>(niciunul)</translation>
    </message>
    <message>
        <source>Patient</source>
        <translation>Pacient</translation>
    </message>
    <message>
        <source>(anonymised)</source>
        <translation>(anonimizat)</translation>
    </message>
    <message>
        <source>Patient ID</source>
        <translation>ID pacient</translation>
    </message>
    <message>
        <source>Birth date, sex</source>
        <translation>Data nașterii, sexul</translation>
    </message>
    <message>
        <source>Accession</source>
        <translation>Număr de acces</translation>
    </message>
    <message>
        <source>Study</source>
        <translation>Studiu</translation>
    </message>
    <message>
        <source>Series</source>
        <translation>Serie</translation>
    </message>
    <message>
        <source>Source</source>
        <translation>Sursă</translation>
    </message>
    <message>
        <source>Rendering</source>
        <translation>Randare</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Data</translation>
    </message>
    <message>
        <source>Linework report</source>
        <translation>Raport Linework</translation>
    </message>
    <message>
        <source>Text:</source>
        <translation>Text:</translation>
    </message>
    <message>
        <source>%1 exists. Replace it?</source>
        <translation>%1 există deja. O înlocuiți?</translation>
    </message>
    <message>
        <source>%1 holds a Secondary Capture already (%2). Replace it?</source>
        <translation>%1 conține deja o Secondary Capture (%2). O înlocuiți?</translation>
    </message>
    <message>
        <source>Exporting %1 at %2 x %3…</source>
        <translation>Se exportă %1 la %2 x %3…</translation>
    </message>
    <message>
        <source>%1: a Secondary Capture joins the source&apos;s study, and %2 is not a DICOM series</source>
        <translation>%1: o Secondary Capture se alătură studiului sursei, iar %2 nu este o serie DICOM</translation>
    </message>
    <message>
        <source>label</source>
        <translation>etichetă</translation>
    </message>
    <message>
        <source>arrow</source>
        <translation>săgeată</translation>
    </message>
    <message>
        <source>ruler</source>
        <translation>riglă</translation>
    </message>
    <message>
        <source>angle</source>
        <translation>unghi</translation>
    </message>
    <message>
        <source>3D panels</source>
        <translation>Panouri 3D</translation>
    </message>
    <message>
        <source>3D panels and slices</source>
        <translation>Panouri 3D și secțiuni</translation>
    </message>
    <message>
        <source>Surface at %1</source>
        <translation>Suprafață la %1</translation>
    </message>
    <message>
        <source>Drag: rotate · Shift/middle drag: pan · wheel/right drag: zoom · Ctrl drag: roll · Shift+click: linked cursor</source>
        <translation>Tragere: rotire · Shift sau butonul din mijloc + tragere: deplasare · rotiță sau butonul drept + tragere: zoom · Ctrl + tragere: ruliu · Shift+clic: cursor legat</translation>
    </message>
    <message>
        <source>Soft tissue</source>
        <translation>Țesut moale</translation>
    </message>
    <message>
        <source>Lung</source>
        <translation>Plămân</translation>
    </message>
    <message>
        <source>Brain</source>
        <translation>Creier</translation>
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
        <translation>Coronal</translation>
    </message>
    <message>
        <source>Sagittal</source>
        <translation>Sagital</translation>
    </message>
    <message>
        <source>stored units</source>
        <translation>unități stocate</translation>
    </message>
    <message>
        <source>%1 stored units</source>
        <translation>%1, unități stocate</translation>
    </message>
    <message>
        <source>Silhouette and axial slice</source>
        <translation>Siluetă și secțiune axială</translation>
    </message>
    <message>
        <source>Silhouette and coronal slice</source>
        <translation>Siluetă și secțiune coronală</translation>
    </message>
    <message>
        <source>Silhouette and sagittal slice</source>
        <translation>Siluetă și secțiune sagitală</translation>
    </message>
    <message>
        <source>Nothing was sent to %1: %2</source>
        <translation>Nimic nu a fost trimis la %1: %2</translation>
    </message>
    <message>
        <source>%1 answered:</source>
        <translation>Răspunsul de la %1:</translation>
    </message>
    <message>
        <source>No PACS node is configured: add one in Settings (%1)</source>
        <translation>Niciun nod PACS configurat: adăugați unul în Setări (%1)</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationActions</name>
    <message>
        <source>&amp;Text label</source>
        <translation>Etichetă &amp;text</translation>
    </message>
    <message>
        <source>T</source>
        <translation>T</translation>
    </message>
    <message>
        <source>&amp;Arrow</source>
        <translation>S&amp;ăgeată</translation>
    </message>
    <message>
        <source>A</source>
        <translation>A</translation>
    </message>
    <message>
        <source>&amp;Ruler</source>
        <translation>&amp;Riglă</translation>
    </message>
    <message>
        <source>R</source>
        <translation>R</translation>
    </message>
    <message>
        <source>An&amp;gle</source>
        <translation>&amp;Unghi</translation>
    </message>
    <message>
        <source>G</source>
        <translation>G</translation>
    </message>
    <message>
        <source>&amp;Cancel tool</source>
        <translation>Anulează &amp;instrumentul</translation>
    </message>
    <message>
        <source>&amp;Delete annotation</source>
        <translation>Șter&amp;ge adnotarea</translation>
    </message>
    <message>
        <source>&amp;Edit text…</source>
        <translation>&amp;Editează textul…</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationDocument</name>
    <message>
        <source>Add %1</source>
        <translation>Adaugă %1</translation>
    </message>
    <message>
        <source>Delete %1</source>
        <translation>Șterge %1</translation>
    </message>
    <message>
        <source>Move %1 point</source>
        <translation>Mută punctul (%1)</translation>
    </message>
    <message>
        <source>Edit %1 text</source>
        <translation>Editează textul (%1)</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationPersistence</name>
    <message>
        <source>Annotations not loaded, and not saved for this series so the stored ones are kept: %1</source>
        <translation>Adnotările nu au fost încărcate și nu se salvează pentru această serie, ca să se păstreze cele stocate: %1</translation>
    </message>
    <message>
        <source>Annotations not saved: %1</source>
        <translation>Adnotările nu au fost salvate: %1</translation>
    </message>
</context>
<context>
    <name>lw::gui::AnnotationToolController</name>
    <message>
        <source>Text of the %1</source>
        <translation>Textul (%1)</translation>
    </message>
    <message>
        <source>A text label needs a text: delete it with Del instead</source>
        <translation>O etichetă text are nevoie de un text: ștergeți-o cu Del</translation>
    </message>
    <message>
        <source>Text label: click the point on the surface to label</source>
        <translation>Etichetă text: faceți clic pe punctul de pe suprafață de etichetat</translation>
    </message>
    <message>
        <source>Arrow: click where its tail goes</source>
        <translation>Săgeată: faceți clic unde începe coada ei</translation>
    </message>
    <message>
        <source>Arrow: click the point it shows (Esc cancels)</source>
        <translation>Săgeată: faceți clic pe punctul indicat (Esc anulează)</translation>
    </message>
    <message>
        <source>Ruler: click the first point on the surface</source>
        <translation>Riglă: faceți clic pe primul punct de pe suprafață</translation>
    </message>
    <message>
        <source>Ruler: click the second point (Esc cancels)</source>
        <translation>Riglă: faceți clic pe al doilea punct (Esc anulează)</translation>
    </message>
    <message>
        <source>Angle: click the end of the first arm</source>
        <translation>Unghi: faceți clic pe capătul primei laturi</translation>
    </message>
    <message>
        <source>Angle: click the vertex (Esc cancels)</source>
        <translation>Unghi: faceți clic pe vârf (Esc anulează)</translation>
    </message>
    <message>
        <source>Angle: click the end of the second arm (Esc cancels)</source>
        <translation>Unghi: faceți clic pe capătul celei de-a doua laturi (Esc anulează)</translation>
    </message>
    <message>
        <source>No surface under the pointer: click on the surface</source>
        <translation>Nicio suprafață sub cursor: faceți clic pe suprafață</translation>
    </message>
    <message>
        <source>Text label</source>
        <translation>Etichetă text</translation>
    </message>
    <message>
        <source>No surface under the pointer: the point stays where it was</source>
        <translation>Nicio suprafață sub cursor: punctul rămâne unde era</translation>
    </message>
    <message>
        <source>Click where the first point is: every point of one annotation lies on the same slice, or in 3D (Esc cancels)</source>
        <translation>Faceți clic acolo unde este primul punct: toate punctele unei adnotări se află pe aceeași secțiune sau în 3D (Esc anulează)</translation>
    </message>
    <message>
        <source>Not on the slice: the point stays where it was</source>
        <translation>Nu este pe secțiune: punctul rămâne unde era</translation>
    </message>
    <message>
        <source>Not on the slice: click on the slice&apos;s image</source>
        <translation>Nu este pe secțiune: faceți clic pe imaginea secțiunii</translation>
    </message>
</context>
<context>
    <name>lw::gui::Annotations</name>
    <message>
        <source>text label</source>
        <translation>etichetă text</translation>
    </message>
    <message>
        <source>arrow</source>
        <translation>săgeată</translation>
    </message>
    <message>
        <source>ruler</source>
        <translation>riglă</translation>
    </message>
    <message>
        <source>angle</source>
        <translation>unghi</translation>
    </message>
</context>
<context>
    <name>lw::gui::ExportActions</name>
    <message>
        <source>&amp;Export PNG…</source>
        <translation>&amp;Exportă PNG…</translation>
    </message>
    <message>
        <source>Ctrl+E</source>
        <translation>Ctrl+E</translation>
    </message>
    <message>
        <source>Export &amp;report (PDF)…</source>
        <translation>Exportă r&amp;aportul (PDF)…</translation>
    </message>
    <message>
        <source>Ctrl+Shift+E</source>
        <translation>Ctrl+Shift+E</translation>
    </message>
    <message>
        <source>Export Secondary &amp;Capture (DICOM)…</source>
        <translation>Exportă Secondary &amp;Capture (DICOM)…</translation>
    </message>
    <message>
        <source>Open a review to export it</source>
        <translation>Deschideți o examinare pentru a o exporta</translation>
    </message>
    <message>
        <source>Exported %1</source>
        <translation>S-a exportat %1</translation>
    </message>
    <message>
        <source>Export failed</source>
        <translation>Exportul a eșuat</translation>
    </message>
    <message>
        <source>Export PNG</source>
        <translation>Exportă PNG</translation>
    </message>
    <message>
        <source>PNG images (*.png)</source>
        <translation>Imagini PNG (*.png)</translation>
    </message>
    <message>
        <source>Export report</source>
        <translation>Exportă raportul</translation>
    </message>
    <message>
        <source>PDF documents (*.pdf)</source>
        <translation>Documente PDF (*.pdf)</translation>
    </message>
    <message>
        <source>A Secondary Capture joins the source&apos;s study, and %1 is not a DICOM series</source>
        <translation>O Secondary Capture se alătură studiului sursei, iar %1 nu este o serie DICOM</translation>
    </message>
    <message>
        <source>Export Secondary Capture</source>
        <translation>Exportă Secondary Capture</translation>
    </message>
    <message>
        <source>Folder for the Secondary Capture</source>
        <translation>Dosarul pentru Secondary Capture</translation>
    </message>
    <message>
        <source>a Secondary Capture into %1</source>
        <translation>o Secondary Capture în %1</translation>
    </message>
</context>
<context>
    <name>lw::gui::HistogramView</name>
    <message>
        <source>Histogram of the volume (log counts); click to set the iso-value</source>
        <translation>Histograma volumului (frecvențe logaritmice); faceți clic pentru a seta valoarea izo</translation>
    </message>
</context>
<context>
    <name>lw::gui::IsoControl</name>
    <message>
        <source>Iso-value (HU)</source>
        <translation>Valoare izo (HU)</translation>
    </message>
    <message>
        <source> HU</source>
        <translation> HU</translation>
    </message>
    <message>
        <source>Iso-value:</source>
        <translation>Valoare izo:</translation>
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
        <translation>Studii</translation>
    </message>
    <message>
        <source>Opening cancelled</source>
        <translation>Deschiderea a fost anulată</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Anulează</translation>
    </message>
    <message>
        <source>&amp;File</source>
        <translation>&amp;Fișier</translation>
    </message>
    <message>
        <source>Main</source>
        <translation>Bara principală</translation>
    </message>
    <message>
        <source>Import &amp;folder…</source>
        <translation>&amp;Importă un dosar…</translation>
    </message>
    <message>
        <source>Ctrl+I</source>
        <translation>Ctrl+I</translation>
    </message>
    <message>
        <source>Import &amp;DICOMDIR…</source>
        <translation>Importă un &amp;DICOMDIR…</translation>
    </message>
    <message>
        <source>Ctrl+Shift+I</source>
        <translation>Ctrl+Shift+I</translation>
    </message>
    <message>
        <source>&amp;Open path without importing…</source>
        <translation>Desc&amp;hide o cale fără import…</translation>
    </message>
    <message>
        <source>&amp;Settings…</source>
        <translation>&amp;Setări…</translation>
    </message>
    <message>
        <source>Ctrl+,</source>
        <translation>Ctrl+,</translation>
    </message>
    <message>
        <source>&amp;Close review</source>
        <translation>Închide e&amp;xaminarea</translation>
    </message>
    <message>
        <source>&amp;Quit</source>
        <translation>Ieși&amp;re</translation>
    </message>
    <message>
        <source>&amp;View</source>
        <translation>&amp;Vizualizare</translation>
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
        <translation>S&amp;tânga</translation>
    </message>
    <message>
        <source>&amp;Right</source>
        <translation>&amp;Dreapta</translation>
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
        <translation>&amp;Resetează camera</translation>
    </message>
    <message>
        <source>&amp;Studies</source>
        <translation>St&amp;udii</translation>
    </message>
    <message>
        <source>Opening %1</source>
        <translation>Se deschide %1</translation>
    </message>
    <message>
        <source>Series %1 has no image files in the database: re-import its folder</source>
        <translation>Seria %1 nu are fișiere de imagine în baza de date: importați din nou dosarul ei</translation>
    </message>
    <message>
        <source>Opening series</source>
        <translation>Se deschide seria</translation>
    </message>
    <message>
        <source>Open a DICOM folder without importing it</source>
        <translation>Deschideți un dosar DICOM fără a-l importa</translation>
    </message>
    <message>
        <source>Cannot open</source>
        <translation>Nu se poate deschide</translation>
    </message>
    <message>
        <source>&amp;Annotate</source>
        <translation>&amp;Adnotări</translation>
    </message>
    <message>
        <source>&amp;Edit</source>
        <translation>&amp;Editare</translation>
    </message>
    <message>
        <source>&amp;Undo</source>
        <translation>&amp;Anulează</translation>
    </message>
    <message>
        <source>Ctrl+Z</source>
        <translation>Ctrl+Z</translation>
    </message>
    <message>
        <source>&amp;Redo</source>
        <translation>&amp;Refă</translation>
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
        <translation>%1 este deja deschis</translation>
    </message>
    <message>
        <source>Annotations will not be saved: %1</source>
        <translation>Adnotările nu vor fi salvate: %1</translation>
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
        <translation>Trimite la &amp;PACS…</translation>
    </message>
    <message>
        <source>Store the Secondary Capture and the report (Encapsulated PDF) in the patient&apos;s study on the PACS</source>
        <translation>Salvează Secondary Capture și raportul (Encapsulated PDF) în studiul pacientului din PACS</translation>
    </message>
    <message>
        <source>Open a review to send it to the PACS</source>
        <translation>Deschideți o examinare pentru a o trimite la PACS</translation>
    </message>
    <message>
        <source>A send to the PACS is still running</source>
        <translation>O trimitere la PACS este încă în curs</translation>
    </message>
    <message>
        <source>Send to PACS</source>
        <translation>Trimite la PACS</translation>
    </message>
    <message>
        <source>Sending to %1…</source>
        <translation>Se trimite la %1…</translation>
    </message>
    <message>
        <source>Sent to %1</source>
        <translation>Trimis la %1</translation>
    </message>
    <message>
        <source>Sending to %1 failed</source>
        <translation>Trimiterea la %1 a eșuat</translation>
    </message>
</context>
<context>
    <name>lw::gui::PacsSender</name>
    <message>
        <source>Cannot create a temporary folder for the objects to send: %1</source>
        <translation>Nu se poate crea un dosar temporar pentru obiectele de trimis: %1</translation>
    </message>
    <message>
        <source>Secondary Capture</source>
        <translation>Secondary Capture</translation>
    </message>
    <message>
        <source>Report (Encapsulated PDF)</source>
        <translation>Raport (Encapsulated PDF)</translation>
    </message>
    <message>
        <source>A send to the PACS is still running</source>
        <translation>O trimitere la PACS este încă în curs</translation>
    </message>
    <message>
        <source>An anonymised export cannot be sent to the PACS because it would no longer belong to the patient&apos;s study</source>
        <translation>Un export anonimizat nu poate fi trimis la PACS, deoarece nu ar mai aparține studiului pacientului</translation>
    </message>
    <message>
        <source>Only a review of a DICOM series can be sent to the PACS: %1 has no study to join</source>
        <translation>Doar examinarea unei serii DICOM poate fi trimisă la PACS: %1 nu aparține niciunui studiu</translation>
    </message>
</context>
<context>
    <name>lw::gui::PacsSettingsPage</name>
    <message>
        <source>Where the workstation receives a C-MOVE&apos;s images; the PACS must list this AE title with this host and port</source>
        <translation>Aici primește stația imaginile unui C-MOVE; PACS-ul trebuie să cunoască acest titlu AE cu această gazdă și port</translation>
    </message>
    <message>
        <source>Workstation AE title:</source>
        <translation>Titlul AE al stației:</translation>
    </message>
    <message>
        <source>Storage port (C-MOVE):</source>
        <translation>Port de recepție (C-MOVE):</translation>
    </message>
    <message>
        <source>Name</source>
        <translation>Nume</translation>
    </message>
    <message>
        <source>Called AE title</source>
        <translation>Titlu AE apelat</translation>
    </message>
    <message>
        <source>Host</source>
        <translation>Gazdă</translation>
    </message>
    <message>
        <source>Port</source>
        <translation>Port</translation>
    </message>
    <message>
        <source>PACS nodes:</source>
        <translation>Noduri PACS:</translation>
    </message>
    <message>
        <source>Saved in %1</source>
        <translation>Salvat în %1</translation>
    </message>
    <message>
        <source>Add</source>
        <translation>Adaugă</translation>
    </message>
    <message>
        <source>Remove</source>
        <translation>Elimină</translation>
    </message>
    <message>
        <source>Test</source>
        <translation>Testează</translation>
    </message>
    <message>
        <source>Sends a C-ECHO to the selected node</source>
        <translation>Trimite un C-ECHO nodului selectat</translation>
    </message>
    <message>
        <source>Not saved: %1</source>
        <translation>Nesalvat: %1</translation>
    </message>
    <message>
        <source>node %1</source>
        <translation>nod %1</translation>
    </message>
    <message>
        <source>Select a node to test</source>
        <translation>Selectați un nod de testat</translation>
    </message>
    <message>
        <source>A test runs</source>
        <translation>Un test rulează</translation>
    </message>
    <message>
        <source>Testing %1…</source>
        <translation>Se testează %1…</translation>
    </message>
    <message>
        <source>Test: %1</source>
        <translation>Test: %1</translation>
    </message>
    <message>
        <source>Test failed: %1</source>
        <translation>Test eșuat: %1</translation>
    </message>
    <message>
        <source>Retrieve by</source>
        <translation>Preluare prin</translation>
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
        <translation>C-MOVE trimite imaginile la portul de stocare de mai sus: PACS-ul trebuie să cunoască titlul AE al acestei stații de lucru, cu gazda și portul ei</translation>
    </message>
</context>
<context>
    <name>lw::gui::PictureExportDialog</name>
    <message>
        <source>Both panels side by side</source>
        <translation>Ambele panouri alăturate</translation>
    </message>
    <message>
        <source>Iso-surface panel</source>
        <translation>Panoul izosuprafeței</translation>
    </message>
    <message>
        <source>Silhouette panel</source>
        <translation>Panoul siluetei</translation>
    </message>
    <message>
        <source> px</source>
        <translation> px</translation>
    </message>
    <message>
        <source>Picture:</source>
        <translation>Imagine:</translation>
    </message>
    <message>
        <source>Size of each panel:</source>
        <translation>Dimensiunea fiecărui panou:</translation>
    </message>
    <message>
        <source>The panels are rendered again at this size; lines, annotations and text grow with it.</source>
        <translation>Panourile sunt randate din nou la această dimensiune; liniile, adnotările și textul cresc proporțional.</translation>
    </message>
</context>
<context>
    <name>lw::gui::RemotePanel</name>
    <message>
        <source>Retrieve</source>
        <translation>Preluare</translation>
    </message>
    <message>
        <source>The PACS to query (Settings → PACS)</source>
        <translation>PACS-ul interogat (Setări → PACS)</translation>
    </message>
    <message>
        <source>Patient name (DOE^J*)</source>
        <translation>Numele pacientului (DOE^J*)</translation>
    </message>
    <message>
        <source>Patient ID</source>
        <translation>ID pacient</translation>
    </message>
    <message>
        <source>Dates YYYYMMDD-YYYYMMDD</source>
        <translation>Date AAAALLZZ-AAAALLZZ</translation>
    </message>
    <message>
        <source>Modality in the study (empty: any)</source>
        <translation>Modalitate în studiu (gol: oricare)</translation>
    </message>
    <message>
        <source>Search PACS</source>
        <translation>Caută în PACS</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Anulează</translation>
    </message>
    <message>
        <source>The PACS nodes cannot be read: %1</source>
        <translation>Nodurile PACS nu pot fi citite: %1</translation>
    </message>
    <message>
        <source>no PACS: Settings → PACS</source>
        <translation>niciun PACS: Setări → PACS</translation>
    </message>
    <message>
        <source>Choose a PACS node (Settings → PACS adds one)</source>
        <translation>Alegeți un nod PACS (Setări → PACS adaugă unul)</translation>
    </message>
    <message>
        <source>Dates: %1</source>
        <translation>Date: %1</translation>
    </message>
    <message>
        <source>Searching %1…</source>
        <translation>Se caută în %1…</translation>
    </message>
    <message>
        <source>Studies found on %1: %2</source>
        <translation>Studii găsite pe %1: %2</translation>
    </message>
    <message>
        <source>Query cancelled</source>
        <translation>Interogare anulată</translation>
    </message>
    <message>
        <source>Query of %1 failed: %2</source>
        <translation>Interogarea %1 a eșuat: %2</translation>
    </message>
    <message>
        <source>Series query failed: %1</source>
        <translation>Interogarea seriilor a eșuat: %1</translation>
    </message>
    <message>
        <source>Retrieve series and open</source>
        <translation>Preia seria și deschide</translation>
    </message>
    <message>
        <source>Retrieve study</source>
        <translation>Preia studiul</translation>
    </message>
    <message>
        <source>%1 is no longer a PACS node</source>
        <translation>%1 nu mai este un nod PACS</translation>
    </message>
    <message>
        <source>A retrieve is running: wait for it or cancel it</source>
        <translation>O preluare rulează: așteptați-o sau anulați-o</translation>
    </message>
    <message>
        <source>Retrieving from %1…</source>
        <translation>Preluare de la %1…</translation>
    </message>
    <message>
        <source>Retrieving from %1: %2 of %3 images</source>
        <translation>Preluare de la %1: %2 din %3 imagini</translation>
    </message>
    <message>
        <source>%1 of %2 images are here (%3 were already)</source>
        <translation>%1 din %2 imagini sunt aici (%3 erau deja)</translation>
    </message>
    <message>
        <source>Retrieve cancelled: %1; a new retrieve fetches the others</source>
        <translation>Preluare anulată: %1; o nouă preluare aduce restul</translation>
    </message>
    <message>
        <source>Retrieved from %1: %2</source>
        <translation>Preluat de la %1: %2</translation>
    </message>
    <message>
        <source>Retrieve from %1 failed: %2</source>
        <translation>Preluarea de la %1 a eșuat: %2</translation>
    </message>
</context>
<context>
    <name>lw::gui::RemoteStudyModel</name>
    <message>
        <source>On %1: double-click to retrieve and open</source>
        <translation>Pe %1: dublu clic pentru preluare și deschidere</translation>
    </message>
    <message>
        <source>On %1: expand for its series, Retrieve in the context menu</source>
        <translation>Pe %1: extindeți pentru serii, Preluare în meniul contextual</translation>
    </message>
    <message>
        <source>Remote: %1</source>
        <translation>La distanță: %1</translation>
    </message>
    <message>
        <source>Modality</source>
        <translation>Modalitate</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Dată</translation>
    </message>
    <message>
        <source>Images</source>
        <translation>Imagini</translation>
    </message>
    <message>
        <source>Description</source>
        <translation>Descriere</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReportExportDialog</name>
    <message>
        <source>Export report</source>
        <translation>Exportă raportul</translation>
    </message>
    <message>
        <source>Findings, comparison, recommendation…</source>
        <translation>Constatări, comparație, recomandare…</translation>
    </message>
    <message>
        <source>Anonymise (leave out the patient&apos;s name, ID, birth date, sex and the accession number)</source>
        <translation>Anonimizează (omite numele, ID-ul, data nașterii și sexul pacientului, precum și numărul de acces)</translation>
    </message>
    <message>
        <source>Comment:</source>
        <translation>Comentariu:</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReviewArrangement</name>
    <message>
        <source>Layout of the review (Alt+1 … Alt+5)</source>
        <translation>Aranjarea examinării (Alt+1 … Alt+5)</translation>
    </message>
    <message>
        <source>Custom window</source>
        <translation>Fereastră proprie</translation>
    </message>
    <message>
        <source>Window %1, level %2 HU</source>
        <translation>Fereastră %1, nivel %2 HU</translation>
    </message>
    <message>
        <source>Window and level of the slices (right drag on a slice to adjust)</source>
        <translation>Fereastra și nivelul secțiunilor (tragere cu butonul drept pe o secțiune pentru ajustare)</translation>
    </message>
    <message>
        <source>Layout</source>
        <translation>Aranjare</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReviewPanel</name>
    <message>
        <source>OpenGL failed: %1</source>
        <translation>OpenGL a eșuat: %1</translation>
    </message>
    <message>
        <source>Out of memory uploading the surface to OpenGL</source>
        <translation>Memorie insuficientă la încărcarea suprafeței în OpenGL</translation>
    </message>
</context>
<context>
    <name>lw::gui::ReviewWidget</name>
    <message>
        <source>Rendering the surface at %1 HU…</source>
        <translation>Se randează suprafața la %1 HU…</translation>
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
        <translation>Stânga</translation>
    </message>
    <message>
        <source>Right</source>
        <translation>Dreapta</translation>
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
        <translation>Vedere %1</translation>
    </message>
    <message>
        <source>Reset</source>
        <translation>Resetează</translation>
    </message>
    <message>
        <source>Reset the camera (Home)</source>
        <translation>Resetează camera (Home)</translation>
    </message>
    <message>
        <source>No surface at %1 HU</source>
        <translation>Nicio suprafață la %1 HU</translation>
    </message>
    <message>
        <source>Method %1 · %2 · mode %3 · %4</source>
        <translation>Metoda %1 · %2 · modul %3 · %4</translation>
    </message>
    <message>
        <source>L (%1-cell bricks)</source>
        <translation>L (blocuri de %1 celule)</translation>
    </message>
    <message>
        <source> · marching cubes %1 ms</source>
        <translation> · marching cubes %1 ms</translation>
    </message>
    <message>
        <source> · GL iso %1 ms, silhouette %2 ms</source>
        <translation> · GL izo %1 ms, silueta %2 ms</translation>
    </message>
    <message>
        <source> · silhouette: extract %1, segments %2, visibility %3, draw %4 ms</source>
        <translation> · silueta: extragere %1, segmente %2, vizibilitate %3, desenare %4 ms</translation>
    </message>
    <message>
        <source> · GL iso %1 ms</source>
        <translation> · GL izo %1 ms</translation>
    </message>
    <message>
        <source> · iso shaded on the CPU %1 ms</source>
        <translation> · izo umbrită pe CPU %1 ms</translation>
    </message>
    <message>
        <source> · GL iso on the worker %1 ms</source>
        <translation> · GL izo pe firul de lucru %1 ms</translation>
    </message>
    <message>
        <source> · %1 triangles · %2 segments</source>
        <translation> · %1 triunghiuri · %2 segmente</translation>
    </message>
    <message>
        <source> · voxels split %1×%2×%3</source>
        <translation> · voxeli împărțiți %1×%2×%3</translation>
    </message>
    <message>
        <source> · iso shaded from the device&apos;s mesh %1 ms</source>
        <translation> · izo umbrită din rețeaua de pe GPU %1 ms</translation>
    </message>
    <message>
        <source>Linked cursor at %1</source>
        <translation>Cursor legat la %1</translation>
    </message>
    <message>
        <source>No surface under the pointer: Shift+click on the surface</source>
        <translation>Nicio suprafață sub cursor: Shift+clic pe suprafață</translation>
    </message>
</context>
<context>
    <name>lw::gui::SendToPacsDialog</name>
    <message>
        <source>Send to PACS</source>
        <translation>Trimite la PACS</translation>
    </message>
    <message>
        <source>PACS:</source>
        <translation>PACS:</translation>
    </message>
    <message>
        <source>The Secondary Capture and the report (as DICOM Encapsulated PDF) join the patient&apos;s study.</source>
        <translation>Secondary Capture și raportul (ca DICOM Encapsulated PDF) intră în studiul pacientului.</translation>
    </message>
</context>
<context>
    <name>lw::gui::SettingsDialog</name>
    <message>
        <source>Linework settings</source>
        <translation>Setări Linework</translation>
    </message>
    <message>
        <source>Method</source>
        <translation>Metodă</translation>
    </message>
    <message>
        <source>Appearance</source>
        <translation>Aspect</translation>
    </message>
    <message>
        <source>Iso presets</source>
        <translation>Presetări izo</translation>
    </message>
    <message>
        <source>Silhouette method:</source>
        <translation>Metoda siluetei:</translation>
    </message>
    <message>
        <source>Off: whole volume (S)</source>
        <translation>Oprit: volumul întreg (S)</translation>
    </message>
    <message>
        <source>Auto: chunked above the memory budget</source>
        <translation>Automat: pe blocuri peste bugetul de memorie</translation>
    </message>
    <message>
        <source>Fixed brick size (L)</source>
        <translation>Dimensiune fixă a blocului (L)</translation>
    </message>
    <message>
        <source>Chunking:</source>
        <translation>Împărțire în blocuri:</translation>
    </message>
    <message>
        <source> cells per brick</source>
        <translation> celule pe bloc</translation>
    </message>
    <message>
        <source>Brick size:</source>
        <translation>Dimensiunea blocului:</translation>
    </message>
    <message>
        <source> MiB</source>
        <translation> MiB</translation>
    </message>
    <message>
        <source>Memory budget:</source>
        <translation>Buget de memorie:</translation>
    </message>
    <message>
        <source>Automatic (free memory less a margin)</source>
        <translation>Automat (memoria liberă minus o rezervă)</translation>
    </message>
    <message>
        <source>Device memory a CUDA frame may use. Above it the volume streams through the GPU in slabs; below what one slab needs, the frame is drawn on the CPU.</source>
        <translation>Memoria dispozitivului pe care o poate folosi un cadru CUDA. Peste ea, volumul trece prin GPU în felii groase; sub cât necesită o felie, cadrul este desenat pe CPU.</translation>
    </message>
    <message>
        <source>GPU memory budget:</source>
        <translation>Buget de memorie GPU:</translation>
    </message>
    <message>
        <source>a: extract when the iso-value changes</source>
        <translation>a: extrage când se schimbă valoarea izo</translation>
    </message>
    <message>
        <source>b: extract every frame</source>
        <translation>b: extrage la fiecare cadru</translation>
    </message>
    <message>
        <source>Mode:</source>
        <translation>Mod:</translation>
    </message>
    <message>
        <source>Hide occluded silhouette lines</source>
        <translation>Ascunde liniile de siluetă acoperite</translation>
    </message>
    <message>
        <source>Visibility:</source>
        <translation>Vizibilitate:</translation>
    </message>
    <message>
        <source>Test along each segment (method 2), not only its ends</source>
        <translation>Testează de-a lungul fiecărui segment (metoda 2), nu doar la capete</translation>
    </message>
    <message>
        <source> px</source>
        <translation> px</translation>
    </message>
    <message>
        <source>Keep every line pixel</source>
        <translation>Păstrează fiecare pixel de linie</translation>
    </message>
    <message>
        <source>Line fragments with fewer pixels are dropped: the speckle that noise on nearly flat surfaces draws. Contours are longer.</source>
        <translation>Fragmentele de linie cu mai puțini pixeli sunt eliminate: punctele pe care zgomotul le desenează pe suprafețele aproape plane. Contururile sunt mai lungi.</translation>
    </message>
    <message>
        <source>Drop strokes under:</source>
        <translation>Elimină trăsăturile sub:</translation>
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
        <translation>Automat</translation>
    </message>
    <message>
        <source>Back-end:</source>
        <translation>Backend:</translation>
    </message>
    <message>
        <source>CUDA is not available: %1</source>
        <translation>CUDA nu este disponibil: %1</translation>
    </message>
    <message>
        <source>Line width:</source>
        <translation>Grosimea liniei:</translation>
    </message>
    <message>
        <source>Line colour:</source>
        <translation>Culoarea liniei:</translation>
    </message>
    <message>
        <source>Background:</source>
        <translation>Fundal:</translation>
    </message>
    <message>
        <source>Draw the silhouette over the iso-surface panel too</source>
        <translation>Desenează silueta și peste panoul izosuprafeței</translation>
    </message>
    <message>
        <source>Overlay:</source>
        <translation>Suprapunere:</translation>
    </message>
    <message>
        <source>Perspective</source>
        <translation>Perspectivă</translation>
    </message>
    <message>
        <source>Orthographic</source>
        <translation>Ortografică</translation>
    </message>
    <message>
        <source>Projection:</source>
        <translation>Proiecție:</translation>
    </message>
    <message>
        <source>Auto: on the render thread with CUDA or software OpenGL, else in the panels</source>
        <translation>Automat: pe firul de randare cu CUDA sau OpenGL software, altfel în panouri</translation>
    </message>
    <message>
        <source>In the panels&apos; own OpenGL context</source>
        <translation>În contextul OpenGL propriu al panourilor</translation>
    </message>
    <message>
        <source>On the render thread (keeps the window responsive)</source>
        <translation>Pe firul de randare (fereastra rămâne receptivă)</translation>
    </message>
    <message>
        <source>Draw with OpenGL:</source>
        <translation>Desenare cu OpenGL:</translation>
    </message>
    <message>
        <source>This display&apos;s OpenGL: %1%2</source>
        <translation>OpenGL-ul acestui ecran: %1%2</translation>
    </message>
    <message>
        <source> (software)</source>
        <translation> (software)</translation>
    </message>
    <message>
        <source>This display offers no OpenGL 4.5 core context</source>
        <translation>Acest ecran nu oferă un context OpenGL 4.5 core</translation>
    </message>
    <message>
        <source>Language:</source>
        <translation>Limba:</translation>
    </message>
    <message>
        <source>A new language applies the next time Linework starts.</source>
        <translation>O limbă nouă se aplică la următoarea pornire a Linework.</translation>
    </message>
    <message>
        <source>Name</source>
        <translation>Nume</translation>
    </message>
    <message>
        <source>Iso-value (HU)</source>
        <translation>Valoare izo (HU)</translation>
    </message>
    <message>
        <source>Add</source>
        <translation>Adaugă</translation>
    </message>
    <message>
        <source>Remove</source>
        <translation>Elimină</translation>
    </message>
    <message>
        <source>Preset %1</source>
        <translation>Presetare %1</translation>
    </message>
    <message>
        <source>Choose a colour</source>
        <translation>Alegeți o culoare</translation>
    </message>
    <message>
        <source>Close the surface where the scan ends</source>
        <translation>Închide suprafața acolo unde se termină scanarea</translation>
    </message>
    <message>
        <source>Where the first or last slice cuts bone, the cut face becomes part of the surface and its edge is drawn as a line.</source>
        <translation>Acolo unde prima sau ultima secțiune taie osul, fața tăiată devine parte a suprafeței, iar marginea ei este desenată ca linie.</translation>
    </message>
    <message>
        <source>Volume border:</source>
        <translation>Marginea volumului:</translation>
    </message>
    <message>
        <source>Suggestive contours</source>
        <translation>Contururi sugestive</translation>
    </message>
    <message>
        <source>Also draw where the surface almost turns away from the view (concave folds, necks), beside the silhouette. On thick-slice CT they follow the slice steps.</source>
        <translation>Desenează pe lângă siluetă și locurile unde suprafața aproape se întoarce de la privitor (pliuri concave, gâtuiri). La CT cu secțiuni groase urmează treptele secțiunilor.</translation>
    </message>
    <message>
        <source>Smooth the normals (noisy scans)</source>
        <translation>Netezește normalele (scanări cu zgomot)</translation>
    </message>
    <message>
        <source>Normals from differences averaged over the neighbouring voxels (Sobel): fewer specks on noisy, thin-slice scans. Thick slices are smoothed within the slice only.</source>
        <translation>Normale din diferențe mediate peste voxelii vecini (Sobel): mai puține puncte izolate la scanările cu zgomot și secțiuni subțiri. Secțiunile groase sunt netezite doar în interiorul secțiunii.</translation>
    </message>
    <message>
        <source>Normals:</source>
        <translation>Normale:</translation>
    </message>
    <message>
        <source>Finer triangles on thick slices and coarse grids</source>
        <translation>Triunghiuri mai fine la secțiuni groase și grile grosiere</translation>
    </message>
    <message>
        <source>Splits the cells of a coarse axis (thick slices, a coarse grid) by linear interpolation, so the triangles follow the same surface closely and the lines lie on the shaded outline. No value is invented; costs some speed on such series.</source>
        <translation>Împarte celulele unei axe grosiere (secțiuni groase, o grilă grosieră) prin interpolare liniară, astfel încât triunghiurile urmează îndeaproape aceeași suprafață, iar liniile stau pe conturul umbrit. Nicio valoare nu este inventată; costă puțină viteză la astfel de serii.</translation>
    </message>
    <message>
        <source>Surface:</source>
        <translation>Suprafață:</translation>
    </message>
    <message>
        <source>Hidden lines, thin, dashed and grey</source>
        <translation>Linii ascunse, subțiri, întrerupte și gri</translation>
    </message>
    <message>
        <source>The technical-illustration convention: the parts of the silhouette behind the surface, under the visible lines</source>
        <translation>Convenția desenului tehnic: părțile siluetei din spatele suprafeței, sub liniile vizibile</translation>
    </message>
    <message>
        <source>Smooth across thick slices</source>
        <translation>Netezire peste secțiunile groase</translation>
    </message>
    <message>
        <source>Where the slices are three or more pixels apart, the surface between them joins the outlines of neighbouring slices smoothly (shape-based interpolation) instead of drawing straight lines between their grey values, so a skull drawn from a thick-slice series shows no terraces. Off: straight lines between the slices.</source>
        <translation>Acolo unde secțiunile sunt la trei sau mai mulți pixeli distanță, suprafața dintre ele unește lin contururile secțiunilor vecine (interpolare bazată pe formă), în loc să tragă linii drepte între valorile lor de gri; astfel, un craniu dintr-o serie cu secțiuni groase nu arată terase. Dezactivat: linii drepte între secțiuni.</translation>
    </message>
    <message>
        <source>Iso contour on slices:</source>
        <translation>Contur izo pe secțiuni:</translation>
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
        <translation>F %1 · N %2</translation>
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
        <translation>oricând</translation>
    </message>
    <message>
        <source>The study database cannot be opened: %1</source>
        <translation>Baza de date a studiilor nu poate fi deschisă: %1</translation>
    </message>
    <message>
        <source>Import folder…</source>
        <translation>Importă un dosar…</translation>
    </message>
    <message>
        <source>Import DICOMDIR…</source>
        <translation>Importă un DICOMDIR…</translation>
    </message>
    <message>
        <source>Remove from database</source>
        <translation>Elimină din baza de date</translation>
    </message>
    <message>
        <source>Removes the selected series from the database; the files on disk are kept</source>
        <translation>Elimină seriile selectate din baza de date; fișierele de pe disc sunt păstrate</translation>
    </message>
    <message>
        <source>Search patient, ID, description…</source>
        <translation>Căutați pacient, ID, descriere…</translation>
    </message>
    <message>
        <source>From</source>
        <translation>De la</translation>
    </message>
    <message>
        <source>to</source>
        <translation>până la</translation>
    </message>
    <message>
        <source>Cancel</source>
        <translation>Anulează</translation>
    </message>
    <message>
        <source>The study database cannot be read: %1</source>
        <translation>Baza de date a studiilor nu poate fi citită: %1</translation>
    </message>
    <message>
        <source>Cannot import %1: the study database is not open (%2)</source>
        <translation>%1 nu poate fi importat: baza de date a studiilor nu este deschisă (%2)</translation>
    </message>
    <message>
        <source>%1 will be imported after the current import</source>
        <translation>%1 va fi importat după importul în curs</translation>
    </message>
    <message>
        <source>Importing %1</source>
        <translation>Se importă %1</translation>
    </message>
    <message>
        <source>Importing %1…</source>
        <translation>Se importă %1…</translation>
    </message>
    <message>
        <source>Import a DICOM folder</source>
        <translation>Importați un dosar DICOM</translation>
    </message>
    <message>
        <source>Import a DICOMDIR</source>
        <translation>Importați un DICOMDIR</translation>
    </message>
    <message>
        <source>DICOMDIR (DICOMDIR dicomdir);;All files (*)</source>
        <translation>DICOMDIR (DICOMDIR dicomdir);;Toate fișierele (*)</translation>
    </message>
    <message>
        <source>Cancelling…</source>
        <translation>Se anulează…</translation>
    </message>
    <message>
        <source>Import of %1 cancelled; the database is unchanged</source>
        <translation>Importul din %1 a fost anulat; baza de date este neschimbată</translation>
    </message>
    <message>
        <source>Imported %1: %2 new, %3 updated series from %4 files</source>
        <translation>S-a importat %1: %2 serii noi, %3 actualizate, din %4 fișiere</translation>
    </message>
    <message>
        <source>… and %1 more</source>
        <translation>… și încă %1</translation>
    </message>
    <message>
        <source>%1. %2 file(s) could not be used:
%3</source>
        <translation>%1. %2 fișier(e) nu au putut fi folosite:
%3</translation>
    </message>
    <message>
        <source>%1: no DICOM series found</source>
        <translation>%1: nu s-a găsit nicio serie DICOM</translation>
    </message>
    <message>
        <source>Import of %1 failed: %2</source>
        <translation>Importul din %1 a eșuat: %2</translation>
    </message>
    <message>
        <source>Import failed: %1</source>
        <translation>Importul a eșuat: %1</translation>
    </message>
    <message numerus="yes">
        <source>Remove %n series from the study database?

The files on disk are kept; you can import them again.</source>
        <translation>
            <numerusform>Eliminați %n serie din baza de date a studiilor?

Fișierele de pe disc sunt păstrate; le puteți importa din nou.</numerusform>
            <numerusform>Eliminați %n serii din baza de date a studiilor?

Fișierele de pe disc sunt păstrate; le puteți importa din nou.</numerusform>
            <numerusform>Eliminați %n de serii din baza de date a studiilor?

Fișierele de pe disc sunt păstrate; le puteți importa din nou.</numerusform>
        </translation>
    </message>
    <message>
        <source>Cannot remove the series: %1</source>
        <translation>Seriile nu pot fi eliminate: %1</translation>
    </message>
    <message numerus="yes">
        <source>Removed %n series from the database (files on disk kept)</source>
        <translation>
            <numerusform>S-a eliminat %n serie din baza de date (fișierele de pe disc sunt păstrate)</numerusform>
            <numerusform>S-au eliminat %n serii din baza de date (fișierele de pe disc sunt păstrate)</numerusform>
            <numerusform>S-au eliminat %n de serii din baza de date (fișierele de pe disc sunt păstrate)</numerusform>
        </translation>
    </message>
    <message>
        <source>The files of series &quot;%1&quot; are missing (%2): import its folder again or remove it</source>
        <translation>Fișierele seriei „%1” lipsesc (%2): importați din nou dosarul ei sau eliminați-o</translation>
    </message>
    <message>
        <source>none referenced</source>
        <translation>niciunul înregistrat</translation>
    </message>
    <message>
        <source>%1 of %2 files of series &quot;%3&quot; are missing</source>
        <translation>Lipsesc %1 din %2 fișiere ale seriei „%3”</translation>
    </message>
    <message numerus="yes">
        <source>%n series selected</source>
        <translation>
            <numerusform>%n serie selectată</numerusform>
            <numerusform>%n serii selectate</numerusform>
            <numerusform>%n de serii selectate</numerusform>
        </translation>
    </message>
    <message>
        <source>no thumbnail</source>
        <translation>fără miniatură</translation>
    </message>
    <message>
        <source>Description</source>
        <translation>Descriere</translation>
    </message>
    <message>
        <source>Modality</source>
        <translation>Modalitate</translation>
    </message>
    <message>
        <source>Series number</source>
        <translation>Numărul seriei</translation>
    </message>
    <message>
        <source>Study date</source>
        <translation>Data studiului</translation>
    </message>
    <message>
        <source>Slices</source>
        <translation>Secțiuni</translation>
    </message>
    <message>
        <source>Files</source>
        <translation>Fișiere</translation>
    </message>
    <message>
        <source>Dimensions</source>
        <translation>Dimensiuni</translation>
    </message>
    <message>
        <source>Spacing</source>
        <translation>Spațiere</translation>
    </message>
    <message>
        <source>Gantry tilt</source>
        <translation>Înclinarea gantry-ului</translation>
    </message>
    <message>
        <source>Slice gaps</source>
        <translation>Distanțe între secțiuni</translation>
    </message>
    <message>
        <source>uneven, %1 to %2 mm</source>
        <translation>neuniforme, între %1 și %2 mm</translation>
    </message>
    <message>
        <source>even (%1 mm)</source>
        <translation>uniforme (%1 mm)</translation>
    </message>
    <message>
        <source>Missing slices</source>
        <translation>Secțiuni lipsă</translation>
    </message>
    <message>
        <source>Volumes</source>
        <translation>Volume</translation>
    </message>
    <message>
        <source>Imported from</source>
        <translation>Importat din</translation>
    </message>
    <message>
        <source>Imported at</source>
        <translation>Importat la</translation>
    </message>
    <message>
        <source>Series UID</source>
        <translation>UID serie</translation>
    </message>
    <message>
        <source>Warnings</source>
        <translation>Avertismente</translation>
    </message>
    <message>
        <source>Files that could not be used</source>
        <translation>Fișiere care nu au putut fi folosite</translation>
    </message>
</context>
<context>
    <name>lw::gui::StudyTreeModel</name>
    <message>
        <source>Patient / study / series</source>
        <translation>Pacient / studiu / serie</translation>
    </message>
    <message>
        <source>Modality</source>
        <translation>Modalitate</translation>
    </message>
    <message>
        <source>Date</source>
        <translation>Data</translation>
    </message>
    <message>
        <source>Slices</source>
        <translation>Secțiuni</translation>
    </message>
    <message>
        <source>Dimensions</source>
        <translation>Dimensiuni</translation>
    </message>
    <message>
        <source>Spacing (mm)</source>
        <translation>Spațiere (mm)</translation>
    </message>
    <message>
        <source>Warnings</source>
        <translation>Avertismente</translation>
    </message>
    <message>
        <source>%1: %2</source>
        <translation>%1: %2</translation>
    </message>
    <message>
        <source>(no description)</source>
        <translation>(fără descriere)</translation>
    </message>
    <message>
        <source>(no name)</source>
        <translation>(fără nume)</translation>
    </message>
    <message>
        <source>Study %1</source>
        <translation>Studiul %1</translation>
    </message>
</context>
<context>
    <name>lw::gui::VolumeLoader</name>
    <message>
        <source>out of memory while loading the volume</source>
        <translation>memorie insuficientă la încărcarea volumului</translation>
    </message>
</context>
<context>
    <name>lw::render::SilhouetteMethod</name>
    <message>
        <source>Method 1: marching cubes + geometry shader</source>
        <translation>Metoda 1: marching cubes + geometry shader</translation>
    </message>
    <message>
        <source>Method 2: silhouette only + ray-cast visibility</source>
        <translation>Metoda 2: doar silueta + vizibilitate prin ray casting</translation>
    </message>
    <message>
        <source>Method 3: own z-buffer rasterizer</source>
        <translation>Metoda 3: rasterizator propriu cu z-buffer</translation>
    </message>
</context>
<context>
    <name>main</name>
    <message>
        <source>Iso-surface and silhouette review of CT series</source>
        <translation>Examinarea seriilor CT ca izosuprafață și siluetă</translation>
    </message>
    <message>
        <source>DICOM folder, DICOMDIR, file, volume or phantom:N to review at once</source>
        <translation>Dosar DICOM, DICOMDIR, fișier, volum sau phantom:N de examinat imediat</translation>
    </message>
    <message>
        <source>Iso-value in HU.</source>
        <translation>Valoarea izo în HU.</translation>
    </message>
    <message>
        <source>Series instance UID.</source>
        <translation>Series Instance UID.</translation>
    </message>
    <message>
        <source>Study database file.</source>
        <translation>Fișierul bazei de date a studiilor.</translation>
    </message>
</context>
</TS>
