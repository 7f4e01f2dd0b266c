-- A study database as Linework wrote it at schema version 1 (commit a5d5716, before annotations
-- were stored): StudyDatabase::write of two series, a warning and an import problem, dumped
-- with sqlite3 .dump (which leaves out PRAGMA user_version: added by hand before COMMIT).
-- The migration test loads it one statement per line.
PRAGMA foreign_keys=OFF;
BEGIN TRANSACTION;
CREATE TABLE patients ( id INTEGER PRIMARY KEY, patient_key TEXT NOT NULL UNIQUE, patient_id TEXT NOT NULL, name TEXT NOT NULL, birth_date TEXT, sex TEXT);
INSERT INTO patients VALUES(1,'LW-V1Schema^One','LW-V1','Schema^One','19700101','F');
CREATE TABLE studies ( id INTEGER PRIMARY KEY, uid TEXT NOT NULL UNIQUE, patient_ref INTEGER NOT NULL REFERENCES patients(id) ON DELETE CASCADE, study_id TEXT, description TEXT, date TEXT, time TEXT, accession TEXT);
INSERT INTO studies VALUES(1,'1.2.826.0.1.3680043.10.1001',1,NULL,'CT head','20240102','101500','ACC1');
CREATE TABLE series ( id INTEGER PRIMARY KEY, uid TEXT NOT NULL UNIQUE, study_ref INTEGER NOT NULL REFERENCES studies(id) ON DELETE CASCADE, modality TEXT, description TEXT, number INTEGER, slice_count INTEGER NOT NULL DEFAULT 0, file_count INTEGER NOT NULL DEFAULT 0, dim_x INTEGER, dim_y INTEGER, dim_z INTEGER, spacing_x REAL, spacing_y REAL, spacing_z REAL, tilt_degrees REAL, uneven_gaps INTEGER NOT NULL DEFAULT 0, min_gap REAL, max_gap REAL, missing_slices INTEGER NOT NULL DEFAULT 0, volume_count INTEGER NOT NULL DEFAULT 0, thumbnail BLOB, source_root TEXT, imported_at TEXT);
INSERT INTO series VALUES(1,'1.2.826.0.1.3680043.10.1001.1',1,'CT','bone',1,3,3,16,16,3,0.5,0.5,1.25,12.0,0,0.0,0.0,0,1,NULL,'/data/pacs-export','2026-11-23T18:10:23Z');
INSERT INTO series VALUES(2,'1.2.826.0.1.3680043.10.1001.2',1,'CT','soft tissue',2,3,3,16,16,3,0.5,0.5,1.25,0.0,0,0.0,0.0,0,1,NULL,'/data/pacs-export','2026-11-23T18:10:23Z');
CREATE TABLE series_files ( id INTEGER PRIMARY KEY, series_ref INTEGER NOT NULL REFERENCES series(id) ON DELETE CASCADE, path TEXT NOT NULL, sop_uid TEXT);
INSERT INTO series_files VALUES(1,1,'/data/pacs-export/s1/IM0.dcm','1.2.826.0.1.3680043.10.1001.1.0');
INSERT INTO series_files VALUES(2,1,'/data/pacs-export/s1/IM1.dcm','1.2.826.0.1.3680043.10.1001.1.1');
INSERT INTO series_files VALUES(3,1,'/data/pacs-export/s1/IM2.dcm','1.2.826.0.1.3680043.10.1001.1.2');
INSERT INTO series_files VALUES(4,2,'/data/pacs-export/s2/IM0.dcm','1.2.826.0.1.3680043.10.1001.2.0');
INSERT INTO series_files VALUES(5,2,'/data/pacs-export/s2/IM1.dcm','1.2.826.0.1.3680043.10.1001.2.1');
INSERT INTO series_files VALUES(6,2,'/data/pacs-export/s2/IM2.dcm','1.2.826.0.1.3680043.10.1001.2.2');
CREATE TABLE series_messages ( id INTEGER PRIMARY KEY, series_ref INTEGER NOT NULL REFERENCES series(id) ON DELETE CASCADE, kind TEXT NOT NULL CHECK (kind IN ('warning', 'error')), file TEXT, text TEXT NOT NULL);
INSERT INTO series_messages VALUES(1,1,'warning',NULL,'gantry tilt 12 degrees');
CREATE TABLE import_log ( id INTEGER PRIMARY KEY, imported_at TEXT NOT NULL, source_root TEXT, file TEXT, reason TEXT NOT NULL);
INSERT INTO import_log VALUES(1,'2026-11-23T18:10:23Z','/data/pacs-export','/data/pacs-export/README.txt','not a DICOM file');
CREATE INDEX series_files_series ON series_files(series_ref);
CREATE INDEX series_messages_series ON series_messages(series_ref);
PRAGMA user_version=1;
COMMIT;
