//! A scene of 3D bodies (`mesh = { kind = "box", … }`) resolved into a [`Model<Solid>`]: the
//! bodies' hexahedral meshes, then the same fixes, loads and monitors as in 2D
//! (`build_steps.rs`, generic over the dimension), the rigid planes and spheres and the
//! contact pairs (`build_surface_pairs.rs`). What 3D does not have yet — pressures, body
//! loads, skew supports, the 2D body models — is refused, naming the missing feature.

use super::build::Ctx;
use super::types::{BodyModel, MeshSpec, SceneFile};
use super::{SceneError, SceneSource};
use crate::model::box_mesh::BoxMesh;
use crate::model::{Body, Element, Model, Solid, SolidKind};
use crate::problem::Problem;
use crate::settings::SolverSettings;

/// Whether the scene is 3D: one of its bodies has a 3D mesh.
pub fn is_3d(s: &SceneFile) -> bool {
    s.bodies.iter().any(|b| b.mesh.is_3d())
}

/// Build the problem of a checked 3D scene.
pub fn build_solid(src: &SceneSource, s: &SceneFile) -> Result<Problem<Solid>, SceneError> {
    super::validate::validate(src, s)?;
    let cx = Ctx::new(src);
    let end = super::build::steps::checked_end(&cx, s)?;
    refuse_2d_only(&cx, s)?;
    let mut m = Model::<Solid> {
        name: s.name.clone(),
        description: s.description.clone(),
        ..Model::default()
    };
    add_solid_bodies(&cx, src, s, &mut m)?;
    super::build::steps::add_fixes(&cx, s, &mut m, end)?;
    super::build::steps::add_loads(&cx, s, &mut m, end)?;
    let rigid = super::build_surface_pairs::rigid_surfaces(&cx, s, end)?;
    super::build_surface_pairs::add_surface_contacts(&cx, s, &mut m, &rigid)?;
    super::build_surface_pairs::refuse_rigid_overclosures(&cx, &m)?;
    super::build::steps::add_monitors(&cx, s, &mut m)?;
    Ok(Problem {
        model: m,
        settings: SolverSettings {
            stepping: s.stepping.clone(),
            newton: s.solver.clone(),
        },
    })
}

/// What a 3D scene cannot have yet, refused with the missing feature named.
fn refuse_2d_only(cx: &Ctx, s: &SceneFile) -> Result<(), SceneError> {
    let missing = |near: &str, what: &str| {
        cx.err(
            near,
            format!("this scene has 3D bodies (a `box` mesh) and {what}: not in contrail's 3D models yet"),
            "surface and body loads come in a later slice of issue 33; remove them, or mesh the bodies in 2D",
        )
    };
    if !s.pressures.is_empty() {
        return Err(missing("pressure", "pressures ([[pressure]])"));
    }
    if let Some(b) = s.body_loads.first() {
        return Err(missing(&b.body, "body loads ([[body_load]])"));
    }
    if let Some(b) = s.bodies.iter().find(|b| !b.mesh.is_3d()) {
        return Err(cx.err(
            &b.name,
            format!("body `{}` has a 2D mesh in a scene of 3D bodies", b.name),
            "a scene is 2D or 3D in all its bodies: give every body a `box` mesh, or none",
        ));
    }
    if let Some(b) = s
        .bodies
        .iter()
        .find(|b| b.model != BodyModel::PlaneStrain || b.thickness.is_some())
    {
        return Err(cx.err(
            &b.name,
            format!(
                "body `{}`: model = \"{}\" is a 2D setting; its `box` mesh makes it 3D",
                b.name,
                b.model.name()
            ),
            "remove `model` and `thickness` from 3D bodies",
        ));
    }
    Ok(())
}

/// The 3D bodies: material, element (the scene's `element` key mapped by
/// [`SolidKind::from_element`]), box or Gmsh mesh with its node sets and faces.
fn add_solid_bodies(cx: &Ctx, src: &SceneSource, s: &SceneFile, m: &mut Model<Solid>) -> Result<(), SceneError> {
    for b in &s.bodies {
        let material = super::build::steps::body_material(cx, b, m.bodies.iter().any(|o| o.name == b.name))?;
        let Some(mesh) = solid_mesh(src, b)? else {
            continue;
        };
        super::build::steps::check_dof_limit(cx, s, b, 3 * (m.nodes.len() + mesh.nodes.len()))?;
        let (off, bi) = (m.nodes.len(), m.bodies.len());
        m.nodes.extend(mesh.nodes.iter().copied());
        (m.elements).extend(mesh.hexes.iter().map(|h| Element {
            nodes: h.map(|n| n + off),
            body: bi,
        }));
        m.bodies.push(Body {
            name: b.name.clone(),
            material,
            kind: SolidKind::from_element(b.element),
            kinematics: (),
            first_node: off,
            node_count: mesh.nodes.len(),
            node_sets: (mesh.node_sets.into_iter())
                .map(|(k, v)| (k, v.into_iter().map(|n| n + off).collect()))
                .collect(),
            faces: (mesh.faces.into_iter())
                .map(|(k, v)| (k, v.into_iter().map(|q| q.map(|n| n + off)).collect()))
                .collect(),
        });
    }
    Ok(())
}

/// The hexahedral mesh of a 3D body: its box, or its Gmsh file (`gmsh-3d`); `None` for a 2D
/// mesh (refused before).
fn solid_mesh(src: &SceneSource, b: &super::types::BodySpec) -> Result<Option<BoxMesh>, SceneError> {
    Ok(match &b.mesh {
        MeshSpec::Box {
            origin,
            size,
            elements,
            grading,
        } => Some(BoxMesh::new(*origin, *size, *elements, *grading)),
        MeshSpec::Revolved {
            origin,
            size,
            elements,
            grading,
            around,
            core,
            turn_deg,
        } => {
            let at = |k: usize| {
                crate::model::mesh::graded_coords(size[k], elements[k], grading[k])
                    .iter()
                    .map(|v| origin[k] + v)
                    .collect::<Vec<f64>>()
            };
            let quarters = (*turn_deg / 90.0).round() as usize;
            Some(crate::model::revolved_mesh::revolution(
                &at(0),
                &at(1),
                (*around, quarters),
                *core,
            ))
        }
        MeshSpec::HemisphereShell {
            centre,
            radius,
            elements,
        } => Some(crate::model::shell_mesh::hemisphere_shell(
            *centre,
            *radius,
            elements[0],
            elements[1],
        )),
        MeshSpec::SphereShell {
            centre,
            radius,
            elements,
            part,
        } => Some(crate::model::shell_mesh::sphere_shell(
            *centre,
            *radius,
            (elements[0], elements[1]),
            part.shell_part(),
        )),
        MeshSpec::Gmsh3d { file } => {
            let g = super::mesh::gmsh_solid(src, b, file)?;
            Some(BoxMesh {
                nodes: g.nodes,
                hexes: g.hexes,
                node_sets: g.node_sets,
                faces: g.faces,
            })
        }
        _ => None,
    })
}
