//! Checks of the `rigid` tables: exactly one shape; polylines, arcs and the pieces of a
//! composite outline well formed; an outline's pieces joined end to end; arc sides that agree
//! with the orientation; a 3D plane's and sphere's numbers finite, a plane's normal not zero,
//! a sphere's and a cylinder's radius positive, a cylinder's axis not zero.

use super::{named, sub, Check, Extent, P, R};
use crate::scene::types::{ArcSide, ArcSpec, CylinderSpec, PieceSpec, PlaneSpec, PolygonSpec, RigidSpec, SphereSpec};

/// Relative tolerance on the joints of an outline (of the outline's size).
pub const JOINT_TOL: f64 = 1e-9;

pub(super) fn check(c: &Check, i: usize, r: &RigidSpec, ext: &mut Extent) -> R {
    let key = named("rigid", &r.name);
    let p = [P::K("rigid"), P::I(i)];
    if let Some(pt) = r.point {
        c.point(&sub(&p, "point"), &format!("{key}.point"), pt, ext)?;
    }
    if let Some(pts) = &r.polyline {
        polyline(c, &sub(&p, "polyline"), &format!("{key}.polyline"), pts, ext)?;
    }
    if let Some(a) = &r.arc {
        arc(c, &sub(&p, "arc"), &format!("{key}.arc"), a, ext)?;
    }
    if let Some(pieces) = &r.outline {
        outline(c, &sub(&p, "outline"), &format!("{key}.outline"), pieces, ext)?;
    }
    if let Some(poly) = &r.polygon {
        polygon(c, &sub(&p, "polygon"), &format!("{key}.polygon"), poly, ext)?;
    }
    if let Some(pl) = &r.plane {
        plane(c, &sub(&p, "plane"), &format!("{key}.plane"), pl, ext)?;
    }
    if let Some(sp) = &r.sphere {
        sphere(c, &sub(&p, "sphere"), &format!("{key}.sphere"), sp, ext)?;
    }
    if let Some(cy) = &r.cylinder {
        cylinder(c, &sub(&p, "cylinder"), &format!("{key}.cylinder"), cy, ext)?;
    }
    for (k, m) in [("x", &r.motion.x), ("y", &r.motion.y), ("z", &r.motion.z)] {
        if let Some(m) = m {
            c.ramp(&sub(&sub(&p, "move"), k), &format!("{key}.move.{k}"), m, ext)?;
        }
    }
    Ok(())
}

/// A 3D point: finite coordinates, its reach added to the extent.
fn point3(c: &Check, path: &[P], key: &str, p: [f64; 3], ext: &mut Extent) -> R {
    for (k, x) in p.iter().enumerate() {
        c.finite(path, &format!("{key}[{k}]"), *x)?;
        ext.add(x.abs());
    }
    Ok(())
}

/// A direction: finite components, not all zero (`why` and `fix` of the refusal).
fn direction(c: &Check, path: &[P], key: &str, v: [f64; 3], (why, fix): (&str, &str)) -> R {
    for (k, x) in v.iter().enumerate() {
        c.finite(path, &format!("{key}[{k}]"), *x)?;
    }
    if v.iter().all(|x| *x == 0.0) {
        return Err(c.fail(path, key, format!("{v:?}"), why, fix));
    }
    Ok(())
}

/// A rigid plane: a finite point, a finite normal that is not zero.
fn plane(c: &Check, pp: &[P], key: &str, pl: &PlaneSpec, ext: &mut Extent) -> R {
    point3(c, &sub(pp, "point"), &format!("{key}.point"), pl.point, ext)?;
    let why = "a plane's normal must not be zero (it is made unit)";
    let fix = "give the outward normal, pointing from the rigid body towards the slaves, e.g. [0, 0, 1]";
    direction(c, &sub(pp, "normal"), &format!("{key}.normal"), pl.normal, (why, fix))?;
    Ok(())
}

/// A rigid sphere: a finite centre, a positive radius.
fn sphere(c: &Check, sp: &[P], key: &str, s: &SphereSpec, ext: &mut Extent) -> R {
    point3(c, &sub(sp, "centre"), &format!("{key}.centre"), s.centre, ext)?;
    c.positive(&sub(sp, "radius"), &format!("{key}.radius"), s.radius)?;
    ext.add(s.centre.iter().fold(0.0f64, |a, x| a.max(x.abs())) + s.radius);
    Ok(())
}

/// A rigid cylinder: a finite point, a finite axis that is not zero, a positive radius.
fn cylinder(c: &Check, cp: &[P], key: &str, s: &CylinderSpec, ext: &mut Extent) -> R {
    point3(c, &sub(cp, "point"), &format!("{key}.point"), s.point, ext)?;
    let why = "a cylinder's axis must not be zero (it is made unit)";
    let fix = "give the direction of the cylinder's axis, e.g. [0, 1, 0]";
    direction(c, &sub(cp, "axis"), &format!("{key}.axis"), s.axis, (why, fix))?;
    c.positive(&sub(cp, "radius"), &format!("{key}.radius"), s.radius)?;
    ext.add(s.point.iter().fold(0.0f64, |a, x| a.max(x.abs())) + s.radius);
    Ok(())
}

fn at<'a>(path: &[P<'a>], k: usize) -> Vec<P<'a>> {
    path.iter().copied().chain([P::I(k)]).collect()
}

fn polyline(c: &Check, pp: &[P], key: &str, pts: &[[f64; 2]], ext: &mut Extent) -> R {
    for (k, q) in pts.iter().enumerate() {
        c.point(&at(pp, k), &format!("{key}[{k}]"), *q, ext)?;
    }
    if pts.len() < 2 {
        return Err(c.fail(
            pp,
            key,
            format!("{} point(s)", pts.len()),
            "a polyline needs at least 2 points",
            "list at least two points [[x, y], [x, y]]",
        ));
    }
    for (k, w) in pts.windows(2).enumerate() {
        if w[0] == w[1] {
            return Err(c.fail(
                &at(pp, k + 1),
                &format!("{key}[{}]", k + 1),
                format!("{:?}", w[1]),
                "repeats the previous point (a segment of zero length)",
                "remove the repeated point",
            ));
        }
    }
    Ok(())
}

fn arc(c: &Check, ap: &[P], key: &str, a: &ArcSpec, ext: &mut Extent) -> R {
    c.point(&sub(ap, "centre"), &format!("{key}.centre"), a.centre, ext)?;
    c.positive(&sub(ap, "radius"), &format!("{key}.radius"), a.radius)?;
    ext.add(a.centre[0].abs().max(a.centre[1].abs()) + a.radius);
    c.finite(&sub(ap, "from_deg"), &format!("{key}.from_deg"), a.from_deg)?;
    c.finite(&sub(ap, "to_deg"), &format!("{key}.to_deg"), a.to_deg)?;
    let sweep = a.to_deg - a.from_deg;
    if sweep == 0.0 || sweep.abs() > 360.0 {
        return Err(c.fail(
            &sub(ap, "to_deg"),
            &format!("{key}.to_deg"),
            a.to_deg,
            &format!(
                "the arc from {}° sweeps {sweep}°; it must sweep more than 0° and at most 360°",
                a.from_deg
            ),
            "give from_deg and to_deg less than a full turn apart",
        ));
    }
    if let Some(side) = a.side {
        let ccw = sweep > 0.0;
        let want = if ccw { ArcSide::Inside } else { ArcSide::Outside };
        if side != want {
            return Err(c.fail(
                &sub(ap, "side"),
                &format!("{key}.side"),
                format!("\"{}\"", side.name()),
                &format!(
                    "the arc runs {} (from_deg = {}, to_deg = {}), which puts the rigid body {} the circle",
                    if ccw { "counter-clockwise" } else { "clockwise" },
                    a.from_deg,
                    a.to_deg,
                    want.name()
                ),
                "swap from_deg and to_deg, or correct `side` (inside: a disc, outside: a cavity)",
            ));
        }
    }
    Ok(())
}

fn polygon(c: &Check, pp: &[P], key: &str, poly: &PolygonSpec, ext: &mut Extent) -> R {
    c.point(&sub(pp, "centre"), &format!("{key}.centre"), poly.centre, ext)?;
    c.positive(&sub(pp, "radius"), &format!("{key}.radius"), poly.radius)?;
    for (k, v) in [
        ("from_deg", poly.from_deg),
        ("to_deg", poly.to_deg),
        ("facet_at_deg", poly.facet_at_deg),
    ] {
        c.finite(&sub(pp, k), &format!("{key}.{k}"), v)?;
    }
    if !(3..=100_000).contains(&poly.sides) {
        return Err(c.fail(
            &sub(pp, "sides"),
            &format!("{key}.sides"),
            poly.sides,
            "a regular polygon has 3 to 100 000 sides",
            "give e.g. sides = 8",
        ));
    }
    let sweep = poly.to_deg - poly.from_deg;
    if !(sweep > 0.0 && sweep <= 360.0) {
        return Err(c.fail(
            &sub(pp, "to_deg"),
            &format!("{key}.to_deg"),
            poly.to_deg,
            "the outline runs counter-clockwise from from_deg to to_deg, at most a turn",
            "give from_deg < to_deg ≤ from_deg + 360",
        ));
    }
    ext.add(poly.centre[0].abs().max(poly.centre[1].abs()) + poly.radius);
    Ok(())
}

/// First and last point of an outline piece.
pub fn piece_ends(piece: &PieceSpec) -> Option<([f64; 2], [f64; 2])> {
    match (&piece.line, &piece.arc) {
        (Some(pts), None) if pts.len() >= 2 => Some((pts[0], pts[pts.len() - 1])),
        (None, Some(a)) => {
            let at = |deg: f64| {
                let t = deg.to_radians();
                [a.centre[0] + a.radius * t.cos(), a.centre[1] + a.radius * t.sin()]
            };
            Some((at(a.from_deg), at(a.to_deg)))
        }
        _ => None,
    }
}

fn outline(c: &Check, op: &[P], key: &str, pieces: &[PieceSpec], ext: &mut Extent) -> R {
    if pieces.is_empty() {
        return Err(c.fail(
            op,
            key,
            "[]",
            "an outline needs at least one piece",
            "list its pieces in order: outline = [{ line = [[x, y], ...] }, { arc = { ... } }, ...]",
        ));
    }
    for (k, piece) in pieces.iter().enumerate() {
        let pp = at(op, k);
        let pk = format!("{key}[{k}]");
        match (&piece.line, &piece.arc) {
            (Some(pts), None) => polyline(c, &sub(&pp, "line"), &format!("{pk}.line"), pts, ext)?,
            (None, Some(a)) => arc(c, &sub(&pp, "arc"), &format!("{pk}.arc"), a, ext)?,
            _ => {
                return Err(c.fail(
                    &pp,
                    &pk,
                    "a piece",
                    "each piece is exactly one of `line` (a polyline) or `arc`",
                    "write { line = [[x, y], [x, y]] } or { arc = { centre = [x, y], radius = r, from_deg = a, to_deg = b } }",
                ))
            }
        }
    }
    let size = pieces
        .iter()
        .filter_map(piece_ends)
        .flat_map(|(a, b)| [a, b])
        .fold(1.0f64, |m, q| m.max(q[0].abs()).max(q[1].abs()));
    for k in 1..pieces.len() {
        let (Some((_, end)), Some((start, _))) = (piece_ends(&pieces[k - 1]), piece_ends(&pieces[k])) else {
            continue;
        };
        let gap = (start[0] - end[0]).hypot(start[1] - end[1]);
        if gap > JOINT_TOL * size {
            return Err(c.fail(
                &at(op, k),
                &format!("{key}[{k}]"),
                format!("starts at [{:.6}, {:.6}]", start[0], start[1]),
                &format!(
                    "the pieces of an outline join end to end: piece {} ends at [{:.6}, {:.6}], {gap:.3e} away",
                    k - 1,
                    end[0],
                    end[1]
                ),
                "start each piece where the previous one ends (for an arc: centre + radius·(cos from_deg, sin from_deg))",
            ));
        }
    }
    Ok(())
}
