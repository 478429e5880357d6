//! The steps of [`super::build_model`], one per part of the scene, each adding to the model
//! what its part of the scene file describes (and refusing what it cannot build, naming the
//! entry and the fix).

use super::*;
use crate::element::quad::{ElementKind, Kinematics};

/// The scene's end time, after checking `[stepping]` has `end > 0` and `increments ≥ 1`.
pub(in crate::scene) fn checked_end(cx: &Ctx, s: &SceneFile) -> Result<f64, SceneError> {
    let end = s.stepping.end;
    if s.stepping.increments == 0 || end <= 0.0 {
        return Err(cx.err(
            "stepping",
            "stepping needs end > 0 and increments ≥ 1".into(),
            "fix [stepping]",
        ));
    }
    Ok(end)
}

/// Refuse a body that would take the model to `dofs` DOFs, beyond the scene's limit.
pub(in crate::scene) fn check_dof_limit(cx: &Ctx, s: &SceneFile, b: &BodySpec, dofs: usize) -> Result<(), SceneError> {
    if dofs <= s.limits.max_dofs {
        return Ok(());
    }
    Err(cx.err(
        &b.name,
        format!(
            "body `{}`: the model would have {dofs} DOFs, more than the limit of {}",
            b.name, s.limits.max_dofs
        ),
        "use a coarser mesh, or raise the limit with --set limits.max_dofs=N",
    ))
}

/// A body's material from its `[body.material]`, refusing a name already `taken` by another
/// body and elastic constants out of range (`E > 0`, `−1 < ν < 0.5`).
pub(in crate::scene) fn body_material(cx: &Ctx, b: &BodySpec, taken: bool) -> Result<Material, SceneError> {
    if taken {
        return Err(cx.err(
            &b.name,
            format!("two bodies are named `{}`", b.name),
            "give each body its own name",
        ));
    }
    let mat = &b.material;
    if mat.young <= 0.0 || !(-1.0 < mat.poisson && mat.poisson < 0.5) {
        return Err(cx.err(
            &b.name,
            format!("body `{}`: need young > 0 and −1 < poisson < 0.5", b.name),
            "fix [body.material]",
        ));
    }
    let (lambda, mu) = lame(mat.young, mat.poisson);
    Ok(match mat.model {
        MaterialModel::SaintVenantKirchhoff => Material::SaintVenantKirchhoff { lambda, mu },
        MaterialModel::NeoHookean => Material::NeoHookean { lambda, mu },
    })
}

/// The deformable bodies: material, mesh (nodes, elements, node sets and faces, numbered
/// after the bodies before); records each body's mesh file in `cx` for later messages.
pub(super) fn add_bodies(cx: &mut Ctx, s: &SceneFile, m: &mut Model) -> Result<(), SceneError> {
    let mut mesh_files = Vec::new();
    for b in &s.bodies {
        let material = body_material(cx, b, m.bodies.iter().any(|o| o.name == b.name))?;
        if b.element == ElementKind::SolidShell {
            return Err(cx.err(
                &b.name,
                format!("body `{}`: `solid-shell` is a 3D element and this mesh is 2D", b.name),
                "use q4-eas-safe (the default), q4-eas, q4-eas-stab or q4 for a 2D mesh; solid-shell for a box or Gmsh hexahedral mesh",
            ));
        }
        let kinematics = crate::scene::body_model::kinematics(cx, b)?;
        let mut mesh = body_mesh(cx.src, b)?;
        if kinematics == Kinematics::Axisymmetric {
            crate::scene::body_model::check_radii(cx, &b.name, &mut mesh.nodes)?;
        }
        check_dof_limit(cx, s, b, 2 * (m.nodes.len() + mesh.nodes.len()))?;
        mesh_files.push(mesh.file.clone());
        let off = m.nodes.len();
        let bi = m.bodies.len();
        m.nodes.extend(mesh.nodes.iter().copied());
        m.elements.extend(mesh.quads.iter().map(|q| Element {
            nodes: q.map(|n| n + off),
            body: bi,
        }));
        m.bodies.push(Body {
            name: b.name.clone(),
            material,
            kind: b.element,
            kinematics,
            first_node: off,
            node_count: mesh.nodes.len(),
            node_sets: mesh
                .node_sets
                .into_iter()
                .map(|(k, v)| (k, v.into_iter().map(|n| n + off).collect()))
                .collect(),
            faces: mesh
                .faces
                .into_iter()
                .map(|(k, v)| (k, v.into_iter().map(|s| s.map(|n| n + off)).collect()))
                .collect(),
        });
    }
    cx.mesh_files = mesh_files;
    Ok(())
}

/// The prescribed displacements (`[[fix]]`): global components, or a skew support along a
/// `direction` (made unit). A component prescribed twice is refused, and so is a node with a
/// skew support and any other fix (its two DOFs are turned into the support's frame).
pub(in crate::scene) fn add_fixes<S: Dim>(
    cx: &Ctx,
    s: &SceneFile,
    m: &mut Model<S>,
    end: f64,
) -> Result<(), SceneError> {
    let mut fixed = vec![false; m.dof_count()];
    let mut skew = vec![false; m.nodes.len()];
    let label = |i: usize, f: &FixSpec| f.name.clone().map_or(format!("[[fix]] {i}"), |n| format!("fix `{n}`"));
    for (i, f) in s.fixes.iter().enumerate() {
        let bi = body_index(cx, m, &f.body)?;
        let turn = turn_of::<S>(cx, f, &label(i, f), end)?;
        for n in select(cx, m, bi, &f.nodes)? {
            let twice = |what: &str| {
                cx.err(
                    f.name.as_deref().unwrap_or(&f.body),
                    format!("{}: node {n} of `{}` {what}", label(i, f), f.body),
                    "remove the overlap between [[fix]] entries (a skew support holds a node alone: fix both components with components = [\"x\", \"y\"] instead)",
                )
            };
            if skew[n] {
                return Err(twice("already has a skew support"));
            }
            if let Some(d) = f.direction {
                if S::D != 2 {
                    return Err(cx.err(
                        f.name.as_deref().unwrap_or(&f.body),
                        format!("{}: a skew support (`direction`) in a 3D model", label(i, f)),
                        "skew supports are 2D only for now: fix global components instead",
                    ));
                }
                if fixed[2 * n] || fixed[2 * n + 1] {
                    return Err(twice("already has a prescribed component"));
                }
                skew[n] = true;
                let len = d[0].hypot(d[1]);
                m.skew.push(SkewPrescribed {
                    node: n,
                    direction: [d[0] / len, d[1] / len],
                    ramp: ramp(&f.value, end),
                });
                continue;
            }
            for &c in &f.components {
                let k = comp_of::<S>(cx, c, &f.body)?;
                let dof = S::D * n + k;
                if fixed[dof] {
                    return Err(twice(&format!("component {c:?} is prescribed twice")));
                }
                fixed[dof] = true;
                m.prescribed.push(Prescribed {
                    dof,
                    ramp: ramp(&f.value, end),
                    turn: turn.as_ref().map(|(angle, axis, point)| {
                        let x = m.nodes[n].as_ref();
                        Turn {
                            angle: angle.clone(),
                            axis: *axis,
                            arm: std::array::from_fn(|c| x[c] - point[c]),
                            component: k,
                        }
                    }),
                });
            }
        }
    }
    Ok(())
}

/// The turn fix `f` prescribes, if it turns its nodes: its angle in radians, its unit axis
/// and a point of the axis (3D only; each node's [`Turn`] adds its arm and component).
type FixTurn = (Ramp, [f64; 3], [f64; 3]);

fn turn_of<S: Dim>(cx: &Ctx, f: &FixSpec, label: &str, end: f64) -> Result<Option<FixTurn>, SceneError> {
    let Some(t) = &f.turn else { return Ok(None) };
    if S::D != 3 {
        return Err(cx.err(
            f.name.as_deref().unwrap_or(&f.body),
            format!("{label}: a `turn` in a 2D model"),
            "turns are 3D only: prescribe the components' histories instead",
        ));
    }
    let len = t.axis.iter().map(|a| a * a).sum::<f64>().sqrt();
    let mut angle = ramp(&t.angle_deg, end);
    angle.knots.iter_mut().for_each(|kn| kn.1 = kn.1.to_radians());
    Ok(Some((angle, t.axis.map(|a| a / len), t.point)))
}

/// The nodal loads (`[[load]]`: a total shared equally by the selected nodes) and the body
/// loads.
pub(in crate::scene) fn add_loads<S: Dim>(
    cx: &Ctx,
    s: &SceneFile,
    m: &mut Model<S>,
    end: f64,
) -> Result<(), SceneError> {
    for l in &s.loads {
        let bi = body_index(cx, m, &l.body)?;
        let nodes = select(cx, m, bi, &l.nodes)?;
        let share = 1.0 / nodes.len() as f64;
        let mut r = ramp(&l.total, end);
        r.knots.iter_mut().for_each(|k| k.1 *= share);
        for n in nodes {
            m.loads.push(NodalLoad {
                dof: S::D * n + comp_of::<S>(cx, l.component, &l.body)?,
                ramp: r.clone(),
            });
        }
    }
    Ok(())
}

/// The body loads (2D).
pub(super) fn add_body_loads(cx: &Ctx, s: &SceneFile, m: &mut Model, end: f64) -> Result<(), SceneError> {
    for bl in &s.body_loads {
        body_load(cx, m, bl, end)?;
    }
    Ok(())
}

/// Consistent nodal forces of a dead body load, summed per DOF, as nodal loads.
fn body_load(cx: &Ctx, m: &mut Model, bl: &BodyLoadSpec, end: f64) -> Result<(), SceneError> {
    let bi = body_index(cx, m, &bl.body)?;
    if !bl.force.iter().all(|v| v.is_finite()) {
        return Err(cx.err(
            &bl.body,
            format!("body_load on `{}`: force {:?} is not finite", bl.body, bl.force),
            "give a finite force per unit volume [bx, by]",
        ));
    }
    let factor = bl.factor.as_ref().map_or(Ramp::linear(1.0, end), |f| ramp(f, end));
    let mut total = std::collections::BTreeMap::<usize, f64>::new();
    let mut f = [0.0; 8];
    for e in m.elements.iter().filter(|e| e.body == bi) {
        let x = e.nodes.map(|n| m.nodes[n]);
        let kinematics = m.bodies[bi].kinematics;
        crate::element::body_force::quad_body_force_with(&x, bl.force, kinematics, &mut f);
        for (i, &n) in e.nodes.iter().enumerate() {
            for c in 0..2 {
                *total.entry(2 * n + c).or_default() += f[2 * i + c];
            }
        }
    }
    for (dof, value) in total.into_iter().filter(|(_, v)| *v != 0.0) {
        let mut r = factor.clone();
        r.knots.iter_mut().for_each(|k| k.1 *= value);
        m.loads.push(NodalLoad { dof, ramp: r });
    }
    Ok(())
}

/// The rigid bodies: shape and motion (the 3D keys `plane`, `sphere`, `cylinder`, `move.z` refused).
pub(super) fn add_rigid(cx: &Ctx, s: &SceneFile, m: &mut Model, end: f64) -> Result<(), SceneError> {
    for r in &s.rigid {
        refuse_3d_rigid(cx, r)?;
        let shape = rigid_shape(cx, r)?;
        m.rigid.push(RigidBody {
            name: r.name.clone(),
            shape,
            motion: [motion_ramp(&r.motion.x, end), motion_ramp(&r.motion.y, end)],
        });
    }
    Ok(())
}

/// A 2D scene's rigid body with a 3D key (`plane`, `sphere`, `cylinder`, `move.z`) is refused.
fn refuse_3d_rigid(cx: &Ctx, r: &RigidSpec) -> Result<(), SceneError> {
    let key = [
        ("plane", r.plane.is_some()),
        ("sphere", r.sphere.is_some()),
        ("cylinder", r.cylinder.is_some()),
        ("move.z", r.motion.z.is_some()),
    ]
    .into_iter()
    .find_map(|(k, given)| given.then_some(k));
    match key {
        Some(k) => Err(cx.err(
            &r.name,
            format!("rigid body `{}`: `{k}` is a 3D rigid surface in a 2D scene", r.name),
            "a 2D rigid body is a point, polyline, arc, outline or polygon moved in x and y (a cylinder's section is an `arc`); `plane`, `sphere`, `cylinder` and `move.z` need 3D bodies (a `box` or `gmsh-3d` mesh)",
        )),
        None => Ok(()),
    }
}

/// The contact pairs of the scene, then the pairs they imply (second passes, the vertices of
/// rigid outlines not named as slaves elsewhere), and the vertex regions each pair owns.
pub(super) fn add_contacts(cx: &Ctx, s: &SceneFile, m: &mut Model) -> Result<(), SceneError> {
    let h = max_edge(m);
    let mut implied = Vec::new();
    for c in &s.contacts {
        refuse_rounded_vertex(cx, s, c)?;
        let mut pair = contact_pair(cx, m, c, h)?;
        implied.extend(build_pairs::implied_pairs(cx, m, c, &mut pair)?);
        m.contacts.push(pair);
    }
    // the vertices a scene names as slaves keep their pairs; the others get one per outline
    let taken: Vec<(usize, usize)> = m
        .contacts
        .iter()
        .flat_map(|p| p.slaves.iter())
        .filter_map(|s| match s {
            Slave::RigidVertex(b, v) => Some((*b, *v)),
            _ => None,
        })
        .collect();
    for (pair, slave_body) in implied {
        match pair {
            build_pairs::Implied::SecondPass(p) => m.contacts.push(*p),
            build_pairs::Implied::Vertices(ip) => {
                if let Some(p) = build_pairs::vertex_pair(m, &m.contacts[ip], slave_body, &taken) {
                    m.contacts.push(p);
                }
            }
        }
    }
    build_pairs::own_vertices(m);
    Ok(())
}

/// The monitors: a rigid body's travel and force, or a node set's mean displacement and
/// summed reaction.
pub(in crate::scene) fn add_monitors<S: Dim>(cx: &Ctx, s: &SceneFile, m: &mut Model<S>) -> Result<(), SceneError> {
    for mon in s.monitors.iter() {
        let target = match (&mon.rigid, &mon.body, &mon.nodes) {
            (Some(r), None, None) if S::D == 3 => {
                let paired = (m.surface_contacts.iter())
                    .any(|p| matches!(&p.master, crate::model::SurfaceMaster::Rigid(rs) if &rs.name == r));
                if !paired {
                    return Err(cx.err(
                        &mon.label,
                        format!(
                            "monitor `{}`: no contact pair has the rigid surface `{r}` as its master",
                            mon.label
                        ),
                        "name a rigid surface that a [[contact]] presses on, or monitor a node set",
                    ));
                }
                MonitorTarget::RigidSurface(r.clone())
            }
            (Some(r), None, None) => MonitorTarget::Rigid(rigid_index(cx, m, r)?),
            (None, Some(b), Some(sel)) => {
                let bi = body_index(cx, m, b)?;
                let nodes = select(cx, m, bi, sel)?;
                match mon.about {
                    None => MonitorTarget::Nodes(nodes),
                    Some(point) if S::D == 3 => MonitorTarget::Moment { nodes, point },
                    Some(_) => {
                        return Err(cx.err(
                            &mon.label,
                            format!("monitor `{}`: `about` (a moment) in a 2D model", mon.label),
                            "moments are monitored in 3D only: remove `about`",
                        ))
                    }
                }
            }
            _ => {
                return Err(cx.err(
                    &mon.label,
                    format!(
                        "monitor `{}` needs either `rigid` or both `body` and `nodes`",
                        mon.label
                    ),
                    "e.g. `rigid = \"punch\"`, or `body = \"block\"` with `nodes = \"top\"`",
                ))
            }
        };
        m.monitors.push(Monitor {
            label: mon.label.clone(),
            target,
            component: comp_of::<S>(cx, mon.component, &mon.label)?,
            sign: mon.sign,
            force_scale: mon.force_scale,
        });
    }
    Ok(())
}
