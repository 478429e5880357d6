//! VTK XML files for ParaView: unstructured grids (`.vtu`) and the collection (`.pvd`)
//! that makes a time series of them.
//!
//! Written by hand (the format is small): VTK XML version 1.0, `header_type="UInt64"`,
//! every array inline as `format="binary"` (base64 of an 8-byte little-endian byte count
//! followed by the little-endian values), so values — NaN included — round-trip exactly.
//! Two datasets per recorded increment:
//!
//! - **mesh** (`VTK_QUAD` cells, reference coordinates): point data `displacement`
//!   (3 components, z = 0); cell data `cauchy_stress` and `green_lagrange_strain` (3×3
//!   tensors, 9 components, plane strain: `σ33` from the material, `E33 = 0`), `von_mises`,
//!   `body` (index). Apply ParaView's *Warp By Vector* on `displacement` for the deformed shape.
//! - **contact** (one `VTK_VERTEX` cell per slave point, current positions): point data
//!   `gap`, `normal_traction` (the normal force `N` of the point), `tangential_traction`
//!   (returned, along the master's unit tangent), `trial_traction`, `state` (0 open, 1 stick,
//!   2 slip), `segment` (−1: none), `pair`, `xi`, `normal` (3 components).
//!
//! The `.pvd` lists both per time step `t` (the load level) as `part` 0 and 1.

use crate::element::fields::CentreFields;
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::ContactPointRecord;
use base64::Engine;
use std::io::{self, Write};

/// Values of one data array.
#[derive(Debug, Clone)]
pub enum Values {
    F64(Vec<f64>),
    I32(Vec<i32>),
}

/// A named data array with its number of components.
#[derive(Debug, Clone)]
pub struct Array {
    pub name: String,
    pub components: usize,
    pub values: Values,
}

impl Array {
    fn f64(name: &str, components: usize, values: Vec<f64>) -> Self {
        Array {
            name: name.into(),
            components,
            values: Values::F64(values),
        }
    }
    fn i32(name: &str, values: Vec<i32>) -> Self {
        Array {
            name: name.into(),
            components: 1,
            values: Values::I32(values),
        }
    }
}

/// One unstructured grid.
#[derive(Debug, Clone, Default)]
pub struct Piece {
    pub points: Vec<[f64; 3]>,
    /// Node lists of the cells, concatenated.
    pub connectivity: Vec<i64>,
    /// End of each cell's node list in `connectivity`.
    pub offsets: Vec<i64>,
    /// VTK cell types (1 vertex, 9 quad).
    pub types: Vec<u8>,
    pub point_data: Vec<Array>,
    pub cell_data: Vec<Array>,
}

const VTK_VERTEX: u8 = 1;
const VTK_QUAD: u8 = 9;
const VTK_HEXAHEDRON: u8 = 12;

/// The mesh dataset of a 3D model: reference nodes, hexahedra (Gmsh/VTK node order, which
/// is `VTK_HEXAHEDRON`'s), displacement, the element fields at each hexahedron's centre when
/// known (as in 2D: `cauchy_stress` and `green_lagrange_strain` as full 3×3 tensors,
/// `von_mises`) and the body of each cell.
pub fn solid_piece(
    nodes: &[[f64; 3]],
    hexes: &[[usize; 8]],
    body: &[usize],
    u: &[f64],
    fields: Option<&[Option<CentreFields>]>,
) -> Piece {
    let disp = (0..3 * nodes.len())
        .map(|d| u.get(d).copied().unwrap_or(f64::NAN))
        .collect();
    let mut p = Piece {
        points: nodes.to_vec(),
        connectivity: hexes.iter().flatten().map(|&n| n as i64).collect(),
        offsets: (1..=hexes.len()).map(|k| 8 * k as i64).collect(),
        types: vec![VTK_HEXAHEDRON; hexes.len()],
        point_data: vec![Array::f64("displacement", 3, disp)],
        cell_data: Vec::new(),
    };
    if let Some(fields) = fields {
        push_fields(&mut p, fields);
    }
    p.cell_data
        .push(Array::i32("body", body.iter().map(|&b| b as i32).collect()));
    p
}

/// The element fields as cell data (`None` per element: written as NaN).
fn push_fields(p: &mut Piece, fields: &[Option<CentreFields>]) {
    let tensor = |get: fn(&CentreFields) -> [[f64; 3]; 3]| -> Vec<f64> {
        fields
            .iter()
            .flat_map(|f| {
                f.as_ref()
                    .map_or([f64::NAN; 9], |f| get(f).concat().try_into().unwrap_or([f64::NAN; 9]))
            })
            .collect()
    };
    p.cell_data.push(Array::f64("cauchy_stress", 9, tensor(|f| f.cauchy)));
    p.cell_data
        .push(Array::f64("green_lagrange_strain", 9, tensor(|f| f.green_lagrange)));
    p.cell_data.push(Array::f64(
        "von_mises",
        1,
        fields
            .iter()
            .map(|f| f.as_ref().map_or(f64::NAN, |f| f.von_mises))
            .collect(),
    ));
}

/// The mesh dataset: reference nodes, quads, displacement and (when known) element fields
/// (`None` per element: its fields could not be evaluated, written as NaN).
pub fn mesh_piece(
    nodes: &[[f64; 2]],
    quads: &[[usize; 4]],
    body: &[usize],
    u: &[f64],
    fields: Option<&[Option<CentreFields>]>,
) -> Piece {
    let mut p = Piece {
        points: nodes.iter().map(|x| [x[0], x[1], 0.0]).collect(),
        connectivity: quads.iter().flatten().map(|&n| n as i64).collect(),
        offsets: (1..=quads.len()).map(|k| 4 * k as i64).collect(),
        types: vec![VTK_QUAD; quads.len()],
        ..Piece::default()
    };
    let disp = (0..nodes.len())
        .flat_map(|n| {
            [
                u.get(2 * n).copied().unwrap_or(f64::NAN),
                u.get(2 * n + 1).copied().unwrap_or(f64::NAN),
                0.0,
            ]
        })
        .collect();
    p.point_data.push(Array::f64("displacement", 3, disp));
    if let Some(fields) = fields {
        push_fields(&mut p, fields);
    }
    p.cell_data
        .push(Array::i32("body", body.iter().map(|&b| b as i32).collect()));
    p
}

/// The contact dataset: one vertex per slave point at its current position.
pub fn contact_piece(points: &[ContactPointRecord]) -> Piece {
    let f = |name: &str, get: fn(&ContactPointRecord) -> f64| Array::f64(name, 1, points.iter().map(get).collect());
    vertices(
        points.iter().map(|p| [p.position[0], p.position[1], 0.0]).collect(),
        vec![
            f("gap", |p| p.gap),
            f("normal_traction", |p| p.normal_force),
            f("tangential_traction", |p| p.traction),
            f("trial_traction", |p| p.trial_traction),
            f("xi", |p| p.xi),
            Array::i32("state", points.iter().map(|p| p.state.code() as i32).collect()),
            Array::i32(
                "segment",
                points.iter().map(|p| p.segment.map_or(-1, |s| s as i32)).collect(),
            ),
            Array::i32("pair", points.iter().map(|p| p.pair as i32).collect()),
            Array::f64(
                "normal",
                3,
                points.iter().flat_map(|p| [p.normal[0], p.normal[1], 0.0]).collect(),
            ),
        ],
    )
}

/// A dataset of one vertex per point, with its point data.
fn vertices(points: Vec<[f64; 3]>, point_data: Vec<Array>) -> Piece {
    let n = points.len();
    Piece {
        points,
        connectivity: (0..n as i64).collect(),
        offsets: (1..=n as i64).collect(),
        types: vec![VTK_VERTEX; n],
        point_data,
        cell_data: Vec::new(),
    }
}

/// The 3D contact points as vertices at the slave positions, with their gap, normal force
/// `N` (`normal_traction`, as in 2D), the contact force and its tangential part (3
/// components), convective coordinates `(ξ¹, ξ²)`, state code (0 open, 1 stick, 2 slip),
/// facet (−1 when none is within reach), crossing flag, pair and the master's normal.
pub fn surface_contact_piece(points: &[SurfacePointRecord]) -> Piece {
    let f = |name: &str, get: fn(&SurfacePointRecord) -> f64| Array::f64(name, 1, points.iter().map(get).collect());
    let v3 = |name: &str, get: fn(&SurfacePointRecord) -> [f64; 3]| {
        Array::f64(name, 3, points.iter().flat_map(get).collect())
    };
    let i = |name: &str, get: fn(&SurfacePointRecord) -> i32| Array::i32(name, points.iter().map(get).collect());
    vertices(
        points.iter().map(|p| p.position).collect(),
        vec![
            f("gap", |p| p.gap),
            f("normal_traction", |p| p.normal_force),
            v3("force", |p| p.force),
            v3("tangential_force", |p| {
                let fn_: f64 = (0..3).map(|c| p.force[c] * p.normal[c]).sum();
                std::array::from_fn(|c| {
                    if fn_.is_finite() {
                        p.force[c] - fn_ * p.normal[c]
                    } else {
                        0.0
                    }
                })
            }),
            Array::f64("xi", 2, points.iter().flat_map(|p| p.xi).collect()),
            i("state", |p| p.state.code() as i32),
            i("facet", |p| p.facet.map_or(-1, |s| s as i32)),
            i("crossing", |p| i32::from(p.crossing)),
            i("pair", |p| p.pair as i32),
            v3("normal", |p| p.normal),
        ],
    )
}

/// Base64 of an 8-byte byte count followed by the bytes (VTK's inline binary encoding).
fn encode(bytes: &[u8]) -> String {
    let mut raw = Vec::with_capacity(8 + bytes.len());
    raw.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
    raw.extend_from_slice(bytes);
    base64::engine::general_purpose::STANDARD.encode(raw)
}

fn write_array(w: &mut dyn Write, name: Option<&str>, components: usize, values: &Values) -> io::Result<()> {
    let (ty, bytes): (&str, Vec<u8>) = match values {
        Values::F64(v) => ("Float64", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
        Values::I32(v) => ("Int32", v.iter().flat_map(|x| x.to_le_bytes()).collect()),
    };
    let name = name.map_or(String::new(), |n| format!(" Name=\"{n}\""));
    // scalars without NumberOfComponents: readers then give them one dimension
    let comps = if components == 1 {
        String::new()
    } else {
        format!(" NumberOfComponents=\"{components}\"")
    };
    writeln!(
        w,
        "<DataArray type=\"{ty}\"{name}{comps} format=\"binary\">\n{}\n</DataArray>",
        encode(&bytes)
    )
}

fn write_raw(w: &mut dyn Write, ty: &str, name: &str, bytes: Vec<u8>) -> io::Result<()> {
    writeln!(
        w,
        "<DataArray type=\"{ty}\" Name=\"{name}\" format=\"binary\">\n{}\n</DataArray>",
        encode(&bytes)
    )
}

/// Write one `.vtu` file.
pub fn write_vtu(w: &mut dyn Write, p: &Piece) -> io::Result<()> {
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    )?;
    writeln!(w, "<UnstructuredGrid>")?;
    writeln!(
        w,
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        p.points.len(),
        p.types.len()
    )?;
    for (tag, arrays) in [("PointData", &p.point_data), ("CellData", &p.cell_data)] {
        writeln!(w, "<{tag}>")?;
        for a in arrays {
            write_array(w, Some(&a.name), a.components, &a.values)?;
        }
        writeln!(w, "</{tag}>")?;
    }
    writeln!(w, "<Points>")?;
    write_array(w, None, 3, &Values::F64(p.points.iter().flatten().copied().collect()))?;
    writeln!(w, "</Points>")?;
    writeln!(w, "<Cells>")?;
    write_raw(
        w,
        "Int64",
        "connectivity",
        p.connectivity.iter().flat_map(|x| x.to_le_bytes()).collect(),
    )?;
    write_raw(
        w,
        "Int64",
        "offsets",
        p.offsets.iter().flat_map(|x| x.to_le_bytes()).collect(),
    )?;
    write_raw(w, "UInt8", "types", p.types.clone())?;
    writeln!(w, "</Cells>")?;
    writeln!(w, "</Piece>\n</UnstructuredGrid>\n</VTKFile>")
}

/// One file of a `.pvd` collection.
#[derive(Debug, Clone)]
pub struct PvdEntry {
    pub t: f64,
    /// 0 the mesh, 1 the contact points.
    pub part: usize,
    /// Path relative to the `.pvd` file (`/`-separated).
    pub file: String,
}

/// Write a `.pvd` collection.
pub fn write_pvd(w: &mut dyn Write, entries: &[PvdEntry]) -> io::Result<()> {
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">"
    )?;
    writeln!(w, "<Collection>")?;
    for e in entries {
        let file = e.file.replace('&', "&amp;").replace('"', "&quot;").replace('<', "&lt;");
        writeln!(
            w,
            "<DataSet timestep=\"{:?}\" group=\"\" part=\"{}\" file=\"{file}\"/>",
            e.t, e.part
        )?;
    }
    writeln!(w, "</Collection>\n</VTKFile>")
}
