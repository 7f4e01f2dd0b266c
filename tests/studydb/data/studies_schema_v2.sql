-- A study database as Linework wrote it at schema version 2 (commit cdbfdcd, before slice
-- annotations): studies_schema_v1.sql's rows, migrateToV2's series_annotations table, and the
-- annotations of both series as that version's annotationsToJson wrote them (annotation file
-- version 1; the texts made by that commit's lw_annotation). Dumped with sqlite3 .dump, which
-- leaves out PRAGMA user_version: added by hand before COMMIT. The migration test loads it one
-- statement per line.
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
CREATE TABLE series_annotations ( series_uid TEXT PRIMARY KEY, json TEXT NOT NULL, updated_at TEXT NOT NULL);
INSERT INTO series_annotations VALUES('1.2.826.0.1.3680043.10.1001.1',replace('{\n  "version": 1,\n  "annotations": [\n    {\n      "type": "ruler",\n      "points": [\n        [\n          -35.6,\n          -82.1,\n          54.1\n        ],\n        [\n          75.2,\n          17.1,\n          48.9\n        ]\n      ]\n    },\n    {\n      "type": "label",\n      "points": [\n        [\n          -11.4,\n          -42.8,\n          2.1\n        ]\n      ],\n      "text": "Orbit"\n    },\n    {\n      "type": "angle",\n      "points": [\n        [\n          -58.4,\n          -44.7,\n          2.7\n        ],\n        [\n          51.1,\n          -60.1,\n          -4.7\n        ],\n        [\n          75.2,\n          17.1,\n          48.9\n        ]\n      ]\n    }\n  ]\n}\n','\n',char(10)),'2026-11-24T09:12:40Z');
INSERT INTO series_annotations VALUES('1.2.826.0.1.3680043.10.1001.2',replace('{\n  "version": 1,\n  "annotations": [\n    {\n      "type": "arrow",\n      "points": [\n        [\n          60,\n          -80,\n          150\n        ],\n        [\n          7.3,\n          -36.3,\n          109.3\n        ]\n      ],\n      "text": "Slice step"\n    }\n  ]\n}\n','\n',char(10)),'2026-11-24T09:15:02Z');
CREATE INDEX series_files_series ON series_files(series_ref);
CREATE INDEX series_messages_series ON series_messages(series_ref);
PRAGMA user_version=2;
COMMIT;
