//! Checks of a body's `[body.mesh]`: sizes, element counts, grading and its bias and focus,
//! rotation; each returns a lower bound of the mesh's smallest element edge.

use super::{sub, Check, Extent, MAX_COORDINATE, P};
use crate::scene::types::{Bias, GridAxes, MeshSpec, Rotation};
use crate::scene::SceneError;

/// Checks a body's mesh (`mesh`: its path, `key`: `body.NAME`) and returns a lower bound of
/// its smallest element edge (infinite for a Gmsh file, checked when read).
pub(super) fn check(c: &Check, mesh: &[P], key: &str, spec: &MeshSpec, ext: &mut Extent) -> Result<f64, SceneError> {
    match spec {
        MeshSpec::Rectangle {
            origin,
            size,
            elements,
            grading,
            bias,
            focus,
            rotate,
        } => rectangle(
            c,
            mesh,
            key,
            (origin, size),
            (elements, grading, bias),
            (*focus, rotate.as_ref()),
            ext,
        ),
        // checked when the file is read (`model::gmsh`): its size is not known here
        MeshSpec::Gmsh { .. } | MeshSpec::Gmsh3d { .. } => Ok(f64::INFINITY),
        MeshSpec::Box {
            origin,
            size,
            elements,
            grading,
        } => box_mesh(c, mesh, key, (origin, size, elements, grading), ext),
        MeshSpec::HemisphereShell {
            centre,
            radius,
            elements,
        }
        | MeshSpec::SphereShell {
            centre,
            radius,
            elements,
            ..
        } => sphere_shell(c, mesh, key, (centre, radius, elements), ext),
        MeshSpec::Revolved {
            origin,
            size,
            elements,
            grading,
            around,
            core,
            turn_deg,
        } => revolved(
            c,
            mesh,
            key,
            (origin, size, elements, grading),
            (*around, *core, *turn_deg),
            ext,
        ),
        MeshSpec::Annulus {
            centre,
            radius,
            angle_deg,
            elements,
            grading,
            bias,
            focus,
        } => {
            let around = annulus(c, mesh, key, (centre, radius, angle_deg, elements), ext)?;
            let span = [*angle_deg, *radius].map(|[a, b]| [a.min(b), a.max(b)]);
            let f = axes(c, mesh, key, elements, grading, bias, *focus, span)?;
            Ok(around * f[0].min(f[1]))
        }
    }
}

/// A rectangle's origin, size, grading and rotation; the smallest element edge.
fn rectangle(
    c: &Check,
    mesh: &[P],
    key: &str,
    (origin, size): (&[f64; 2], &[f64; 2]),
    (elements, grading, bias): GridAxes,
    (focus, rotate): (Option<[f64; 2]>, Option<&Rotation>),
    ext: &mut Extent,
) -> Result<f64, SceneError> {
    c.point(&sub(mesh, "origin"), &format!("{key}.mesh.origin"), *origin, ext)?;
    for (k, s) in size.iter().enumerate() {
        c.positive(&sub(mesh, "size"), &format!("{key}.mesh.size[{k}]"), *s)?;
    }
    let span = [0, 1].map(|k| [origin[k], origin[k] + size[k]]);
    let f = axes(c, mesh, key, elements, grading, bias, focus, span)?;
    let h = (0..2)
        .map(|k| size[k] / elements[k] as f64 * f[k])
        .fold(f64::INFINITY, f64::min);
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        .map(|[a, b]| [origin[0] + a * size[0], origin[1] + b * size[1]]);
    let reach = match rotate {
        Some(r) => rotation(c, mesh, key, r, *origin, &corners, ext)?,
        None => corners.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs())),
    };
    ext.add(reach);
    if !ext.0.is_finite() || reach > MAX_COORDINATE {
        return Err(c.fail(
            mesh,
            &format!("{key}.mesh"),
            format!("a corner {reach:e} from the origin"),
            &format!("reaches more than {MAX_COORDINATE:e} from the origin"),
            "give a smaller mesh (or change the unit of length)",
        ));
    }
    Ok(h)
}

/// Element counts, grading, bias and focus of the two axes of a structured mesh spanning
/// `span[k] = [from, to]`; returns per axis a lower bound of its smallest element over the
/// uniform one: with `G = max(g, 1/g)` every element is at most `G` times the smallest, so a
/// side of length `L_s` (of the axis' `L`, `L_s = L` but towards a `focus`) cut into at most
/// `n` elements has none shorter than `L_s / (n G)`, i.e. `(L_s / L) / G` times `L / n`.
#[allow(clippy::too_many_arguments)]
fn axes(
    c: &Check,
    mesh: &[P],
    key: &str,
    elements: &[usize; 2],
    grading: &[f64; 2],
    bias: &[Bias; 2],
    focus: Option<[f64; 2]>,
    span: [[f64; 2]; 2],
) -> Result<[f64; 2], SceneError> {
    let mut factor = [1.0; 2];
    for k in 0..2 {
        if elements[k] == 0 {
            return Err(c.fail(
                &sub(mesh, "elements"),
                &format!("{key}.mesh.elements[{k}]"),
                0,
                "must be ≥ 1",
                "give at least one element each way",
            ));
        }
        c.positive(&sub(mesh, "grading"), &format!("{key}.mesh.grading[{k}]"), grading[k])?;
        if !(1e-6..=1e6).contains(&grading[k]) {
            return Err(c.fail(
                &sub(mesh, "grading"),
                &format!("{key}.mesh.grading[{k}]"),
                grading[k],
                "must be between 1e-6 and 1e6",
                "give the ratio of element sizes the `bias` names, e.g. 1 (uniform)",
            ));
        }
        let len = span[k][1] - span[k][0];
        let g = grading[k].max(1.0 / grading[k]);
        let mut shortest_side = len;
        if let (Bias::Centre, Some(f)) = (bias[k], focus) {
            let at = f[k];
            c.finite(&sub(mesh, "focus"), &format!("{key}.mesh.focus[{k}]"), at)?;
            if !(span[k][0] < at && at < span[k][1]) {
                return Err(c.fail(
                    &sub(mesh, "focus"),
                    &format!("{key}.mesh.focus[{k}]"),
                    at,
                    &format!(
                        "must lie strictly inside the mesh along that axis ({} .. {})",
                        span[k][0], span[k][1]
                    ),
                    "give an interior point to refine towards, or remove `focus` to refine the middle",
                ));
            }
            shortest_side = (at - span[k][0]).min(span[k][1] - at);
        }
        factor[k] = shortest_side / len / g;
    }
    if focus.is_some() && !bias.contains(&Bias::Centre) {
        return Err(c.fail(
            &sub(mesh, "focus"),
            &format!("{key}.mesh.focus"),
            format!("{:?}", focus.unwrap_or_default()),
            &format!(
                "is used only along an axis with bias = \"centre\" (bias is [\"{}\", \"{}\"])",
                bias[0].name(),
                bias[1].name()
            ),
            "set bias = [\"centre\", \"centre\"] (or on one axis), or remove `focus`",
        ));
    }
    Ok(factor)
}

/// The rotation's angle and point; returns the largest coordinate of the turned `corners`.
fn rotation(
    c: &Check,
    mesh: &[P],
    key: &str,
    r: &Rotation,
    origin: [f64; 2],
    corners: &[[f64; 2]],
    ext: &mut Extent,
) -> Result<f64, SceneError> {
    let at = sub(mesh, "rotate");
    c.finite(&at, &format!("{key}.mesh.rotate.angle_deg"), r.angle_deg)?;
    let about = r.about.unwrap_or(origin);
    c.point(&at, &format!("{key}.mesh.rotate.about"), about, ext)?;
    let mut turned = corners.to_vec();
    crate::model::mesh::rotate(&mut turned, r.angle_deg, about);
    Ok(turned.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs())))
}

/// The checks of an annulus' centre, radii and angles; returns its smallest element edge
/// when uniform.
fn annulus(
    c: &Check,
    mesh: &[P],
    key: &str,
    (centre, radius, angle_deg, elements): (&[f64; 2], &[f64; 2], &[f64; 2], &[usize; 2]),
    ext: &mut Extent,
) -> Result<f64, SceneError> {
    c.point(&sub(mesh, "centre"), &format!("{key}.mesh.centre"), *centre, ext)?;
    for k in 0..2 {
        c.positive(&sub(mesh, "radius"), &format!("{key}.mesh.radius[{k}]"), radius[k])?;
        c.finite(
            &sub(mesh, "angle_deg"),
            &format!("{key}.mesh.angle_deg[{k}]"),
            angle_deg[k],
        )?;
        if elements[k] == 0 {
            return Err(c.fail(
                &sub(mesh, "elements"),
                &format!("{key}.mesh.elements[{k}]"),
                0,
                "must be ≥ 1",
                "give at least one element each way",
            ));
        }
    }
    let sweep = (angle_deg[1] - angle_deg[0]).abs();
    if radius[1] <= radius[0] || sweep == 0.0 || sweep > 360.0 {
        return Err(c.fail(
            mesh,
            &format!("{key}.mesh"),
            format!("radius {radius:?}, angle_deg {angle_deg:?}"),
            "needs radius[0] < radius[1] and two different angles at most a turn apart",
            "e.g. radius = [1.0, 1.005], angle_deg = [0.0, 180.0]",
        ));
    }
    ext.add(centre[0].abs().max(centre[1].abs()) + radius[1]);
    let around = radius[0] * sweep.to_radians() / elements[0] as f64;
    Ok(around.min((radius[1] - radius[0]) / elements[1] as f64))
}

/// Checks a `box` mesh: a finite origin, positive sizes, at least one element per axis,
/// positive grading; returns the smallest element edge.
/// The section of a revolved mesh checked as the box of its extent along r, z and around
/// (`r₀ ≥ 0`, `around ≥ 1`, `0 < core < 1`).
fn revolved(
    c: &Check,
    mesh: &[P],
    key: &str,
    (origin, size, elements, grading): (&[f64; 2], &[f64; 2], &[usize; 2], &[f64; 2]),
    (around, core, turn_deg): (usize, f64, f64),
    ext: &mut Extent,
) -> Result<f64, SceneError> {
    let whole_turns = turn_deg == 90.0 || (origin[0] > 0.0 && (turn_deg == 180.0 || turn_deg == 360.0));
    if !whole_turns {
        return Err(c.fail(
            &sub(mesh, "turn_deg"),
            &format!("{key}.mesh.turn_deg"),
            turn_deg,
            "must be 90, or 180 or 360 for a hollow section (origin[0] > 0)",
            "model a full section as its quarter (90) with its symmetry planes",
        ));
    }
    if origin[0].is_nan() || origin[0] < 0.0 {
        return Err(c.fail(
            &sub(mesh, "origin"),
            &format!("{key}.mesh.origin[0]"),
            origin[0],
            "must be ≥ 0 (the section's least radius)",
            "give the section in x = r ≥ 0",
        ));
    }
    if around == 0 || !(core > 0.0 && core < 1.0) {
        return Err(c.fail(
            mesh,
            &format!("{key}.mesh"),
            format!("around = {around}, core = {core}"),
            "needs around ≥ 1 and 0 < core < 1",
            "e.g. around = 8, core = 0.5",
        ));
    }
    let r_max = origin[0] + size[0];
    let box_origin = [origin[0], origin[0], origin[1]];
    let box_size = [size[0], size[0], size[1]];
    let h = box_mesh(
        c,
        mesh,
        key,
        (
            &box_origin,
            &box_size,
            &[elements[0], around, elements[1]],
            &[grading[0], 1.0, grading[1]],
        ),
        ext,
    )?;
    Ok(h.min(std::f64::consts::FRAC_PI_2 * r_max / (around.max(2 * elements[0])) as f64))
}

fn box_mesh(
    c: &Check,
    mesh: &[P],
    key: &str,
    (origin, size, elements, grading): (&[f64; 3], &[f64; 3], &[usize; 3], &[f64; 3]),
    ext: &mut Extent,
) -> Result<f64, SceneError> {
    let mut h = f64::INFINITY;
    for k in 0..3 {
        c.finite(&sub(mesh, "origin"), &format!("{key}.mesh.origin[{k}]"), origin[k])?;
        c.positive(&sub(mesh, "size"), &format!("{key}.mesh.size[{k}]"), size[k])?;
        c.positive(&sub(mesh, "grading"), &format!("{key}.mesh.grading[{k}]"), grading[k])?;
        if elements[k] == 0 {
            return Err(c.fail(
                &sub(mesh, "elements"),
                &format!("{key}.mesh.elements[{k}]"),
                0,
                "must be ≥ 1",
                "give at least one element along each axis",
            ));
        }
        let xs = crate::model::mesh::graded_coords(size[k], elements[k], grading[k]);
        h = xs.windows(2).map(|w| w[1] - w[0]).fold(h, f64::min);
        ext.add(origin[k].abs().max((origin[k] + size[k]).abs()));
    }
    if !ext.0.is_finite() || ext.0 > MAX_COORDINATE {
        return Err(c.fail(
            mesh,
            &format!("{key}.mesh"),
            format!("a corner {:e} from the origin", ext.0),
            &format!("reaches more than {MAX_COORDINATE:e} from the origin"),
            "give a smaller mesh (or change the unit of length)",
        ));
    }
    Ok(h)
}

/// A hollow hemisphere or sphere: finite centre, `0 < inner < outer`, `n` even ≥ 2 and ≥ 1 layer;
/// its smallest edge is at least the inner radius' share of a cell's angle or a layer.
fn sphere_shell(
    c: &Check,
    mesh: &[P],
    key: &str,
    (centre, radius, elements): (&[f64; 3], &[f64; 2], &[usize; 2]),
    ext: &mut Extent,
) -> Result<f64, SceneError> {
    for (k, x) in centre.iter().enumerate() {
        c.finite(&sub(mesh, "centre"), &format!("{key}.mesh.centre[{k}]"), *x)?;
    }
    c.positive(&sub(mesh, "radius"), &format!("{key}.mesh.radius[0]"), radius[0])?;
    if radius[1].partial_cmp(&radius[0]) != Some(std::cmp::Ordering::Greater) || !radius[1].is_finite() {
        return Err(c.fail(
            &sub(mesh, "radius"),
            &format!("{key}.mesh.radius"),
            format!("[{}, {}]", radius[0], radius[1]),
            "must be [inner, outer] with 0 < inner < outer",
            "give the inner radius first",
        ));
    }
    let [n, layers] = *elements;
    if n < 2 || n % 2 == 1 || layers == 0 {
        return Err(c.fail(
            &sub(mesh, "elements"),
            &format!("{key}.mesh.elements"),
            format!("[{n}, {layers}]"),
            "must be [n, layers] with n even and ≥ 2, layers ≥ 1",
            "give e.g. elements = [8, 2]",
        ));
    }
    ext.add(centre.iter().fold(0.0f64, |m, x| m.max(x.abs())) + radius[1]);
    if !ext.0.is_finite() || ext.0 > MAX_COORDINATE {
        return Err(c.fail(
            mesh,
            &format!("{key}.mesh"),
            format!("a point {:e} from the origin", ext.0),
            &format!("reaches more than {MAX_COORDINATE:e} from the origin"),
            "give a smaller mesh (or change the unit of length)",
        ));
    }
    // the equiangular cells span π/(2n) of arc, the narrowest by a factor cos²(π/4) = 1/2
    let around = radius[0] * std::f64::consts::FRAC_PI_2 / n as f64 * 0.5;
    Ok(around.min((radius[1] - radius[0]) / layers as f64))
}
