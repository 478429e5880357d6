//! Semantic checks of a parsed scene, run before anything is allocated or solved.
//!
//! Every number must be finite and in its physical range (E > 0, −1 < ν < 0.5, ε_N > 0,
//! ε_T ≥ 0, μ ≥ 0, sizes > 0, grading > 0, radius > 0, increments ≥ 1, …); names are unique;
//! polylines have ≥ 2 distinct consecutive points; arcs span less than a full turn and, when
//! they say on which `side` the rigid body is, their orientation must agree; the geometry must
//! be small enough against the search radius for the contact grid; and the model must fit the
//! size limits of `[limits]` (raise them with `--set limits.max_dofs=…`).
//!
//! Each rule names the key in `--set` syntax, the value and the fix, with `file:line:col` of the
//! value in the scene text when it is there.

use super::types::*;
use super::{line_col, SceneError, SceneSource};
use std::fmt::Display;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// Geometry extent over search radius beyond which the uniform contact grid could not index
/// its cells (keys are `i64`, cell counts multiply).
pub const MAX_EXTENT_OVER_RADIUS: f64 = 1e8;

/// Largest distance of a mesh corner from the origin: beyond it a graded mesh's node
/// coordinates can overflow while origin and size are finite (found by the long scene fuzz:
/// `size = 1e308` gave a node at `[inf, −9.2e18]`).
pub const MAX_COORDINATE: f64 = 1e12;

/// Bytes per DOF of the memory estimate (sparse matrix, LU factors with fill, vectors);
/// calibrated on a 10⁶-element mesh, which used about 4.5 GB before running out of memory.
pub const BYTES_PER_DOF: f64 = 2_250.0;

#[path = "validate_fix.rs"]
mod fix;
#[path = "validate_mesh.rs"]
mod mesh;
#[path = "validate_monitors.rs"]
mod monitors;
#[path = "validate_rigid.rs"]
mod rigid;

/// One step of a key path: a table key or an array index.
#[derive(Debug, Clone, Copy)]
enum P<'a> {
    K(&'a str),
    I(usize),
}

/// Finds where a value sits in the scene text.
struct Locator<'a> {
    src: &'a SceneSource,
    doc: Option<Spanned<DeValue<'a>>>,
}

impl<'a> Locator<'a> {
    fn new(src: &'a SceneSource) -> Self {
        let doc = DeTable::parse(&src.text)
            .ok()
            .map(|t| Spanned::new(t.span(), DeValue::Table(t.into_inner())));
        Locator { src, doc }
    }

    /// `:line:col` of the deepest existing prefix of `path` (empty if none).
    fn at(&self, path: &[P]) -> String {
        let Some(mut v) = self.doc.as_ref() else {
            return String::new();
        };
        let mut span = None;
        for p in path {
            let next = match *p {
                P::K(k) => v.get_ref().get(k),
                P::I(i) => v.get_ref().get(i),
            };
            match next {
                Some(n) => {
                    v = n;
                    span = Some(n.span());
                }
                None => break,
            }
        }
        span.map_or(String::new(), |s| {
            let (l, c) = line_col(&self.src.text, s.start);
            format!(":{l}:{c}")
        })
    }
}

/// The checks of one scene, with the first failure kept.
struct Check<'a> {
    loc: Locator<'a>,
}

type R = Result<(), SceneError>;

impl Check<'_> {
    fn fail(&self, path: &[P], key: &str, value: impl Display, rule: &str, fix: &str) -> SceneError {
        SceneError::Invalid {
            origin: self.loc.src.origin.clone(),
            location: self.loc.at(path),
            message: format!("`{key}` = {value}: {rule}"),
            hint: fix.to_string(),
        }
    }

    fn finite(&self, path: &[P], key: &str, x: f64) -> R {
        if x.is_finite() {
            Ok(())
        } else {
            Err(self.fail(
                path,
                key,
                x,
                "must be a finite number",
                "give a finite number (no nan or inf)",
            ))
        }
    }

    fn positive(&self, path: &[P], key: &str, x: f64) -> R {
        self.finite(path, key, x)?;
        if x > 0.0 {
            Ok(())
        } else {
            Err(self.fail(path, key, x, "must be > 0", "give a positive number"))
        }
    }

    fn non_negative(&self, path: &[P], key: &str, x: f64) -> R {
        self.finite(path, key, x)?;
        if x >= 0.0 {
            Ok(())
        } else {
            Err(self.fail(path, key, x, "must be ≥ 0", "give zero or a positive number"))
        }
    }

    fn ramp(&self, path: &[P], key: &str, r: &RampSpec, ext: &mut Extent) -> R {
        match r {
            RampSpec::Final(v) => {
                self.finite(path, key, *v)?;
                ext.add(v.abs());
            }
            RampSpec::Path(knots) => {
                if knots.is_empty() {
                    return Err(self.fail(
                        path,
                        key,
                        "[]",
                        "a history needs at least one knot",
                        "give [[t, value], ...] or one final value",
                    ));
                }
                let mut last = f64::NEG_INFINITY;
                for (i, k) in knots.iter().enumerate() {
                    let p: Vec<P> = path.iter().copied().chain([P::I(i)]).collect();
                    self.finite(&p, &format!("{key}[{i}].t"), k[0])?;
                    self.finite(&p, &format!("{key}[{i}].value"), k[1])?;
                    if k[0] < last {
                        return Err(self.fail(
                            &p,
                            &format!("{key}[{i}].t"),
                            k[0],
                            "knot times must not decrease",
                            "sort the [t, value] knots by t",
                        ));
                    }
                    last = k[0];
                    ext.add(k[1].abs());
                }
            }
        }
        Ok(())
    }

    fn point(&self, path: &[P], key: &str, p: [f64; 2], ext: &mut Extent) -> R {
        self.finite(path, &format!("{key}[0]"), p[0])?;
        self.finite(path, &format!("{key}[1]"), p[1])?;
        ext.add(p[0].abs().max(p[1].abs()));
        Ok(())
    }

    fn selection(&self, path: &[P], key: &str, s: &NodeSelection) -> R {
        if let NodeSelection::Where(w) = s {
            for (k, v) in [("x", w.x), ("y", w.y), ("z", w.z)] {
                if let Some(v) = v {
                    self.finite(&sub(path, k), &format!("{key}.{k}"), v)?;
                }
            }
            if let Some(b) = w.bbox {
                for c in b.iter().flatten() {
                    self.finite(&sub(path, "box"), &format!("{key}.box"), *c)?;
                }
            }
            self.non_negative(&sub(path, "tol"), &format!("{key}.tol"), w.tol)?;
        }
        Ok(())
    }
}

fn sub<'a>(path: &[P<'a>], k: &'a str) -> Vec<P<'a>> {
    path.iter().copied().chain([P::K(k)]).collect()
}

/// Largest coordinate or displacement magnitude seen (for the contact grid bound).
#[derive(Default)]
struct Extent(f64);

impl Extent {
    fn add(&mut self, x: f64) {
        self.0 = self.0.max(x);
    }
}

/// Name of an element of an array of named tables in `--set` syntax (`body.strip`).
fn named(table: &str, name: &str) -> String {
    format!("{table}.{name}")
}

/// Check a scene (after `--set` overrides) before its model is built.
///
/// The location is that of the key in the scene text; a value given by `--set` is reported with
/// its overridden value at the place the key is written (or its table).
pub fn validate(src: &SceneSource, s: &SceneFile) -> Result<(), SceneError> {
    let c = Check { loc: Locator::new(src) };
    let mut ext = Extent::default();
    stepping(&c, s)?;
    unique(&c, "body", s.bodies.iter().map(|b| b.name.as_str()))?;
    unique(&c, "rigid", s.rigid.iter().map(|r| r.name.as_str()))?;
    unique(&c, "contact", s.contacts.iter().map(|r| r.name.as_str()))?;
    let mut min_h = f64::INFINITY;
    for (i, b) in s.bodies.iter().enumerate() {
        min_h = min_h.min(body(&c, i, b, &mut ext)?);
    }
    limits(&c, s)?;
    fix::check(&c, s, &mut ext)?;
    for (i, r) in s.rigid.iter().enumerate() {
        rigid::check(&c, i, r, &mut ext)?;
    }
    for (i, k) in s.contacts.iter().enumerate() {
        contact(&c, i, k, min_h, ext.0)?;
    }
    monitors::check(&c, s)?;
    Ok(())
}

fn unique<'a>(c: &Check, table: &str, names: impl Iterator<Item = &'a str>) -> R {
    let mut seen = std::collections::HashSet::new();
    for (i, n) in names.enumerate() {
        if !seen.insert(n) {
            return Err(c.fail(
                &[P::K(table), P::I(i), P::K("name")],
                &format!("{table}.{i}.name"),
                format!("\"{n}\""),
                &format!("another [[{table}]] has the same name"),
                &format!("give each [[{table}]] its own name"),
            ));
        }
    }
    Ok(())
}

fn stepping(c: &Check, s: &SceneFile) -> R {
    let st = &s.stepping;
    let p = |k| [P::K("stepping"), P::K(k)];
    c.positive(&p("end"), "stepping.end", st.end)?;
    if st.increments == 0 {
        return Err(c.fail(
            &p("increments"),
            "stepping.increments",
            0,
            "must be ≥ 1",
            "give at least one increment",
        ));
    }
    if st.increments > s.limits.max_increments {
        return Err(c.fail(
            &p("increments"),
            "stepping.increments",
            st.increments,
            &format!("more than the limit of {} increments", s.limits.max_increments),
            "use fewer increments, or raise the limit with --set limits.max_increments=N",
        ));
    }
    if st.max_cutbacks > 60 {
        return Err(c.fail(
            &p("max_cutbacks"),
            "stepping.max_cutbacks",
            st.max_cutbacks,
            "must be ≤ 60 (a step of end/2^60 is below rounding)",
            "give at most 60",
        ));
    }
    c.finite(&p("growth"), "stepping.growth", st.growth)?;
    if st.growth < 1.0 {
        return Err(c.fail(
            &p("growth"),
            "stepping.growth",
            st.growth,
            "must be ≥ 1",
            "give a growth factor ≥ 1 (1: never grow)",
        ));
    }
    let n = &s.solver;
    let q = |k| [P::K("solver"), P::K(k)];
    if n.max_iterations == 0 || n.max_iterations > 10_000 {
        return Err(c.fail(
            &q("max_iterations"),
            "solver.max_iterations",
            n.max_iterations,
            "must be between 1 and 10000",
            "give e.g. 25",
        ));
    }
    c.non_negative(&q("residual_tol"), "solver.residual_tol", n.residual_tol)?;
    c.non_negative(&q("residual_abs"), "solver.residual_abs", n.residual_abs)?;
    c.non_negative(&q("energy_tol"), "solver.energy_tol", n.energy_tol)?;
    c.positive(&q("divergence_factor"), "solver.divergence_factor", n.divergence_factor)
}

/// Checks a body and returns its smallest element edge.
fn body(c: &Check, i: usize, b: &BodySpec, ext: &mut Extent) -> Result<f64, SceneError> {
    let key = named("body", &b.name);
    let p = [P::K("body"), P::I(i)];
    let m = sub(&p, "material");
    c.positive(&sub(&m, "young"), &format!("{key}.material.young"), b.material.young)?;
    let nu = b.material.poisson;
    c.finite(&sub(&m, "poisson"), &format!("{key}.material.poisson"), nu)?;
    if !(-1.0 < nu && nu < 0.5) {
        return Err(c.fail(
            &sub(&m, "poisson"),
            &format!("{key}.material.poisson"),
            nu,
            "must satisfy −1 < ν < 0.5",
            "give e.g. 0.3 (0.5 is incompressible and not supported)",
        ));
    }
    mesh::check(c, &sub(&p, "mesh"), &key, &b.mesh, ext)
}

fn limits(c: &Check, s: &SceneFile) -> R {
    let lim = &s.limits;
    // counted in f64: element counts may be anything up to u64::MAX
    let dofs: f64 = s.bodies.iter().map(|b| estimated_dofs(&b.mesh)).sum();
    let worst =
        (s.bodies.iter().enumerate()).max_by(|a, b| a.1.mesh.element_count().total_cmp(&b.1.mesh.element_count()));
    let at = worst.map_or(vec![P::K("limits")], |(i, _)| {
        vec![P::K("body"), P::I(i), P::K("mesh"), P::K("elements")]
    });
    let key = worst.map_or("limits".to_string(), |(_, b)| {
        format!("{}.mesh.elements", named("body", &b.name))
    });
    let value = worst.map_or(String::new(), |(_, b)| elements_text(&b.mesh));
    if dofs > lim.max_dofs as f64 {
        return Err(c.fail(
            &at,
            &key,
            value,
            &format!(
                "the model would have {dofs:.3e} DOFs, more than the limit of {}",
                lim.max_dofs
            ),
            "use fewer elements, or raise the limit with --set limits.max_dofs=N",
        ));
    }
    let gib = dofs * BYTES_PER_DOF / (1u64 << 30) as f64;
    if gib > lim.max_memory_gib {
        return Err(c.fail(
            &at,
            &key,
            value,
            &format!(
                "the model would need about {gib:.1} GiB, more than the limit of {} GiB",
                lim.max_memory_gib
            ),
            "use fewer elements, or raise the limit with --set limits.max_memory_gib=X",
        ));
    }
    Ok(())
}

/// The DOFs a generated mesh will have, before it is built (0 for a mesh file).
fn estimated_dofs(mesh: &MeshSpec) -> f64 {
    match mesh {
        MeshSpec::Rectangle { elements, .. } | MeshSpec::Annulus { elements, .. } => {
            2.0 * (elements[0] as f64 + 1.0) * (elements[1] as f64 + 1.0)
        }
        MeshSpec::Box { elements, .. } => 3.0 * elements.iter().map(|&n| n as f64 + 1.0).product::<f64>(),
        MeshSpec::HemisphereShell { elements: [n, l], .. } => {
            let n = *n as f64;
            3.0 * (3.0 * n * n + 2.0 * n + 1.0) * (*l as f64 + 1.0)
        }
        MeshSpec::SphereShell {
            elements: [n, l], part, ..
        } => 3.0 * part.shell_part().surface_counts(*n).1 as f64 * (*l as f64 + 1.0),
        MeshSpec::Revolved {
            elements: [nr, nz],
            around,
            ..
        } => {
            let nr = *nr as f64 + 1.0;
            3.0 * nr * nr.max(*around as f64 + 1.0) * (*nz as f64 + 1.0)
        }
        MeshSpec::Gmsh { .. } | MeshSpec::Gmsh3d { .. } => 0.0,
    }
}

/// A mesh's `elements` as written (its file for a mesh file).
fn elements_text(mesh: &MeshSpec) -> String {
    match mesh {
        MeshSpec::Rectangle { elements, .. } | MeshSpec::Annulus { elements, .. } => {
            format!("[{}, {}]", elements[0], elements[1])
        }
        MeshSpec::Box { elements, .. } => format!("[{}, {}, {}]", elements[0], elements[1], elements[2]),
        MeshSpec::HemisphereShell { elements, .. }
        | MeshSpec::SphereShell { elements, .. }
        | MeshSpec::Revolved { elements, .. } => {
            format!("[{}, {}]", elements[0], elements[1])
        }
        MeshSpec::Gmsh { file, .. } | MeshSpec::Gmsh3d { file } => file.clone(),
    }
}

fn contact(c: &Check, i: usize, k: &ContactSpec, min_h: f64, extent: f64) -> R {
    let key = named("contact", &k.name);
    let p = [P::K("contact"), P::I(i)];
    c.positive(&sub(&p, "eps_n"), &format!("{key}.eps_n"), k.eps_n)?;
    c.non_negative(&sub(&p, "eps_t"), &format!("{key}.eps_t"), k.eps_t)?;
    c.non_negative(&sub(&p, "mu"), &format!("{key}.mu"), k.mu)?;
    if let Some(knots) = &k.mu_path {
        mu_path(c, &sub(&p, "mu_path"), &key, knots, k.mu)?;
    }
    if k.mu > 0.0 && k.eps_t == 0.0 {
        return Err(c.fail(
            &sub(&p, "eps_t"),
            &format!("{key}.eps_t"),
            0,
            "friction (mu > 0) needs a tangential penalty",
            "give eps_t > 0, or mu = 0 for frictionless contact",
        ));
    }
    let radius = match k.search_radius {
        Some(r) => {
            c.positive(&sub(&p, "search_radius"), &format!("{key}.search_radius"), r)?;
            r
        }
        // the default is twice the largest edge, which is at least the smallest one
        None => 2.0 * min_h,
    };
    if radius.is_finite() && extent / radius > MAX_EXTENT_OVER_RADIUS {
        return Err(c.fail(
            &sub(&p, "search_radius"),
            &format!("{key}.search_radius"),
            radius,
            &format!("the geometry reaches {extent:e}, more than {MAX_EXTENT_OVER_RADIUS:e} search radii from the origin; the contact search grid cannot cover it"),
            "check the coordinates, displacements and rigid motions for a typo, or give a larger search_radius",
        ));
    }
    Ok(())
}

#[cfg(test)]
#[path = "validate_tests.rs"]
mod tests;

/// A friction history: knots sorted in time, each `μ ≥ 0`, given instead of `mu`.
fn mu_path(c: &Check, p: &[P], key: &str, knots: &[[f64; 2]], mu: f64) -> R {
    if mu != 0.0 {
        return Err(c.fail(
            p,
            &format!("{key}.mu_path"),
            "[…]",
            &format!("is given with mu = {mu}: the friction is either constant or a history"),
            "remove `mu`, or remove `mu_path`",
        ));
    }
    c.ramp(
        p,
        &format!("{key}.mu_path"),
        &RampSpec::Path(knots.to_vec()),
        &mut Extent::default(),
    )?;
    for (i, knot) in knots.iter().enumerate() {
        let at: Vec<P> = p.iter().copied().chain([P::I(i)]).collect();
        c.non_negative(&at, &format!("{key}.mu_path[{i}].value"), knot[1])?;
    }
    Ok(())
}
