PRAGMA foreign_keys=OFF;
BEGIN TRANSACTION;
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
INSERT INTO meta VALUES('schema_version','2');
INSERT INTO meta VALUES('validation_positions','[]');
CREATE TABLE session(
  id INTEGER PRIMARY KEY CHECK (id = 1),
  name TEXT NOT NULL, sample TEXT NOT NULL, operator TEXT NOT NULL, notes TEXT NOT NULL,
  software_version TEXT NOT NULL, created_at TEXT NOT NULL,
  plan_source TEXT NOT NULL, plan_text TEXT NOT NULL,
  rig_file TEXT NOT NULL,
  positions_json TEXT NOT NULL, exposures_json TEXT NOT NULL, bracket_size INTEGER NOT NULL);
INSERT INTO session VALUES(1,'s1','test-sample','tester','acquisition test','0.1.0','2026-11-30T08:26:48.758Z','plan.yaml',replace('sample: test-sample\noperator: tester\nnotes: acquisition test\npositions:\n  - {camera_arm: 20, light_arm: -20}\n  - {camera_arm: 35, light_arm: -35}\nexposures: [0.001, 0.01]\nsettle_s: 0\n','\n',char(10)),'rig.yaml','[{"camera_arm":0.3490658503988659,"light_arm":-0.3490658503988659},{"camera_arm":0.6108652381980153,"light_arm":-0.6108652381980153}]','[0.001,0.01]',2);
CREATE TABLE snapshot_files(
  name TEXT PRIMARY KEY, role TEXT NOT NULL, original_path TEXT NOT NULL, sha256 TEXT NOT NULL);
INSERT INTO snapshot_files VALUES('rig.yaml','rig','/lab/rigs/rig.yaml','641568b0cb9c2aad182ca073feeeba6181b7c766a541597d20876be41b359298');
INSERT INTO snapshot_files VALUES('scene.yaml','geometry','/lab/rigs/scene.yaml','6e82e589cff496dde74f3f7fccbf718cd62e631e941a448bdc394ac27db7908a');
CREATE TABLE runs(
  id INTEGER PRIMARY KEY, started_at TEXT NOT NULL, resumed INTEGER NOT NULL,
  stopped_at TEXT, exit_status TEXT, reason TEXT);
INSERT INTO runs VALUES(1,'2026-11-30T08:26:48.761Z',0,'2026-11-30T08:26:48.800Z','success','');
CREATE TABLE frames(
  id INTEGER PRIMARY KEY, run_id INTEGER NOT NULL,
  position_index INTEGER NOT NULL, bracket_index INTEGER NOT NULL, file_index INTEGER NOT NULL,
  axis_readings_json TEXT NOT NULL,
  requested_exposure_s REAL NOT NULL, exposure_s REAL NOT NULL,
  camera_file_name TEXT NOT NULL, file TEXT NOT NULL UNIQUE, sha256 TEXT NOT NULL,
  bytes INTEGER NOT NULL, captured_at TEXT NOT NULL, recorded_at TEXT NOT NULL,
  status TEXT NOT NULL, saturated_fraction REAL NOT NULL,
  UNIQUE (position_index, bracket_index, file_index));
INSERT INTO frames VALUES(1,1,0,0,0,'{"camera_arm":0.3490658503988659,"light_arm":-0.3490658503988659}',0.0010000000000000000208,0.0010000000000000000208,'SIM_0001.png','frames/p000_b0.png','d43f900eef12887306f121296eb5d742197cc9e93a9cbe5130c0b9b8f194bc60',2969,'2026-11-30T08:26:48.764Z','2026-11-30T08:26:48.777Z','recorded',0.0);
INSERT INTO frames VALUES(2,1,0,1,0,'{"camera_arm":0.3490658503988659,"light_arm":-0.3490658503988659}',0.010000000000000000208,0.010000000000000000208,'SIM_0002.png','frames/p000_b1.png','edcbc73a32c3444c3fa74c5c6bea551d7ab777e2989a053bd5be5d2e0a330e98',4646,'2026-11-30T08:26:48.775Z','2026-11-30T08:26:48.782Z','recorded',0.040364583333333335646);
INSERT INTO frames VALUES(3,1,1,0,0,'{"camera_arm":0.6108652381980153,"light_arm":-0.6108652381980153}',0.0010000000000000000208,0.0010000000000000000208,'SIM_0003.png','frames/p001_b0.png','f9cabb93c193180b79eed3bedfca03364666cad1d65cf753d1a3d48cc427c127',2994,'2026-11-30T08:26:48.780Z','2026-11-30T08:26:48.789Z','recorded',0.0);
INSERT INTO frames VALUES(4,1,1,1,0,'{"camera_arm":0.6108652381980153,"light_arm":-0.6108652381980153}',0.010000000000000000208,0.010000000000000000208,'SIM_0004.png','frames/p001_b1.png','aa5e7881ac6c28c2aec029a7d88ce22fb8b0d3be8253e25435c5fa9edafac732',4547,'2026-11-30T08:26:48.788Z','2026-11-30T08:26:48.797Z','recorded',0.036783854166666664353);
CREATE TABLE positions(
  position_index INTEGER PRIMARY KEY, completed_at TEXT NOT NULL, run_id INTEGER NOT NULL);
INSERT INTO positions VALUES(0,'2026-11-30T08:26:48.782Z',1);
INSERT INTO positions VALUES(1,'2026-11-30T08:26:48.797Z',1);
CREATE TABLE events(
  id INTEGER PRIMARY KEY, at TEXT NOT NULL, run_id INTEGER, level TEXT NOT NULL,
  position_index INTEGER, message TEXT NOT NULL);
INSERT INTO events VALUES(1,'2026-11-30T08:26:48.762Z',1,'info',NULL,'run started: 2 positions to capture');
INSERT INTO events VALUES(2,'2026-11-30T08:26:48.800Z',1,'info',NULL,'run stopped: success: 2 positions, 4 frames recorded in this run, 0 retries, 0 redos; session 9.8 s vs unavoidable 9.8 s (ratio 1.000), wall 0.0 s');
COMMIT;
