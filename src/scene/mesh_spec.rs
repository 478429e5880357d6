//! The `[body.mesh]` table: mesh generators (`rectangle`, `annulus`) with their grading and
//! rotation, or a Gmsh file.

use crate::model::mesh::AxisGrading;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Mesh generators.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum MeshSpec {
    /// Structured mesh of the rectangle `origin .. origin + size`, optionally turned about a
    /// point (`rotate`).
    Rectangle {
        origin: [f64; 2],
        size: [f64; 2],
        /// Elements along x and y.
        elements: [usize; 2],
        /// Grading ratio along x and y (default 1 = uniform); what it compares is set by
        /// `bias` (by default the last element over the first).
        #[serde(default = "unit_grading")]
        grading: [f64; 2],
        /// Where each axis is refined: `"end"` (default: `grading` = last / first element),
        /// `"both"` (symmetric: `grading` = middle / end elements, > 1 refines both ends) or
        /// `"centre"` (`grading` = end / centre elements, > 1 refines the middle, or `focus`).
        #[serde(default)]
        bias: [Bias; 2],
        /// With `bias = "centre"`: the point to refine towards, in the rectangle's coordinates
        /// before `rotate` (default: its middle); a node line is placed through it.
        focus: Option<[f64; 2]>,
        /// Turn the mesh about a point (node selections by coordinates see the turned mesh).
        rotate: Option<Rotation>,
    },
    /// Structured mesh of the ring sector `radius[0] ≤ r ≤ radius[1]`,
    /// `angle_deg[0] ≤ θ ≤ angle_deg[1]` about `centre` (a belt lying on a cylinder); node
    /// sets and faces `inner`, `outer`, `start`, `end` (and `all`).
    Annulus {
        centre: [f64; 2],
        /// Inner and outer radius.
        radius: [f64; 2],
        /// Start and end angle, degrees (counter-clockwise from +x).
        angle_deg: [f64; 2],
        /// Elements around and through.
        elements: [usize; 2],
        /// Grading ratio around (from `angle_deg[0]` to `angle_deg[1]`) and through (from
        /// `radius[0]` to `radius[1]`), as for a rectangle (default 1 = uniform).
        #[serde(default = "unit_grading")]
        grading: [f64; 2],
        /// As for a rectangle, per direction (around, through).
        #[serde(default)]
        bias: [Bias; 2],
        /// With `bias = "centre"`: `[angle_deg, radius]` to refine towards.
        focus: Option<[f64; 2]>,
    },
    /// Structured hexahedral mesh of the box `origin .. origin + size`: the body is 3D
    /// (hexahedra). Node sets and faces `xmin`, `xmax`, `ymin`, `ymax`, `zmin`, `zmax` (and
    /// the set `all`). A 3D scene takes no rigid bodies, contact pairs, pressures or body
    /// loads yet.
    Box {
        origin: [f64; 3],
        size: [f64; 3],
        /// Elements along x, y and z.
        elements: [usize; 3],
        /// Grading ratio along x, y and z: the last element over the first (default 1 =
        /// uniform).
        #[serde(default = "unit_grading3")]
        grading: [f64; 3],
    },
    /// A body of revolution about the `z` axis (by default its quarter): the section rectangle
    /// `origin .. origin + size` in the `(r, z)` plane (`origin[0] = r₀ ≥ 0`), graded as a
    /// rectangle is (the last element over the first), turned from the plane `y = 0` to the
    /// plane `x = 0` (`model::revolved_mesh`): the body is 3D. A full section (`r₀ = 0`) is
    /// meshed as a butterfly (a core square and a ring around it), a hollow one as arcs.
    /// Node sets and faces `ymin`, `xmin` (the symmetry planes), `zmin`, `zmax`, `outer`,
    /// `inner` (hollow), the node set `axis` (full) and `all`.
    Revolved {
        origin: [f64; 2],
        size: [f64; 2],
        /// Elements along r and z.
        elements: [usize; 2],
        #[serde(default = "unit_grading")]
        grading: [f64; 2],
        /// Cells around the quarter of a hollow section (default 8).
        #[serde(default = "eight")]
        around: usize,
        /// The share of the radius a full section's core square takes (default 0.5).
        #[serde(default = "half")]
        core: f64,
        /// How far the section turns, degrees: 90 (default: the quarter, from the plane
        /// `y = 0` to `x = 0`), or for a hollow section 180 (half, `y ≥ 0`) or 360 (whole).
        #[serde(default = "quarter_turn")]
        turn_deg: f64,
    },
    /// Structured hexahedral mesh of a hollow hemisphere, `radius[0] ≤ |x − centre| ≤
    /// radius[1]`, its dome below the centre (`z ≤ centre_z`): the body is 3D. The dome is
    /// the lower half of an equiangular cubed sphere, `3 n²` cells per layer for
    /// `elements = [n, layers]` (`n` even); node sets and faces `outer`, `inner` and `rim`
    /// (the flat annulus at the equator), and the set `all`.
    HemisphereShell {
        centre: [f64; 3],
        /// Inner and outer radius.
        radius: [f64; 2],
        /// `[n, layers]`: `n` cells along an edge of the cube's bottom face (even, ≥ 2),
        /// `layers` hexahedra through the thickness.
        elements: [usize; 2],
    },
    /// Structured hexahedral mesh of a hollow sphere, `radius[0] ≤ |x − centre| ≤ radius[1]`,
    /// or of its octant `x, y, z ≥` the centre's (`part`): the body is 3D. The surfaces are an
    /// equiangular cubed sphere, `n²` cells per cube face and layer for `elements = [n, layers]`
    /// (`n` even; an octant takes `3 n²/4`). Node sets and faces `outer`, `inner`, for an
    /// octant the symmetry faces `xmin`, `ymin`, `zmin`, and the set `all`.
    SphereShell {
        centre: [f64; 3],
        /// Inner and outer radius.
        radius: [f64; 2],
        /// `[n, layers]`: `n` cells along an edge of the cube (even, ≥ 2), `layers`
        /// hexahedra through the thickness.
        elements: [usize; 2],
        /// `"octant"` (default: the symmetric model, faces on three symmetry planes) or
        /// `"whole"`.
        #[serde(default)]
        part: SpherePart,
    },
    /// A Gmsh MSH 4.1 file (ASCII or binary) of linear quadrilaterals: its physical groups
    /// are the body's node sets, its physical curves on the boundary its faces.
    Gmsh {
        /// Path of the `.msh` file, relative to the scene file (for a built-in scene: a
        /// file shipped with it, e.g. `half-disc.msh`).
        file: String,
    },
    /// A Gmsh MSH 4.1 file (ASCII or binary) of 8-node hexahedra: the body is 3D. Its
    /// physical groups are the body's node sets, its physical surfaces of quadrilaterals on
    /// the boundary its faces (`model::gmsh::read_gmsh_hex`).
    #[serde(rename = "gmsh-3d")]
    Gmsh3d {
        /// Path of the `.msh` file, relative to the scene file.
        file: String,
    },
}

pub(super) fn unit_grading() -> [f64; 2] {
    [1.0, 1.0]
}

pub(super) fn eight() -> usize {
    8
}

pub(super) fn half() -> f64 {
    0.5
}

fn quarter_turn() -> f64 {
    90.0
}

pub(super) fn unit_grading3() -> [f64; 3] {
    [1.0, 1.0, 1.0]
}

impl MeshSpec {
    /// The elements a generated mesh will have (an upper estimate for a revolved section; 0
    /// for a mesh file).
    pub fn element_count(&self) -> f64 {
        match self {
            MeshSpec::Rectangle { elements, .. } | MeshSpec::Annulus { elements, .. } => {
                elements[0] as f64 * elements[1] as f64
            }
            MeshSpec::Box { elements, .. } => elements.iter().map(|&n| n as f64).product::<f64>(),
            MeshSpec::HemisphereShell { elements: [n, l], .. } => 3.0 * (*n as f64).powi(2) * *l as f64,
            MeshSpec::SphereShell {
                elements: [n, l], part, ..
            } => part.shell_part().surface_counts(*n).0 as f64 * *l as f64,
            MeshSpec::Revolved {
                elements: [nr, nz],
                around,
                turn_deg,
                ..
            } => {
                let quarters = (turn_deg / 90.0).round().max(1.0);
                (*nr as f64) * (*nr.max(around) as f64) * *nz as f64 * quarters
            }
            MeshSpec::Gmsh { .. } | MeshSpec::Gmsh3d { .. } => 0.0,
        }
    }

    /// Whether the mesh makes a 3D body.
    pub fn is_3d(&self) -> bool {
        matches!(
            self,
            MeshSpec::Box { .. }
                | MeshSpec::Gmsh3d { .. }
                | MeshSpec::HemisphereShell { .. }
                | MeshSpec::SphereShell { .. }
                | MeshSpec::Revolved { .. }
        )
    }
}

/// Which part of a hollow sphere a `sphere-shell` mesh models.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum SpherePart {
    /// `x, y, z ≥` the centre's: an eighth, on three symmetry planes.
    #[default]
    Octant,
    /// The whole sphere.
    Whole,
}

impl SpherePart {
    /// The model's name for the part.
    pub fn shell_part(self) -> crate::model::shell_mesh::ShellPart {
        match self {
            SpherePart::Octant => crate::model::shell_mesh::ShellPart::Octant,
            SpherePart::Whole => crate::model::shell_mesh::ShellPart::Whole,
        }
    }
}

/// Where the elements of one axis of a structured mesh are refined.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Bias {
    /// Geometric from the first to the last element: `grading` = last / first.
    #[default]
    End,
    /// Symmetric about the middle: `grading` = middle / end elements (> 1: fine at both ends).
    Both,
    /// Symmetric about the middle, or towards `focus`: `grading` = end / centre elements
    /// (> 1: fine at the centre).
    #[serde(alias = "center")]
    Centre,
}

impl Bias {
    pub fn name(self) -> &'static str {
        match self {
            Bias::End => "end",
            Bias::Both => "both",
            Bias::Centre => "centre",
        }
    }

    /// The axis grading of `ratio` with this bias; `at` is the focus along the axis
    /// (measured from the axis' start), for [`Bias::Centre`] only.
    pub fn axis(self, ratio: f64, at: Option<f64>) -> AxisGrading {
        match (self, at) {
            (Bias::End, _) => AxisGrading::End(ratio),
            (Bias::Both, _) => AxisGrading::Both(ratio),
            (Bias::Centre, None) => AxisGrading::Centre(ratio),
            (Bias::Centre, Some(at)) => AxisGrading::At { ratio, at },
        }
    }
}

/// A structured mesh's two axes as written: `elements`, `grading`, `bias`.
pub type GridAxes<'a> = (&'a [usize; 2], &'a [f64; 2], &'a [Bias; 2]);

/// A rotation of a mesh by `angle_deg` (counter-clockwise) about `about` (default: the
/// rectangle's `origin`).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Rotation {
    pub angle_deg: f64,
    pub about: Option<[f64; 2]>,
}
