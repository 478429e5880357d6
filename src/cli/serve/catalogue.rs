//! The run catalogue: one SQLite file (`DATA/catalogue.sqlite`, WAL journal) with a row per
//! run — its stable id, scene, overrides, parameters, status, progress, outcome — and a row
//! per parameter value (for filters). Every change is one statement or one transaction, so a
//! killed service leaves a consistent file.

use rusqlite::{params, Connection, OptionalExtension};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;

/// Statuses a run goes through: `queued` → `running` → `completed` | `failed` |
/// `interrupted`; a queued run that is cancelled becomes `cancelled`.
pub const STATUSES: &[&str] = &["queued", "running", "completed", "failed", "interrupted", "cancelled"];

/// Whether a status is final (the run will not change any more unless re-run).
pub fn is_final(status: &str) -> bool {
    !matches!(status, "queued" | "running")
}

/// A catalogued run.
#[derive(Debug, Clone, Serialize)]
pub struct RunRow {
    pub id: String,
    pub seq: i64,
    pub scene: String,
    /// What the solver runs: a built-in name or `scenes/HASH.toml` in the data folder.
    pub scene_ref: String,
    pub sets: Vec<String>,
    pub params: BTreeMap<String, String>,
    pub sweep: Option<String>,
    pub status: String,
    pub failure_kind: Option<String>,
    pub message: String,
    pub submitted_at: f64,
    pub started_at: Option<f64>,
    pub finished_at: Option<f64>,
    pub attempt: i64,
    pub positions_every: i64,
    pub backend: Option<String>,
    pub job: Option<String>,
    #[serde(skip)]
    pub progress: Option<String>,
    #[serde(skip)]
    pub outcome: Option<String>,
    #[serde(skip)]
    pub culprit: Option<String>,
    #[serde(skip)]
    pub metrics: Option<String>,
    #[serde(skip)]
    pub log: String,
}

/// What a new run needs.
pub struct NewRun<'a> {
    pub id: &'a str,
    pub scene: &'a str,
    pub scene_ref: &'a str,
    pub sets: &'a [String],
    pub params: &'a BTreeMap<String, String>,
    pub sweep: Option<&'a str>,
    pub positions_every: usize,
}

/// How a run ended, as written to its row.
pub struct Finish<'a> {
    pub status: &'a str,
    pub failure_kind: Option<&'a str>,
    pub message: &'a str,
    pub outcome: Option<String>,
    pub culprit: Option<String>,
    pub metrics: Option<String>,
    pub log: &'a str,
}

/// Filters of the runs list.
#[derive(Debug, Default)]
pub struct Filter {
    pub scene: Option<String>,
    pub status: Option<String>,
    pub failure_kind: Option<String>,
    pub sweep: Option<String>,
    /// `key = value` pairs a run's parameters must all have.
    pub params: Vec<(String, String)>,
    /// Column to sort by and direction.
    pub sort: String,
    pub descending: bool,
    pub limit: usize,
    pub offset: usize,
}

pub struct Catalogue {
    db: Mutex<Connection>,
}

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS runs (
    seq INTEGER PRIMARY KEY AUTOINCREMENT,
    id TEXT NOT NULL UNIQUE,
    scene TEXT NOT NULL,
    scene_ref TEXT NOT NULL,
    sets TEXT NOT NULL,
    params TEXT NOT NULL,
    sweep TEXT,
    status TEXT NOT NULL,
    failure_kind TEXT,
    message TEXT NOT NULL DEFAULT '',
    submitted_at REAL NOT NULL,
    started_at REAL,
    finished_at REAL,
    attempt INTEGER NOT NULL DEFAULT 1,
    positions_every INTEGER NOT NULL DEFAULT 1,
    backend TEXT,
    job TEXT,
    progress TEXT,
    outcome TEXT,
    culprit TEXT,
    metrics TEXT,
    log TEXT NOT NULL DEFAULT ''
);
CREATE INDEX IF NOT EXISTS runs_status ON runs(status, seq);
CREATE INDEX IF NOT EXISTS runs_scene ON runs(scene);
CREATE TABLE IF NOT EXISTS params (
    id TEXT NOT NULL REFERENCES runs(id),
    key TEXT NOT NULL,
    value TEXT NOT NULL,
    PRIMARY KEY (id, key)
);
CREATE INDEX IF NOT EXISTS params_kv ON params(key, value);
";

const COLUMNS: &str = "seq, id, scene, scene_ref, sets, params, sweep, status, failure_kind, message, \
    submitted_at, started_at, finished_at, attempt, positions_every, backend, job, progress, outcome, culprit, \
    metrics, log";

/// Sortable columns of the list.
pub const SORTS: &[&str] = &[
    "seq",
    "id",
    "scene",
    "status",
    "failure_kind",
    "submitted_at",
    "finished_at",
];

pub fn now() -> f64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

fn row(r: &rusqlite::Row) -> rusqlite::Result<RunRow> {
    let json_vec = |s: String| serde_json::from_str(&s).unwrap_or_default();
    Ok(RunRow {
        seq: r.get(0)?,
        id: r.get(1)?,
        scene: r.get(2)?,
        scene_ref: r.get(3)?,
        sets: json_vec(r.get(4)?),
        params: serde_json::from_str(&r.get::<_, String>(5)?).unwrap_or_default(),
        sweep: r.get(6)?,
        status: r.get(7)?,
        failure_kind: r.get(8)?,
        message: r.get(9)?,
        submitted_at: r.get(10)?,
        started_at: r.get(11)?,
        finished_at: r.get(12)?,
        attempt: r.get(13)?,
        positions_every: r.get(14)?,
        backend: r.get(15)?,
        job: r.get(16)?,
        progress: r.get(17)?,
        outcome: r.get(18)?,
        culprit: r.get(19)?,
        metrics: r.get(20)?,
        log: r.get(21)?,
    })
}

impl Catalogue {
    /// Open (or create) the catalogue in WAL mode.
    pub fn open(path: &Path) -> rusqlite::Result<Catalogue> {
        let db = Connection::open(path)?;
        db.pragma_update(None, "journal_mode", "WAL")?;
        db.pragma_update(None, "synchronous", "NORMAL")?;
        db.pragma_update(None, "foreign_keys", "ON")?;
        db.busy_timeout(std::time::Duration::from_secs(5))?;
        db.execute_batch(SCHEMA)?;
        Ok(Catalogue { db: Mutex::new(db) })
    }

    fn db(&self) -> std::sync::MutexGuard<'_, Connection> {
        self.db.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Insert a queued run unless its id is catalogued; true when inserted.
    pub fn insert(&self, r: &NewRun) -> rusqlite::Result<bool> {
        let mut db = self.db();
        let tx = db.transaction()?;
        let n = tx.execute(
            "INSERT OR IGNORE INTO runs (id, scene, scene_ref, sets, params, sweep, status, submitted_at, positions_every)
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, 'queued', ?7, ?8)",
            params![
                r.id,
                r.scene,
                r.scene_ref,
                serde_json::to_string(r.sets).unwrap_or_default(),
                serde_json::to_string(r.params).unwrap_or_default(),
                r.sweep,
                now(),
                r.positions_every as i64
            ],
        )?;
        if n == 1 {
            for (k, v) in r.params {
                tx.execute(
                    "INSERT OR REPLACE INTO params (id, key, value) VALUES (?1, ?2, ?3)",
                    params![r.id, k, v],
                )?;
            }
        }
        tx.commit()?;
        Ok(n == 1)
    }

    /// Queue a finished run again (a re-run); false when it is queued or running.
    pub fn requeue(&self, id: &str) -> rusqlite::Result<bool> {
        let n = self.db().execute(
            "UPDATE runs SET status = 'queued', failure_kind = NULL, message = '', submitted_at = ?2,
                 started_at = NULL, finished_at = NULL, attempt = attempt + 1, progress = NULL,
                 outcome = NULL, culprit = NULL, metrics = NULL, log = '', job = NULL
             WHERE id = ?1 AND status NOT IN ('queued', 'running')",
            params![id, now()],
        )?;
        Ok(n == 1)
    }

    pub fn get(&self, id: &str) -> rusqlite::Result<Option<RunRow>> {
        self.db()
            .query_row(&format!("SELECT {COLUMNS} FROM runs WHERE id = ?1"), [id], row)
            .optional()
    }

    /// Take the oldest queued run and mark it running on `backend`.
    pub fn claim(&self, backend: &str) -> rusqlite::Result<Option<RunRow>> {
        self.db()
            .query_row(
                &format!(
                    "UPDATE runs SET status = 'running', started_at = ?1, backend = ?2
                     WHERE seq = (SELECT seq FROM runs WHERE status = 'queued' ORDER BY seq LIMIT 1)
                     RETURNING {COLUMNS}"
                ),
                params![now(), backend],
                row,
            )
            .optional()
    }

    pub fn set_job(&self, id: &str, job: &str) -> rusqlite::Result<()> {
        self.db()
            .execute("UPDATE runs SET job = ?2 WHERE id = ?1", params![id, job])
            .map(|_| ())
    }

    pub fn set_progress(&self, id: &str, progress: &str) -> rusqlite::Result<()> {
        self.db()
            .execute(
                "UPDATE runs SET progress = ?2 WHERE id = ?1 AND status = 'running'",
                params![id, progress],
            )
            .map(|_| ())
    }

    /// Write how a running run ended.
    pub fn finish(&self, id: &str, f: &Finish) -> rusqlite::Result<()> {
        self.db()
            .execute(
                "UPDATE runs SET status = ?2, failure_kind = ?3, message = ?4, outcome = ?5, culprit = ?6,
                     metrics = ?7, log = ?8, finished_at = ?9
                 WHERE id = ?1",
                params![
                    id,
                    f.status,
                    f.failure_kind,
                    f.message,
                    f.outcome,
                    f.culprit,
                    f.metrics,
                    f.log,
                    now()
                ],
            )
            .map(|_| ())
    }

    /// Cancel a queued run; true when it was queued.
    pub fn cancel_queued(&self, id: &str) -> rusqlite::Result<bool> {
        let n = self.db().execute(
            "UPDATE runs SET status = 'cancelled', message = 'cancelled before it started', finished_at = ?2
             WHERE id = ?1 AND status = 'queued'",
            params![id, now()],
        )?;
        Ok(n == 1)
    }

    /// Runs left `running` by a service that stopped.
    pub fn running(&self) -> rusqlite::Result<Vec<RunRow>> {
        let db = self.db();
        let mut st = db.prepare(&format!(
            "SELECT {COLUMNS} FROM runs WHERE status = 'running' ORDER BY seq"
        ))?;
        let rows = st.query_map([], row)?.collect();
        rows
    }

    /// Runs matching `f`, and how many match without the limit.
    pub fn list(&self, f: &Filter) -> rusqlite::Result<(Vec<RunRow>, usize)> {
        let mut cond = vec!["1 = 1".to_string()];
        let mut args: Vec<String> = Vec::new();
        let arg = |v: &str, args: &mut Vec<String>| {
            args.push(v.to_string());
            format!("?{}", args.len())
        };
        for (col, v) in [
            ("scene", &f.scene),
            ("status", &f.status),
            ("failure_kind", &f.failure_kind),
            ("sweep", &f.sweep),
        ] {
            if let Some(v) = v {
                let a = arg(v, &mut args);
                cond.push(format!("{col} = {a}"));
            }
        }
        for (k, v) in &f.params {
            let (ka, va) = (arg(k, &mut args), arg(v, &mut args));
            cond.push(format!(
                "id IN (SELECT id FROM params WHERE key = {ka} AND value = {va})"
            ));
        }
        let sort = if SORTS.contains(&f.sort.as_str()) {
            f.sort.as_str()
        } else {
            "seq"
        };
        let dir = if f.descending { "DESC" } else { "ASC" };
        let wh = cond.join(" AND ");
        let db = self.db();
        let total: i64 = db.query_row(
            &format!("SELECT COUNT(*) FROM runs WHERE {wh}"),
            rusqlite::params_from_iter(args.iter()),
            |r| r.get(0),
        )?;
        let sql = format!(
            "SELECT {COLUMNS} FROM runs WHERE {wh} ORDER BY {sort} {dir}, seq {dir} LIMIT {} OFFSET {}",
            f.limit, f.offset
        );
        let mut st = db.prepare(&sql)?;
        let rows = st
            .query_map(rusqlite::params_from_iter(args.iter()), row)?
            .collect::<rusqlite::Result<Vec<_>>>()?;
        Ok((rows, total as usize))
    }

    /// Run counts by status.
    pub fn counts(&self) -> rusqlite::Result<BTreeMap<String, usize>> {
        let db = self.db();
        let mut st = db.prepare("SELECT status, COUNT(*) FROM runs GROUP BY status")?;
        let rows = st
            .query_map([], |r| Ok((r.get::<_, String>(0)?, r.get::<_, i64>(1)? as usize)))?
            .collect();
        rows
    }

    /// SQLite's own check of the file (`ok` when sound).
    pub fn integrity(&self) -> rusqlite::Result<String> {
        self.db().query_row("PRAGMA integrity_check", [], |r| r.get(0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn new_run<'a>(id: &'a str, params: &'a BTreeMap<String, String>) -> NewRun<'a> {
        NewRun {
            id,
            scene: "crossing",
            scene_ref: "crossing",
            sets: &[],
            params,
            sweep: None,
            positions_every: 1,
        }
    }

    #[test]
    fn runs_are_catalogued_once_claimed_in_order_and_filtered() {
        let dir = std::env::temp_dir().join(format!("contrail-cat-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let c = Catalogue::open(&dir.join("c.sqlite")).unwrap();
        let p: BTreeMap<String, String> = [("contact.mu".to_string(), "0.3".to_string())].into();
        let none = BTreeMap::new();
        assert!(c.insert(&new_run("a", &p)).unwrap());
        assert!(!c.insert(&new_run("a", &p)).unwrap());
        assert!(c.insert(&new_run("b", &none)).unwrap());
        assert_eq!(c.claim("local").unwrap().unwrap().id, "a");
        assert!(!c.requeue("a").unwrap(), "a running run is not re-queued");
        let f = Filter {
            params: vec![("contact.mu".into(), "0.3".into())],
            limit: 10,
            ..Filter::default()
        };
        let (rows, total) = c.list(&f).unwrap();
        assert_eq!((rows.len(), total, rows[0].status.as_str()), (1, 1, "running"));
        assert!(c.cancel_queued("b").unwrap());
        assert_eq!(c.claim("local").unwrap().map(|r| r.id), None);
        assert_eq!(c.running().unwrap().len(), 1);
        assert_eq!(c.integrity().unwrap(), "ok");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
