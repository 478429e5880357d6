//! Gmsh meshes: MSH 4.1 files (ASCII or binary, parsed by the `mshio` crate) → linear
//! quadrilaterals with named node sets and boundary faces, in the conventions of
//! [`super::mesh::RectMesh`].
//!
//! - **Elements**: every 4-node quadrilateral (Gmsh type 3) of the file belongs to the body;
//!   quadrilaterals numbered clockwise are renumbered counter-clockwise, non-convex or
//!   degenerate ones are errors. Any other 2D or 3D element type (triangles, second-order
//!   elements, …) is an error that says which setting of the `.geo` makes quadrilaterals.
//!   Points (type 15) and 2-node lines (type 1) are read for the physical groups only.
//! - **Physical groups → node sets**: every physical group (point, curve or surface) is a
//!   node set under its name (`$PhysicalNames`; an unnamed group is named by its tag), plus
//!   `all`. Nodes that no quadrilateral uses (the centre point of an arc, …) are dropped.
//! - **Physical curves → faces**: the 2-node lines of a physical curve whose lines all lie
//!   on the boundary of the quadrilaterals become a face: a chain of segments `[a, b]`
//!   oriented so that the body is on their left (counter-clockwise around the body, the
//!   outward normal is the segment direction turned by −90°), whatever the direction of
//!   the curve in the `.geo`. A curve through the interior is a node set, not a face.
//! - The mesh must lie in the plane `z = 0`.
//!
//! Node tags are those of the file; `mshio` keeps them only when they are sparse, so a file
//! with dense tags must list its node blocks in tag order (Gmsh does).

use std::collections::{BTreeMap, HashMap, HashSet};

use mshio::{ElementType, MshFile};

/// A mesh read from a Gmsh file: nodes, counter-clockwise quadrilaterals, node sets and
/// faces, indexed from 0 in the order of the file's node tags.
#[derive(Debug, Clone)]
pub struct GmshMesh {
    /// Node coordinates `[x, y]`.
    pub nodes: Vec<[f64; 2]>,
    /// Quadrilaterals, counter-clockwise.
    pub quads: Vec<[usize; 4]>,
    /// Node sets by physical-group name, and `all`.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Boundary faces by physical-curve name (segments counter-clockwise around the body).
    pub faces: BTreeMap<String, Vec<[usize; 2]>>,
    /// Quadrilaterals that were numbered clockwise in the file and have been renumbered.
    pub reoriented: usize,
    /// Physical curves that are not faces because some of their lines are not on the
    /// boundary (name, number of such lines).
    pub interior_curves: Vec<(String, usize)>,
}

/// A Gmsh file that cannot be used as a body mesh. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum GmshError {
    #[error("{file}: cannot read the mesh file: {source}\n  hint: {hint}")]
    Read {
        file: String,
        source: std::io::Error,
        hint: String,
    },
    #[error("{file}: MSH format {version} is not supported (contrail reads MSH 4.1, ASCII or binary, with 8-byte sizes)\n  hint: export it again with `gmsh FILE.geo -2 -format msh41` (add `-bin` for binary), or in the GUI: File > Export > Gmsh MSH, Version 4 ASCII/Binary")]
    Version { file: String, version: String },
    #[error("{file}: not a readable Gmsh MSH 4.1 file: {message}\n  hint: write it with `gmsh FILE.geo -2 -format msh41`; a file edited by hand must keep the section counts consistent")]
    Parse { file: String, message: String },
    #[error("{file}: {count} element(s) of Gmsh type {code} ({kind}) on {entity}: contrail meshes a body with 4-node quadrilaterals only\n  hint: {hint}")]
    UnsupportedElement {
        file: String,
        kind: String,
        code: u8,
        count: usize,
        entity: String,
        hint: String,
    },
    #[error("{file}: the file has no quadrilaterals\n  hint: put the surface in a physical group (`Physical Surface(\"body\") = {{1}};`) and recombine it (`Mesh.RecombineAll = 1;`), or save every element with `Mesh.SaveAll = 1;`")]
    NoQuads { file: String },
    #[error("{file}: element {element} refers to node {node}, which the $Nodes section does not have\n  hint: the file is inconsistent; export it again from Gmsh")]
    MissingNode { file: String, element: u64, node: u64 },
    #[error("{file}: node {node} has z = {z:e}; a body mesh must lie in the plane z = 0\n  hint: draw the geometry in the x–y plane")]
    NotPlanar { file: String, node: u64, z: f64 },
    #[error("{file}: quadrilateral {element} is {what}\n  hint: remesh (e.g. a smaller size or `Mesh.Smoothing = 10;`); contrail needs convex quadrilaterals")]
    BadQuad { file: String, element: u64, what: String },
    #[error("{file}: physical group `{group}` has node {node}, which no quadrilateral uses\n  hint: a node set must lie on the meshed surface; check the group's entities")]
    NodeOffBody { file: String, group: String, node: u64 },
    #[error("{file}: the $Nodes section is inconsistent: {message}\n  hint: export the mesh again from Gmsh")]
    Nodes { file: String, message: String },
    #[error("{file}: the file has no hexahedra (a `gmsh-3d` mesh is made of 8-node hexahedra)\n  hint: put the volume in a physical group (`Physical Volume(\"body\") = {{1}};`) and mesh it with hexahedra (a transfinite or extruded volume with `Recombine`), or save every element with `Mesh.SaveAll = 1;`")]
    NoHexes { file: String },
    #[error("{file}: hexahedron {element} is {what}\n  hint: export the mesh again from Gmsh, or fix the element's node order")]
    BadHex { file: String, element: u64, what: String },
}

/// What Gmsh element type `code` is, and how to avoid it.
fn unsupported(code: u8) -> (&'static str, &'static str) {
    match code {
        2 => (
            "3-node triangle",
            "recombine the triangles into quadrilaterals: add `Mesh.RecombineAll = 1;` and `Mesh.SubdivisionAlgorithm = 1;` (every element a quadrilateral) to the .geo, or `Recombine Surface{…};`",
        ),
        8 | 9 | 10 | 16 | 26..=28 => (
            "second-order element",
            "use linear elements: `Mesh.ElementOrder = 1;` (or `gmsh -order 1`)",
        ),
        4..=7 | 11..=14 | 17..=19 => (
            "3D element",
            "a `gmsh` mesh is 2D: mesh a plane surface with `gmsh -2`, or make the body 3D with `kind = \"gmsh-3d\"` (8-node hexahedra)",
        ),
        _ => (
            "element",
            "use linear quadrilaterals (Gmsh type 3): `Mesh.ElementOrder = 1; Mesh.RecombineAll = 1;`",
        ),
    }
}

/// `$MeshFormat` version, file type and data size, checked before `mshio` sees the file
/// (it supports 4.1 with 8-byte sizes only).
/// The MSH 4.1 file in `bytes` parsed (its header checked first); `file` names it in errors.
fn parse(file: &str, bytes: &[u8]) -> Result<MshFile<u64, i32, f64>, GmshError> {
    check_header(file, bytes)?;
    mshio::parse_msh_bytes(bytes).map_err(|e| GmshError::Parse {
        file: file.into(),
        message: e.to_string().lines().take(6).collect::<Vec<_>>().join(" / "),
    })
}

fn check_header(file: &str, bytes: &[u8]) -> Result<(), GmshError> {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(256)]);
    let mut lines = head.lines().map(str::trim).skip_while(|l| l.is_empty());
    if lines.next() != Some("$MeshFormat") {
        return Err(GmshError::Parse {
            file: file.into(),
            message: "it does not start with `$MeshFormat`".into(),
        });
    }
    let fmt: Vec<&str> = lines.next().unwrap_or("").split_whitespace().collect();
    let version = fmt.first().copied().unwrap_or("(none)").to_string();
    if version != "4.1" || fmt.len() < 3 || !matches!(fmt[1], "0" | "1") || fmt[2] != "8" {
        return Err(GmshError::Version {
            file: file.into(),
            version: fmt.join(" "),
        });
    }
    Ok(())
}

/// Physical group names of `$PhysicalNames` (ASCII in both encodings), by `(dim, tag)`.
fn physical_names(bytes: &[u8]) -> HashMap<(i32, i32), String> {
    let mut names = HashMap::new();
    let key = b"$PhysicalNames";
    let Some(start) = bytes.windows(key.len()).position(|w| w == key) else {
        return names;
    };
    let rest = &bytes[start + key.len()..];
    let end = rest
        .windows(b"$EndPhysicalNames".len())
        .position(|w| w == b"$EndPhysicalNames")
        .unwrap_or(rest.len());
    let text = String::from_utf8_lossy(&rest[..end]);
    for line in text.lines().skip_while(|l| l.trim().is_empty()).skip(1) {
        let mut it = line.trim().splitn(3, char::is_whitespace);
        let (Some(dim), Some(tag), Some(name)) = (it.next(), it.next(), it.next()) else {
            continue;
        };
        if let (Ok(dim), Ok(tag)) = (dim.parse(), tag.parse()) {
            names.insert((dim, tag), name.trim().trim_matches('"').to_string());
        }
    }
    names
}

/// Physical group tags of every entity, by `(dim, entity tag)`.
fn entity_groups(msh: &MshFile<u64, i32, f64>) -> HashMap<(i32, i32), Vec<i32>> {
    let mut map = HashMap::new();
    if let Some(e) = &msh.data.entities {
        for p in &e.points {
            map.insert((0, p.tag), p.physical_tags.clone());
        }
        for c in &e.curves {
            map.insert((1, c.tag), c.physical_tags.clone());
        }
        for s in &e.surfaces {
            map.insert((2, s.tag), s.physical_tags.clone());
        }
    }
    map
}

/// Node coordinates by tag.
fn node_table(file: &str, msh: &MshFile<u64, i32, f64>) -> Result<HashMap<u64, [f64; 3]>, GmshError> {
    let mut table = HashMap::new();
    let Some(nodes) = &msh.data.nodes else {
        return Ok(table);
    };
    let bad = |message: String| GmshError::Nodes {
        file: file.into(),
        message,
    };
    let total: usize = nodes.node_blocks.iter().map(|b| b.nodes.len()).sum();
    if total as u64 != nodes.num_nodes {
        return Err(bad(format!(
            "the header counts {} nodes, the blocks hold {total}",
            nodes.num_nodes
        )));
    }
    let mut next = nodes.min_node_tag;
    for b in &nodes.node_blocks {
        match &b.node_tags {
            Some(tags) => {
                for (&tag, &i) in tags {
                    let n = b
                        .nodes
                        .get(i)
                        .ok_or_else(|| bad(format!("node {tag} out of its block")))?;
                    table.insert(tag, [n.x, n.y, n.z]);
                }
            }
            None => {
                for n in &b.nodes {
                    table.insert(next, [n.x, n.y, n.z]);
                    next += 1;
                }
            }
        }
    }
    Ok(table)
}

fn element_name(t: ElementType) -> u8 {
    t as u8
}

/// Elements of the file sorted by use: quadrilaterals (tag, node tags, entity) and the
/// node tags of lines and points per `(dim, entity)`.
struct Sorted {
    quads: Vec<(u64, [u64; 4], i32)>,
    lines: HashMap<i32, Vec<[u64; 2]>>,
    points: HashMap<i32, Vec<u64>>,
}

fn sort_elements(file: &str, msh: &MshFile<u64, i32, f64>) -> Result<Sorted, GmshError> {
    let mut s = Sorted {
        quads: Vec::new(),
        lines: HashMap::new(),
        points: HashMap::new(),
    };
    let Some(elements) = &msh.data.elements else {
        return Ok(s);
    };
    for b in &elements.element_blocks {
        let bad_nodes = |tag: u64| GmshError::Parse {
            file: file.into(),
            message: format!("element {tag} has the wrong number of nodes for its type"),
        };
        match b.element_type {
            ElementType::Qua4 => {
                for e in &b.elements {
                    let n: [u64; 4] = e.nodes.as_slice().try_into().map_err(|_| bad_nodes(e.element_tag))?;
                    s.quads.push((e.element_tag, n, b.entity_tag));
                }
            }
            ElementType::Lin2 => {
                for e in &b.elements {
                    let n: [u64; 2] = e.nodes.as_slice().try_into().map_err(|_| bad_nodes(e.element_tag))?;
                    s.lines.entry(b.entity_tag).or_default().push(n);
                }
            }
            ElementType::Pnt => {
                for e in &b.elements {
                    s.points.entry(b.entity_tag).or_default().extend(&e.nodes);
                }
            }
            other => {
                let code = element_name(other);
                let (kind, hint) = unsupported(code);
                let dim = ["point", "curve", "surface", "volume"];
                return Err(GmshError::UnsupportedElement {
                    file: file.into(),
                    kind: kind.into(),
                    code,
                    count: b.elements.len(),
                    entity: format!(
                        "{} {}",
                        dim.get(b.entity_dim as usize).copied().unwrap_or("entity"),
                        b.entity_tag
                    ),
                    hint: hint.into(),
                });
            }
        }
    }
    Ok(s)
}

/// Twice the signed area and the smallest corner cross product of a quadrilateral.
fn quad_shape(x: &[[f64; 2]; 4]) -> (f64, f64) {
    let mut area2 = 0.0;
    let mut min_cross = f64::INFINITY;
    for i in 0..4 {
        let (p, q, r) = (x[(i + 3) % 4], x[i], x[(i + 1) % 4]);
        area2 += q[0] * r[1] - r[0] * q[1];
        let cross = (q[0] - p[0]) * (r[1] - q[1]) - (q[1] - p[1]) * (r[0] - q[0]);
        min_cross = min_cross.min(cross);
    }
    (area2, min_cross)
}

/// Read a Gmsh MSH 4.1 mesh (ASCII or binary) from its bytes; `file` names it in errors.
pub fn read_gmsh(file: &str, bytes: &[u8]) -> Result<GmshMesh, GmshError> {
    let msh = parse(file, bytes)?;
    let names = physical_names(bytes);
    let groups = entity_groups(&msh);
    let coords = node_table(file, &msh)?;
    let sorted = sort_elements(file, &msh)?;
    if sorted.quads.is_empty() {
        return Err(GmshError::NoQuads { file: file.into() });
    }
    let (nodes, index) = used_nodes(file, &sorted, &coords)?;
    let (quads, reoriented) = checked_quads(file, &sorted, &index, &nodes)?;
    let groups = Groups {
        file,
        names: &names,
        groups: &groups,
        index: &index,
    };
    let (mut node_sets, faces, interior_curves) = groups.sets_and_faces(&sorted, &boundary_edges(&quads))?;
    node_sets.insert("all".into(), (0..nodes.len()).collect());
    Ok(GmshMesh {
        nodes,
        quads,
        node_sets,
        faces,
        reoriented,
        interior_curves,
    })
}

/// The node index of each node tag a quadrilateral uses.
pub(super) type NodeIndex = HashMap<u64, usize>;

/// The nodes the quadrilaterals use, in tag order, checked to lie in the plane z = 0, with
/// the index of each tag.
fn used_nodes(
    file: &str,
    sorted: &Sorted,
    coords: &HashMap<u64, [f64; 3]>,
) -> Result<(Vec<[f64; 2]>, NodeIndex), GmshError> {
    let mut used: Vec<u64> = sorted.quads.iter().flat_map(|q| q.1).collect();
    used.sort_unstable();
    used.dedup();
    let mut index = HashMap::with_capacity(used.len());
    let mut nodes = Vec::with_capacity(used.len());
    for &tag in &used {
        let Some(&[x, y, z]) = coords.get(&tag) else {
            let element = sorted.quads.iter().find(|q| q.1.contains(&tag)).map_or(0, |q| q.0);
            return Err(GmshError::MissingNode {
                file: file.into(),
                element,
                node: tag,
            });
        };
        if z.abs() > 1e-12 * (1.0 + x.abs().max(y.abs())) || !(x.is_finite() && y.is_finite()) {
            return Err(GmshError::NotPlanar {
                file: file.into(),
                node: tag,
                z,
            });
        }
        index.insert(tag, nodes.len());
        nodes.push([x, y]);
    }
    Ok((nodes, index))
}

/// The quadrilaterals as node indices, turned counter-clockwise where they were not (how many
/// were), refused when degenerate or not convex.
fn checked_quads(
    file: &str,
    sorted: &Sorted,
    index: &HashMap<u64, usize>,
    nodes: &[[f64; 2]],
) -> Result<(Vec<[usize; 4]>, usize), GmshError> {
    let mut quads = Vec::with_capacity(sorted.quads.len());
    let mut reoriented = 0;
    for (tag, q, _) in &sorted.quads {
        let mut n = q.map(|t| index[&t]);
        let (area2, _) = quad_shape(&n.map(|i| nodes[i]));
        if area2 < 0.0 {
            n = [n[0], n[3], n[2], n[1]];
            reoriented += 1;
        }
        let x = n.map(|i| nodes[i]);
        let (area2, min_cross) = quad_shape(&x);
        let size2 = (0..4)
            .map(|i| (x[i][0] - x[(i + 1) % 4][0]).powi(2) + (x[i][1] - x[(i + 1) % 4][1]).powi(2))
            .fold(0.0, f64::max);
        let what = if area2 <= 1e-12 * size2 || HashSet::<usize>::from_iter(n).len() < 4 {
            Some("degenerate (zero area or a repeated node)")
        } else if min_cross <= 0.0 {
            Some("not convex (an inner angle ≥ 180°)")
        } else {
            None
        };
        if let Some(what) = what {
            return Err(GmshError::BadQuad {
                file: file.into(),
                element: *tag,
                what: what.into(),
            });
        }
        quads.push(n);
    }
    Ok((quads, reoriented))
}

#[path = "gmsh_hex.rs"]
mod hex;
pub use hex::{read_gmsh_hex, GmshSolidMesh};

#[path = "gmsh_groups.rs"]
mod groups;
use groups::{boundary_edges, Groups};

/// Order oriented segments into chains (each segment followed by the one starting at its
/// end); open chains first from their free start, closed loops after.
fn chain(segments: Vec<[usize; 2]>) -> Vec<[usize; 2]> {
    let starts: HashMap<usize, usize> = segments.iter().enumerate().map(|(k, s)| (s[0], k)).collect();
    let ends: HashSet<usize> = segments.iter().map(|s| s[1]).collect();
    let mut done = vec![false; segments.len()];
    let mut out = Vec::with_capacity(segments.len());
    let heads: Vec<usize> = (0..segments.len())
        .filter(|&k| !ends.contains(&segments[k][0]))
        .chain(0..segments.len())
        .collect();
    for h in heads {
        let mut k = h;
        while !done[k] {
            done[k] = true;
            out.push(segments[k]);
            match starts.get(&segments[k][1]) {
                Some(&n) => k = n,
                None => break,
            }
        }
    }
    out
}

#[cfg(test)]
#[path = "gmsh_tests.rs"]
mod tests;
