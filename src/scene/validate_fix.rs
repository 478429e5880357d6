//! Checks of the `[[fix]]` and `[[load]]` tables: node selections and histories, names
//! (unique, usable as a `--set` path segment), and a fix's kind: global `components` or a
//! skew `direction`, exactly one of them.

use super::{sub, Check, Extent, P, R};
use crate::scene::types::{FixSpec, SceneFile, TurnSpec};

pub(super) fn check(c: &Check, s: &SceneFile, ext: &mut Extent) -> R {
    names(c, "fix", s.fixes.iter().map(|f| f.name.as_deref()))?;
    names(c, "load", s.loads.iter().map(|l| l.name.as_deref()))?;
    for (i, f) in s.fixes.iter().enumerate() {
        let p = [P::K("fix"), P::I(i)];
        let key = format!("fix.{}", f.name.clone().unwrap_or_else(|| i.to_string()));
        c.selection(&sub(&p, "nodes"), &format!("{key}.nodes"), &f.nodes)?;
        c.ramp(&sub(&p, "value"), &format!("{key}.value"), &f.value, ext)?;
        kind(c, &p, &key, f)?;
        if let Some(t) = &f.turn {
            turn(c, &sub(&p, "turn"), &format!("{key}.turn"), t, f.direction.is_some())?;
        }
    }
    for (i, l) in s.loads.iter().enumerate() {
        let p = [P::K("load"), P::I(i)];
        let key = format!("load.{}", l.name.clone().unwrap_or_else(|| i.to_string()));
        c.selection(&sub(&p, "nodes"), &format!("{key}.nodes"), &l.nodes)?;
        c.ramp(
            &sub(&p, "total"),
            &format!("{key}.total"),
            &l.total,
            &mut Extent::default(),
        )?;
    }
    Ok(())
}

/// Names of a table's entries: unique, and a `--set` path segment that is not an index
/// (no `.`, `=` or blank, not all digits).
fn names<'a>(c: &Check, table: &str, names: impl Iterator<Item = Option<&'a str>>) -> R {
    let mut seen = std::collections::HashMap::new();
    for (i, n) in names.enumerate() {
        let Some(n) = n else { continue };
        let at = [P::K(table), P::I(i), P::K("name")];
        let key = format!("{table}.{i}.name");
        let bad_char = n.is_empty() || n.chars().any(|ch| ch == '.' || ch == '=' || ch.is_whitespace());
        if bad_char || n.chars().all(|ch| ch.is_ascii_digit()) {
            return Err(c.fail(
                &at,
                &key,
                format!("\"{n}\""),
                "a name must be usable in `--set` paths: not empty, no `.`, `=` or blanks, not a number",
                &format!("e.g. name = \"drag\", then --set {table}.drag.…=…"),
            ));
        }
        if let Some(first) = seen.insert(n, i) {
            return Err(c.fail(
                &at,
                &key,
                format!("\"{n}\""),
                &format!("[[{table}]] {first} has the same name"),
                &format!("give each [[{table}]] its own name (names address them in --set {table}.NAME.…)"),
            ));
        }
    }
    Ok(())
}

/// Exactly one of `components` (non-empty) and `direction` (finite, non-zero).
fn kind(c: &Check, p: &[P], key: &str, f: &FixSpec) -> R {
    match (&f.direction, f.components.is_empty()) {
        (None, false) => Ok(()),
        (None, true) => Err(c.fail(
            p,
            &format!("{key}.components"),
            "[]",
            "a fix needs the global components it prescribes, or a `direction`",
            "give components = [\"x\"], [\"y\"] or [\"x\", \"y\"], or direction = [dx, dy] for a skew support",
        )),
        (Some(d), false) => Err(c.fail(
            &sub(p, "direction"),
            &format!("{key}.direction"),
            format!("{d:?}"),
            "is given with `components`: a fix is either global components or one direction",
            "remove `components` (a skew support), or remove `direction`",
        )),
        (Some(d), true) => {
            for (k, v) in d.iter().enumerate() {
                c.finite(&sub(p, "direction"), &format!("{key}.direction[{k}]"), *v)?;
            }
            if d[0].hypot(d[1]) < 1e-12 {
                return Err(c.fail(
                    &sub(p, "direction"),
                    &format!("{key}.direction"),
                    format!("{d:?}"),
                    "has no length: it cannot be made a unit direction",
                    "give the direction of the prescribed displacement, e.g. [0.866, 0.5]",
                ));
            }
            Ok(())
        }
    }
}

/// A turn: a finite point, a finite non-zero axis, an angle history; not on a skew support.
fn turn(c: &Check, p: &[P], key: &str, t: &TurnSpec, skew: bool) -> R {
    if skew {
        return Err(c.fail(
            p,
            key,
            "turn",
            "is given with `direction`: a skew support cannot turn",
            "prescribe the turned components with components = [\"x\", \"y\", \"z\"]",
        ));
    }
    for k in 0..3 {
        c.finite(&sub(p, "point"), &format!("{key}.point[{k}]"), t.point[k])?;
        c.finite(&sub(p, "axis"), &format!("{key}.axis[{k}]"), t.axis[k])?;
    }
    if t.axis.iter().map(|a| a * a).sum::<f64>().sqrt() < 1e-12 {
        return Err(c.fail(
            &sub(p, "axis"),
            &format!("{key}.axis"),
            format!("{:?}", t.axis),
            "has no length: it cannot be made a unit direction",
            "give the axis to turn about, e.g. [0, 0, 1]",
        ));
    }
    // an angle, not a length: it does not widen the scene's extent
    c.ramp(
        &sub(p, "angle_deg"),
        &format!("{key}.angle_deg"),
        &t.angle_deg,
        &mut Extent::default(),
    )
}
