//! `contrail diff`: align two recordings of the same scene by increment (or by load level)
//! and slave point, and report per field the first divergence beyond the tolerance, the
//! largest absolute and relative differences, crossings found in one run only, and where
//! each run stopped.
//!
//! Two values `a`, `b` agree when `|a − b| ≤ tol · max(1, |a|, |b|)` (absolute below 1,
//! relative above); NaN agrees with NaN only; segment ids, states and iteration counts must
//! be equal.

pub use super::diff_surface::SURFACE_FIELDS;
use super::plot::Series;
use super::recording::Recording;
use crate::record::messages::CrossingMessage;
use crate::record::{ContactPointRecord, IncrementRecord, Outcome};
use serde::Serialize;

/// How increments of the two runs are paired.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Align {
    /// Same increment number.
    Increment,
    /// Same load level `t` (runs with different step sizes; unmatched levels are reported).
    Load,
}

/// Two recordings that cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum DiffError {
    #[error("{a} is a run of scene `{sa}`, {b} of scene `{sb}`: diff compares runs of one scene")]
    DifferentScenes {
        a: String,
        b: String,
        sa: String,
        sb: String,
    },
    #[error("{a} and {b} are runs of scene `{scene}` with different meshes or contact pairs; they cannot be aligned point by point")]
    DifferentLayout { a: String, b: String, scene: String },
    #[error("unknown field `{0}`; fields: {1}")]
    UnknownField(String, String),
}

/// Increment-level fields.
pub const INCREMENT_FIELDS: &[&str] = &[
    "t",
    "iterations",
    "residuals",
    "displacement",
    "force",
    "reaction_x",
    "reaction_y",
];
/// Contact-point fields.
pub const POINT_FIELDS: &[&str] = &[
    "segment",
    "state",
    "xi",
    "xi_anchor",
    "gap",
    "normal_force",
    "trial_traction",
    "traction",
];

/// Where two values first disagreed.
#[derive(Debug, Clone, Serialize)]
pub struct Divergence {
    pub increment_a: usize,
    pub increment_b: usize,
    pub t: f64,
    /// `pair/slave (label)` for contact fields.
    pub point: Option<String>,
    pub a: String,
    pub b: String,
}

/// Comparison of one field over all aligned increments (and points).
#[derive(Debug, Clone, Serialize)]
pub struct FieldDiff {
    pub field: String,
    pub compared: usize,
    pub beyond_tolerance: usize,
    pub max_abs: f64,
    pub max_rel: f64,
    pub first_divergence: Option<Divergence>,
}

/// A crossing of one run with no counterpart in the other.
#[derive(Debug, Clone, Serialize, PartialEq, Eq, PartialOrd, Ord)]
pub struct CrossingKey {
    pub increment: usize,
    pub pair: usize,
    pub slave: usize,
    pub from_segment: usize,
    pub to_segment: usize,
}

/// How one run ended.
#[derive(Debug, Clone, Serialize)]
pub struct RunEnd {
    pub file: String,
    pub overrides: Vec<String>,
    pub transfer: Vec<String>,
    pub increments: usize,
    pub final_t: f64,
    pub status: String,
    pub stopped: String,
}

/// The result of a diff.
#[derive(Debug, Clone, Serialize)]
pub struct DiffReport {
    pub scene: String,
    pub align: Align,
    pub tol: f64,
    pub a: RunEnd,
    pub b: RunEnd,
    pub matched_increments: usize,
    pub only_in_a: usize,
    pub only_in_b: usize,
    pub fields: Vec<FieldDiff>,
    pub crossings_only_in_a: Vec<CrossingKey>,
    pub crossings_only_in_b: Vec<CrossingKey>,
    pub within_tolerance: bool,
}

fn run_end(r: &Recording) -> RunEnd {
    let (status, stopped) = match &r.outcome {
        Some(Outcome::Completed { .. }) => ("completed".to_string(), String::new()),
        Some(Outcome::Failed {
            increment, t, reason, ..
        }) => ("failed".into(), format!("increment {increment} (t = {t}): {reason}")),
        Some(Outcome::Interrupted { increment, t }) => (
            "interrupted".into(),
            format!("increment {increment} (last converged t = {t})"),
        ),
        None => ("unknown".into(), "no outcome message".into()),
    };
    RunEnd {
        file: r.path.clone(),
        overrides: r.metadata_list("overrides"),
        transfer: r.metadata_list("transfer"),
        increments: r.increments.len(),
        final_t: r.increments.last().map_or(0.0, |i| i.t),
        status,
        stopped,
    }
}

/// Pairs of increment indices (into `a.increments`, `b.increments`).
pub fn align(a: &Recording, b: &Recording, how: Align) -> Vec<(usize, usize)> {
    let (ia, ib) = (&a.increments, &b.increments);
    let mut out = Vec::new();
    match how {
        Align::Increment => {
            let mut j = 0;
            for (i, x) in ia.iter().enumerate() {
                while j < ib.len() && ib[j].increment < x.increment {
                    j += 1;
                }
                if j < ib.len() && ib[j].increment == x.increment {
                    out.push((i, j));
                }
            }
        }
        Align::Load => {
            let eps = 1e-9 * a.model.end.abs().max(b.model.end.abs()).max(1.0);
            let (mut i, mut j) = (0, 0);
            while i < ia.len() && j < ib.len() {
                let d = ia[i].t - ib[j].t;
                if d.abs() <= eps {
                    out.push((i, j));
                    i += 1;
                    j += 1;
                } else if d < 0.0 {
                    i += 1;
                } else {
                    j += 1;
                }
            }
        }
    }
    out
}

/// A value of a field at an increment (and point).
#[derive(Debug, Clone, PartialEq)]
pub(super) enum V {
    Num(f64),
    Exact(String),
}

fn inc_values(field: &str, r: &IncrementRecord) -> Vec<V> {
    let m = r.monitor.as_ref();
    match field {
        "t" => vec![V::Num(r.t)],
        "iterations" => vec![V::Exact(r.iterations.to_string())],
        "residuals" => r.residuals.iter().map(|x| V::Num(*x)).collect(),
        "displacement" => vec![V::Num(m.map_or(f64::NAN, |m| m.displacement))],
        "force" => vec![V::Num(m.map_or(f64::NAN, |m| m.force))],
        "reaction_x" => vec![V::Num(r.reaction_total[0])],
        "reaction_y" => vec![V::Num(r.reaction_total[1])],
        _ => vec![],
    }
}

fn point_value(field: &str, p: &ContactPointRecord) -> V {
    match field {
        "segment" => V::Exact(p.segment.map_or("none".into(), |s| s.to_string())),
        "state" => V::Exact(format!("{:?}", p.state).to_lowercase()),
        "xi" => V::Num(p.xi),
        "xi_anchor" => V::Num(p.xi_anchor),
        "gap" => V::Num(p.gap),
        "normal_force" => V::Num(p.normal_force),
        "trial_traction" => V::Num(p.trial_traction),
        _ => V::Num(p.traction),
    }
}

/// A numeric value for plots (segment id, state code).
fn plot_value(field: &str, p: &ContactPointRecord) -> f64 {
    match field {
        "segment" => p.segment.map_or(f64::NAN, |s| s as f64),
        "state" => p.state.code() as f64,
        _ => match point_value(field, p) {
            V::Num(x) => x,
            V::Exact(_) => f64::NAN,
        },
    }
}

fn show(v: &V) -> String {
    match v {
        V::Num(x) => format!("{x:.10e}"),
        V::Exact(s) => s.clone(),
    }
}

impl FieldDiff {
    fn new(field: &str) -> Self {
        FieldDiff {
            field: field.to_string(),
            compared: 0,
            beyond_tolerance: 0,
            max_abs: 0.0,
            max_rel: 0.0,
            first_divergence: None,
        }
    }

    pub(super) fn compare(&mut self, a: &V, b: &V, tol: f64, at: impl FnOnce() -> Divergence) {
        self.compared += 1;
        let ok = match (a, b) {
            (V::Num(x), V::Num(y)) => {
                if x.is_nan() || y.is_nan() || x.is_infinite() || y.is_infinite() {
                    let same = (x.is_nan() && y.is_nan()) || x == y;
                    if !same {
                        self.max_abs = f64::INFINITY;
                        self.max_rel = f64::INFINITY;
                    }
                    same
                } else {
                    let d = (x - y).abs();
                    let scale = x.abs().max(y.abs());
                    self.max_abs = self.max_abs.max(d);
                    if scale > 0.0 {
                        self.max_rel = self.max_rel.max(d / scale);
                    }
                    d <= tol * scale.max(1.0)
                }
            }
            _ => a == b,
        };
        if !ok {
            self.beyond_tolerance += 1;
            if self.first_divergence.is_none() {
                let mut d = at();
                d.a = show(a);
                d.b = show(b);
                self.first_divergence = Some(d);
            }
        }
    }
}

/// Refuse recordings of different scenes or layouts.
pub fn check_comparable(a: &Recording, b: &Recording) -> Result<(), DiffError> {
    if a.scene() != b.scene() {
        return Err(DiffError::DifferentScenes {
            a: a.path.clone(),
            b: b.path.clone(),
            sa: a.scene().into(),
            sb: b.scene().into(),
        });
    }
    if !a.model.same_layout(&b.model) {
        return Err(DiffError::DifferentLayout {
            a: a.path.clone(),
            b: b.path.clone(),
            scene: a.scene().into(),
        });
    }
    Ok(())
}

/// Compare two recordings: the fields of every aligned pair of increments and of their
/// contact points, then the crossings, then how each run ended.
pub fn diff(a: &Recording, b: &Recording, how: Align, tol: f64) -> Result<DiffReport, DiffError> {
    check_comparable(a, b)?;
    let pairs = align(a, b, how);
    let point_fields = match a.model.dim() {
        3 => SURFACE_FIELDS,
        _ => POINT_FIELDS,
    };
    let mut fields: Vec<FieldDiff> = INCREMENT_FIELDS
        .iter()
        .chain(point_fields)
        .filter(|f| !(how == Align::Load && **f == "t"))
        .map(|f| FieldDiff::new(f))
        .collect();
    for &(i, j) in &pairs {
        compare_increments(a, b, (i, j), tol, &mut fields);
    }
    let (only_a, only_b) = unmatched_crossings(a, b, &pairs);
    let (ea, eb) = (run_end(a), run_end(b));
    let only_in_a = a.increments.len() - pairs.len();
    let only_in_b = b.increments.len() - pairs.len();
    let within = fields.iter().all(|f| f.beyond_tolerance == 0)
        && only_in_a == 0
        && only_in_b == 0
        && only_a.is_empty()
        && only_b.is_empty()
        && ea.status == eb.status;
    Ok(DiffReport {
        scene: a.scene().into(),
        align: how,
        tol,
        a: ea,
        b: eb,
        matched_increments: pairs.len(),
        only_in_a,
        only_in_b,
        fields,
        crossings_only_in_a: only_a,
        crossings_only_in_b: only_b,
        within_tolerance: within,
    })
}

/// Compare the increment `i` of `a` with the increment `j` of `b`: the increment's fields, then
/// the fields of each contact point recorded in both.
fn compare_increments(a: &Recording, b: &Recording, (i, j): (usize, usize), tol: f64, fields: &mut [FieldDiff]) {
    let (ra, rb) = (&a.increments[i], &b.increments[j]);
    let at = |point: Option<String>| Divergence {
        increment_a: ra.increment,
        increment_b: rb.increment,
        t: ra.t,
        point,
        a: String::new(),
        b: String::new(),
    };
    for fd in fields.iter_mut() {
        if INCREMENT_FIELDS.contains(&fd.field.as_str()) {
            let (va, vb) = (inc_values(&fd.field, ra), inc_values(&fd.field, rb));
            if va.len() != vb.len() {
                fd.compare(
                    &V::Exact(format!("{} values", va.len())),
                    &V::Exact(format!("{} values", vb.len())),
                    tol,
                    || at(None),
                );
            }
            for (x, y) in va.iter().zip(&vb) {
                fd.compare(x, y, tol, || at(None));
            }
        }
    }
    let (sa, sb) = (a.surface_at(ra.increment), b.surface_at(rb.increment));
    super::diff_surface::compare(sa, sb, tol, fields, &at);
    let (ca, cb) = (a.contact_at(ra.increment), b.contact_at(rb.increment));
    for pa in ca {
        let Some(pb) = cb.iter().find(|p| p.pair == pa.pair && p.slave == pa.slave) else {
            continue;
        };
        let label = || Some(format!("{}/{} ({})", pa.pair_name, pa.slave, pa.slave_label));
        for fd in fields.iter_mut().filter(|f| POINT_FIELDS.contains(&f.field.as_str())) {
            fd.compare(&point_value(&fd.field, pa), &point_value(&fd.field, pb), tol, || {
                at(label())
            });
        }
    }
}

/// The crossings of each run without a counterpart in the other (the same pair, slave and
/// segments in the aligned increment), sorted and without repeats.
fn unmatched_crossings(a: &Recording, b: &Recording, pairs: &[(usize, usize)]) -> (Vec<CrossingKey>, Vec<CrossingKey>) {
    let key = |c: &CrossingMessage| CrossingKey {
        increment: c.increment,
        pair: c.crossing.pair,
        slave: c.crossing.slave,
        from_segment: c.crossing.from_segment,
        to_segment: c.crossing.to_segment,
    };
    let same = |x: &CrossingMessage, y: &CrossingMessage| {
        let (kx, ky) = (key(x), key(y));
        (kx.pair, kx.slave, kx.from_segment, kx.to_segment) == (ky.pair, ky.slave, ky.from_segment, ky.to_segment)
    };
    let partner_of_a: std::collections::BTreeMap<usize, usize> = pairs
        .iter()
        .map(|&(i, j)| (a.increments[i].increment, b.increments[j].increment))
        .collect();
    let partner_of_b: std::collections::BTreeMap<usize, usize> = pairs
        .iter()
        .map(|&(i, j)| (b.increments[j].increment, a.increments[i].increment))
        .collect();
    let unmatched = |x: &Recording, y: &Recording, partner: &std::collections::BTreeMap<usize, usize>| {
        let mut keys: Vec<CrossingKey> = x
            .crossings
            .iter()
            .filter(|c| {
                partner
                    .get(&c.increment)
                    .is_none_or(|&inc| !y.crossings.iter().any(|d| d.increment == inc && same(c, d)))
            })
            .map(key)
            .collect();
        keys.sort();
        keys.dedup();
        keys
    };
    (unmatched(a, b, &partner_of_a), unmatched(b, a, &partner_of_b))
}

/// The traces of `field` in both runs (x: increment or load level), crossings marked; for a
/// contact field, of the point `point = (pair, slave)`.
pub fn traces(
    a: &Recording,
    b: &Recording,
    how: Align,
    field: &str,
    point: (usize, usize),
) -> Result<Vec<Series>, DiffError> {
    let is_point = POINT_FIELDS.contains(&field);
    if !is_point && !INCREMENT_FIELDS.contains(&field) {
        let all: Vec<&str> = INCREMENT_FIELDS.iter().chain(POINT_FIELDS).copied().collect();
        return Err(DiffError::UnknownField(field.into(), all.join(", ")));
    }
    let series = |r: &Recording, label: &str| {
        let mut s = Series {
            label: label.to_string(),
            points: Vec::new(),
            markers: Vec::new(),
        };
        for inc in &r.increments {
            let x = match how {
                Align::Increment => inc.increment as f64,
                Align::Load => inc.t,
            };
            let y = if is_point {
                r.contact_at(inc.increment)
                    .iter()
                    .find(|p| (p.pair, p.slave) == point)
                    .map_or(f64::NAN, |p| plot_value(field, p))
            } else {
                match inc_values(field, inc).last() {
                    Some(V::Num(v)) => *v,
                    Some(V::Exact(s)) => s.parse().unwrap_or(f64::NAN),
                    None => f64::NAN,
                }
            };
            s.points.push((x, y));
            let crossed = r
                .crossings
                .iter()
                .any(|c| c.increment == inc.increment && (!is_point || (c.crossing.pair, c.crossing.slave) == point));
            if crossed && y.is_finite() {
                s.markers.push((x, y));
            }
        }
        s
    };
    let label = |r: &Recording| {
        let o = r.metadata_list("overrides");
        if o.is_empty() {
            r.path.clone()
        } else {
            format!("{} ({})", r.path, o.join(" "))
        }
    };
    Ok(vec![series(a, &label(a)), series(b, &label(b))])
}
