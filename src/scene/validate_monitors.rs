//! Checks of the `monitor` tables: unique labels, a node set or a rigid body (not both),
//! finite sign.

use super::{sub, Check, P, R};
use crate::scene::types::SceneFile;

pub(super) fn check(c: &Check, s: &SceneFile) -> R {
    let many = s.monitors.len() > 1;
    let mut seen = std::collections::HashSet::new();
    for (i, m) in s.monitors.iter().enumerate() {
        let path: Vec<P> = if many {
            vec![P::K("monitor"), P::I(i)]
        } else {
            vec![P::K("monitor")]
        };
        let key = |k: &str| {
            if many {
                format!("monitor.{i}.{k}")
            } else {
                format!("monitor.{k}")
            }
        };
        if !seen.insert(m.label.as_str()) {
            return Err(c.fail(
                &sub(&path, "label"),
                &key("label"),
                format!("\"{}\"", m.label),
                "two monitors have this label",
                "give each monitor its own label (it names a CSV column and a curve)",
            ));
        }
        match (&m.rigid, &m.body, &m.nodes) {
            (Some(r), None, None) => {
                if !s.rigid.iter().any(|b| &b.name == r) {
                    let known: Vec<&str> = s.rigid.iter().map(|b| b.name.as_str()).collect();
                    return Err(c.fail(
                        &sub(&path, "rigid"),
                        &key("rigid"),
                        format!("\"{r}\""),
                        "no rigid body has this name",
                        &format!("known rigid bodies: {}", known.join(", ")),
                    ));
                }
            }
            (None, Some(_), Some(sel)) => c.selection(&sub(&path, "nodes"), &key("nodes"), sel)?,
            (Some(_), _, _) => {
                return Err(c.fail(
                    &sub(&path, "rigid"),
                    &key("rigid"),
                    "given with `body`/`nodes`",
                    "a monitor watches either a rigid body or a node set of a body, not both",
                    "keep `rigid`, or `body` and `nodes`",
                ))
            }
            _ => {
                return Err(c.fail(
                    &path,
                    &key("body"),
                    "missing",
                    "a monitor needs `body` and `nodes` (a node set) or `rigid` (a rigid body)",
                    "e.g. `body = \"block\"` and `nodes = \"top\"`, or `rigid = \"punch\"`",
                ))
            }
        }
        c.finite(&sub(&path, "sign"), &key("sign"), m.sign)?;
        c.finite(&sub(&path, "force_scale"), &key("force_scale"), m.force_scale)?;
    }
    Ok(())
}
