//! Gmsh MSH 4.1 hexahedra: a 3D body from a file (the 3D counterpart of [`super::read_gmsh`]).
//!
//! - **Elements**: every 8-node hexahedron (Gmsh type 5) of the file belongs to the body.
//!   Gmsh numbers a hexahedron as the kernel does (`element::hex8`: nodes 0–3 the face
//!   `ζ = −1` counter-clockwise seen from `+ζ`, nodes 4–7 above them), so a well-ordered one
//!   has `det J > 0` at its centre and at the eight Gauss points; one that has not (inverted
//!   numbering, or degenerate) is refused naming the file and the element — never reordered,
//!   since a hexahedron numbered in another convention is not one permutation away.
//!   4-node quadrilaterals (type 3), 2-node lines and points are read for the physical groups
//!   only; any other type (tetrahedra, prisms, second order, …) is refused with a hint.
//! - **Physical groups → node sets**: every physical group (point, curve, surface or volume)
//!   is a node set under its name (`$PhysicalNames`; unnamed: its tag), plus `all`; nodes
//!   that no hexahedron uses are dropped.
//! - **Physical surfaces → faces**: the quadrilaterals of a physical surface whose
//!   quadrilaterals are all faces of exactly one hexahedron become a face, each
//!   quadrilateral ordered so that its normal `(x₁ − x₀) × (x₃ − x₀)` points out of its
//!   hexahedron (as [`super::box_mesh::BoxMesh`]'s faces). A surface through the interior is
//!   a node set only (listed in [`GmshSolidMesh::interior_surfaces`]).

use super::{element_name, node_table, parse, physical_names, unsupported, GmshError};
use crate::element::hex8::{Hex8Geometry, Hex8Kind};
use mshio::{ElementType, MshFile};
use std::collections::{BTreeMap, HashMap};

/// A 3D mesh read from a Gmsh file, indexed from 0 in the order of the file's node tags.
#[derive(Debug, Clone)]
pub struct GmshSolidMesh {
    pub nodes: Vec<[f64; 3]>,
    /// Hexahedra in Gmsh/VTK (= the kernel's) order.
    pub hexes: Vec<[usize; 8]>,
    /// Node sets by physical-group name, and `all`.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Boundary faces by physical-surface name, outward normals.
    pub faces: BTreeMap<String, Vec<[usize; 4]>>,
    /// Physical surfaces that are not faces (name, number of quadrilaterals not on the
    /// boundary).
    pub interior_surfaces: Vec<(String, usize)>,
}

use crate::model::hex_boundary::HEX_FACES;

/// Elements by use: hexahedra (tag, node tags) and the node tags of the lower-dimensional
/// elements per `(dim, entity)`, quadrilaterals apart.
#[derive(Default)]
struct Sorted {
    hexes: Vec<(u64, [u64; 8])>,
    quads: HashMap<i32, Vec<[u64; 4]>>,
    nodes_of: HashMap<(i32, i32), Vec<u64>>,
}

fn sort_elements(file: &str, msh: &MshFile<u64, i32, f64>) -> Result<Sorted, GmshError> {
    let mut s = Sorted::default();
    let Some(elements) = &msh.data.elements else {
        return Ok(s);
    };
    for b in &elements.element_blocks {
        let bad = |tag: u64| GmshError::Parse {
            file: file.into(),
            message: format!("element {tag} has the wrong number of nodes for its type"),
        };
        let key = (b.entity_dim, b.entity_tag);
        match b.element_type {
            ElementType::Hex8 => {
                for e in &b.elements {
                    let n: [u64; 8] = e.nodes.as_slice().try_into().map_err(|_| bad(e.element_tag))?;
                    s.hexes.push((e.element_tag, n));
                    s.nodes_of.entry(key).or_default().extend(n);
                }
            }
            ElementType::Qua4 => {
                for e in &b.elements {
                    let n: [u64; 4] = e.nodes.as_slice().try_into().map_err(|_| bad(e.element_tag))?;
                    s.quads.entry(b.entity_tag).or_default().push(n);
                    s.nodes_of.entry(key).or_default().extend(n);
                }
            }
            ElementType::Lin2 | ElementType::Pnt => {
                s.nodes_of
                    .entry(key)
                    .or_default()
                    .extend(b.elements.iter().flat_map(|e| &e.nodes));
            }
            other => {
                let code = element_name(other);
                let (kind, hint) = match code {
                    4 | 6 | 7 => ("3D element other than a hexahedron", "mesh the volume with hexahedra: `Mesh.RecombineAll = 1; Mesh.Recombine3DAll = 1;` on a transfinite or extruded volume (`Extrude {…} {…; Layers{n}; Recombine;}`)"),
                    _ => unsupported(code),
                };
                return Err(GmshError::UnsupportedElement {
                    file: file.into(),
                    kind: kind.into(),
                    code,
                    count: b.elements.len(),
                    entity: format!("entity ({}, {})", b.entity_dim, b.entity_tag),
                    hint: hint.into(),
                });
            }
        }
    }
    Ok(s)
}

/// Physical group tags of every entity, by `(dim, entity tag)`, volumes included.
fn entity_groups(msh: &MshFile<u64, i32, f64>) -> HashMap<(i32, i32), Vec<i32>> {
    let mut map = HashMap::new();
    if let Some(e) = &msh.data.entities {
        map.extend(e.points.iter().map(|p| ((0, p.tag), p.physical_tags.clone())));
        map.extend(e.curves.iter().map(|c| ((1, c.tag), c.physical_tags.clone())));
        map.extend(e.surfaces.iter().map(|c| ((2, c.tag), c.physical_tags.clone())));
        map.extend(e.volumes.iter().map(|c| ((3, c.tag), c.physical_tags.clone())));
    }
    map
}

/// Read a Gmsh MSH 4.1 mesh of hexahedra (ASCII or binary); `file` names it in errors.
pub fn read_gmsh_hex(file: &str, bytes: &[u8]) -> Result<GmshSolidMesh, GmshError> {
    let msh = parse(file, bytes)?;
    let names = physical_names(bytes);
    let groups = entity_groups(&msh);
    let coords = node_table(file, &msh)?;
    let sorted = sort_elements(file, &msh)?;
    if sorted.hexes.is_empty() {
        return Err(GmshError::NoHexes { file: file.into() });
    }
    let mut used: Vec<u64> = sorted.hexes.iter().flat_map(|h| h.1).collect();
    used.sort_unstable();
    used.dedup();
    let mut index = HashMap::with_capacity(used.len());
    let mut nodes = Vec::with_capacity(used.len());
    for tag in used {
        let Some(x) = coords.get(&tag).filter(|x| x.iter().all(|v| v.is_finite())) else {
            let element = sorted.hexes.iter().find(|h| h.1.contains(&tag)).map_or(0, |h| h.0);
            return Err(GmshError::MissingNode {
                file: file.into(),
                element,
                node: tag,
            });
        };
        index.insert(tag, nodes.len());
        nodes.push(*x);
    }
    let hexes = checked_hexes(file, &sorted, &index, &nodes)?;
    let name = |dim: i32, tag: i32| names.get(&(dim, tag)).cloned().unwrap_or_else(|| tag.to_string());
    let mut node_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (&(dim, entity), tags) in &sorted.nodes_of {
        for &g in groups.get(&(dim, entity)).into_iter().flatten() {
            let set = node_sets.entry(name(dim, g)).or_default();
            set.extend(tags.iter().filter_map(|t| index.get(t)));
        }
    }
    for set in node_sets.values_mut() {
        set.sort_unstable();
        set.dedup();
    }
    let (faces, interior_surfaces) = surface_faces(&sorted, &groups, &index, &hexes, &name);
    node_sets.insert("all".into(), (0..nodes.len()).collect());
    Ok(GmshSolidMesh {
        nodes,
        hexes,
        node_sets,
        faces,
        interior_surfaces,
    })
}

/// The hexahedra as node indices, each checked for `det J > 0` at its centre and Gauss points.
fn checked_hexes(
    file: &str,
    sorted: &Sorted,
    index: &HashMap<u64, usize>,
    nodes: &[[f64; 3]],
) -> Result<Vec<[usize; 8]>, GmshError> {
    let mut hexes = Vec::with_capacity(sorted.hexes.len());
    for (tag, h) in &sorted.hexes {
        let n = h.map(|t| index[&t]);
        if let Err(e) = Hex8Geometry::new(Hex8Kind::Hex8, &n.map(|i| nodes[i])) {
            let mut distinct = n.to_vec();
            distinct.sort_unstable();
            distinct.dedup();
            let what = if distinct.len() < 8 {
                "degenerate (a repeated node)".to_string()
            } else {
                format!("inverted or too distorted ({e}): nodes 0–3 must turn counter-clockwise seen from nodes 4–7, as Gmsh numbers them")
            };
            return Err(GmshError::BadHex {
                file: file.into(),
                element: *tag,
                what,
            });
        }
        hexes.push(n);
    }
    Ok(hexes)
}

type Faces = (BTreeMap<String, Vec<[usize; 4]>>, Vec<(String, usize)>);

/// The physical surfaces on the boundary as outward faces; the others as interior surfaces.
fn surface_faces(
    sorted: &Sorted,
    groups: &HashMap<(i32, i32), Vec<i32>>,
    index: &HashMap<u64, usize>,
    hexes: &[[usize; 8]],
    name: &dyn Fn(i32, i32) -> String,
) -> Faces {
    // every hexahedron face by its sorted nodes: the outward-ordered face, and how many
    // hexahedra have it
    let mut by_key: HashMap<[usize; 4], ([usize; 4], usize)> = HashMap::new();
    for h in hexes {
        for f in HEX_FACES {
            let face = f.map(|i| h[i]);
            let mut key = face;
            key.sort_unstable();
            by_key.entry(key).or_insert((face, 0)).1 += 1;
        }
    }
    let mut found: BTreeMap<String, (Vec<[usize; 4]>, usize)> = BTreeMap::new();
    for (entity, quads) in &sorted.quads {
        for &g in groups.get(&(2, *entity)).into_iter().flatten() {
            let slot = found.entry(name(2, g)).or_default();
            for q in quads {
                let Some(mut key) = q.iter().map(|t| index.get(t).copied()).collect::<Option<Vec<_>>>() else {
                    slot.1 += 1;
                    continue;
                };
                key.sort_unstable();
                let key: [usize; 4] = std::array::from_fn(|i| key[i]);
                match by_key.get(&key) {
                    Some((face, 1)) => slot.0.push(*face),
                    _ => slot.1 += 1,
                }
            }
        }
    }
    let mut faces = BTreeMap::new();
    let mut interior = Vec::new();
    for (n, (quads, off)) in found {
        if off == 0 {
            faces.insert(n, quads);
        } else {
            interior.push((n, off));
        }
    }
    (faces, interior)
}
