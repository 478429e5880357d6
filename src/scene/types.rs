//! The scene file format (TOML). Every table rejects unknown keys; the JSON Schema in
//! `schemas/scene.schema.json` is generated from these types.

use crate::contact::transfer::TransferKind;
use crate::element::quad::ElementKind;
use crate::settings::{NewtonSettings, Stepping};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use super::mesh_spec::{Bias, GridAxes, MeshSpec, Rotation};
pub use super::rigid_spec::{
    ArcSide, ArcSpec, CylinderSpec, MotionSpec, PieceSpec, PlaneSpec, PolygonSpec, SphereSpec,
};

/// A whole scene.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub name: String,
    #[serde(default)]
    pub description: String,
    #[serde(default, rename = "body")]
    pub bodies: Vec<BodySpec>,
    /// Prescribed displacements (Dirichlet conditions).
    #[serde(default, rename = "fix")]
    pub fixes: Vec<FixSpec>,
    /// Dead nodal forces.
    #[serde(default, rename = "load")]
    pub loads: Vec<LoadSpec>,
    /// Dead body loads (gravity) per deformable body.
    #[serde(default, rename = "body_load")]
    pub body_loads: Vec<BodyLoadSpec>,
    /// Dead pressures on faces of deformable bodies.
    #[serde(default, rename = "pressure")]
    pub pressures: Vec<super::pressure::PressureSpec>,
    #[serde(default, rename = "rigid")]
    pub rigid: Vec<RigidSpec>,
    #[serde(default, rename = "contact")]
    pub contacts: Vec<ContactSpec>,
    #[serde(default)]
    pub stepping: Stepping,
    #[serde(default)]
    pub solver: NewtonSettings,
    #[serde(default, rename = "monitor")]
    pub monitors: super::monitors::Monitors,
    /// Model-size limits checked before anything is allocated.
    #[serde(default)]
    pub limits: Limits,
    /// How this plane scene is built in 3D (`build = true`: as its extrusion), so that a
    /// sweep can vary the model as one key.
    pub extrusion: Option<super::extrude::ExtrusionSpec>,
    /// How this axisymmetric scene is built in 3D (`build = true`: the quarter of its
    /// revolution about the axis).
    pub revolution: Option<super::revolve::RevolutionSpec>,
}

/// Limits on the size of a model and of a run, checked before the model is built. Raise them
/// on purpose, e.g. `--set limits.max_dofs=5000000`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Limits {
    /// Largest number of degrees of freedom (2 per node).
    pub max_dofs: usize,
    /// Largest estimated memory of the solve, in GiB (about 2.2 kB per DOF).
    pub max_memory_gib: f64,
    /// Largest number of nominal increments.
    pub max_increments: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_dofs: 2_000_000,
            max_memory_gib: 8.0,
            max_increments: 1_000_000,
        }
    }
}

/// A deformable body meshed with quadrilaterals.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: String,
    pub mesh: MeshSpec,
    pub material: MaterialSpec,
    #[serde(default = "default_element")]
    pub element: ElementKind,
    /// How the 2D mesh stands for the 3D body: `"plane-strain"` (the default; forces per unit
    /// thickness), `"plane-stress"` (a plate of `thickness`; forces for the plate) or
    /// `"axisymmetric"` (a body of revolution about the axis `x = 0`: `x = r ≥ 0`, `y = z`;
    /// every force — loads, reactions, contact, monitors — is the total over the full circle).
    #[serde(default)]
    pub model: BodyModel,
    /// Thickness of a `plane-stress` body (> 0; only with `model = "plane-stress"`).
    pub thickness: Option<f64>,
}

pub use super::body_model::BodyModel;

fn default_element() -> ElementKind {
    ElementKind::Q4EasSafe
}

/// Material model and its elastic constants.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub model: MaterialModel,
    pub young: f64,
    pub poisson: f64,
}

#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum MaterialModel {
    SaintVenantKirchhoff,
    NeoHookean,
}

/// A set of nodes of a body: a named set (`left`, `right`, `bottom`, `top`, `all`,
/// `bottom-left`, …) or the nodes on a coordinate line or in a box (reference coordinates).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum NodeSelection {
    Named(String),
    Where(WhereSpec),
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WhereSpec {
    /// Nodes with this x (within `tol`).
    pub x: Option<f64>,
    /// Nodes with this y (within `tol`).
    pub y: Option<f64>,
    /// Nodes with this z (within `tol`; 3D models only).
    pub z: Option<f64>,
    /// Nodes inside `[[x0, y0], [x1, y1]]`.
    #[serde(rename = "box")]
    pub bbox: Option<[[f64; 2]; 2]>,
    #[serde(default = "default_tol")]
    pub tol: f64,
}

fn default_tol() -> f64 {
    1e-9
}

impl std::fmt::Display for NodeSelection {
    /// The selection as a scene writes it: `"top"`, or `{ x = 0, box = [[0, 0], [1, 1]], tol = 1e-9 }`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            NodeSelection::Named(n) => write!(f, "\"{n}\""),
            NodeSelection::Where(w) => {
                let mut parts = Vec::new();
                if let Some(x) = w.x {
                    parts.push(format!("x = {x}"));
                }
                if let Some(y) = w.y {
                    parts.push(format!("y = {y}"));
                }
                if let Some(z) = w.z {
                    parts.push(format!("z = {z}"));
                }
                if let Some([[x0, y0], [x1, y1]]) = w.bbox {
                    parts.push(format!("box = [[{x0}, {y0}], [{x1}, {y1}]]"));
                }
                parts.push(format!("tol = {}", w.tol));
                write!(f, "{{ {} }}", parts.join(", "))
            }
        }
    }
}

/// A prescribed history: a final value reached linearly at `t = end`, or `(t, value)` knots.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum RampSpec {
    Final(f64),
    Path(Vec<[f64; 2]>),
}

#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Component {
    X,
    Y,
    /// 3D models only.
    Z,
}

/// Prescribed displacement of a node set: of some global components (`components`), or
/// along a direction only (`direction`: a skew support, the component across it free).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FixSpec {
    /// Name, unique among the fixes: `--set fix.NAME.value=…` (the index form
    /// `fix.0.value` works too).
    pub name: Option<String>,
    pub body: String,
    pub nodes: NodeSelection,
    /// Global components prescribed, each to `value` (give this or `direction`).
    #[serde(default)]
    pub components: Vec<Component>,
    /// A skew support: `u · d = value` with `d` this vector made unit, the displacement
    /// across it free (give this or `components`).
    pub direction: Option<[f64; 2]>,
    /// Displacement history (default 0: fixed).
    #[serde(default = "zero_ramp")]
    pub value: RampSpec,
    /// 3D: turn the nodes rigidly about an axis; each listed component then follows the turn
    /// (plus `value`): a twisted face, a rotated grip.
    pub turn: Option<TurnSpec>,
}

/// A rigid turn of a fix's nodes about the axis through `point` along `axis`
/// (right-handed), by `angle_deg(t)` degrees.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TurnSpec {
    /// A point of the axis (in the reference configuration; it stays where it is).
    pub point: [f64; 3],
    /// The axis direction (not zero; made unit).
    pub axis: [f64; 3],
    /// The angle history in degrees: a final value reached at `t = end`, or `(t, angle)`
    /// knots.
    pub angle_deg: RampSpec,
}

fn zero_ramp() -> RampSpec {
    RampSpec::Final(0.0)
}

/// A dead force on a node set.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Name, unique among the loads: `--set load.NAME.total=…`.
    pub name: Option<String>,
    pub body: String,
    pub nodes: NodeSelection,
    pub component: Component,
    /// Total force (split equally over the nodes) as a history: per unit thickness in plane
    /// strain, for the plate in plane stress, the total over the full circle (of all the
    /// nodes' rings together) on an axisymmetric body.
    pub total: RampSpec,
}

/// A dead body load on a deformable body, e.g. gravity: `force = ρ₀ g` per unit reference
/// volume, scaled by `factor` (default: linear from 0 to 1 over the run); the nodal forces are
/// `∫ N b dV` in the body's model (unit thickness, the plate's thickness, or the ring
/// `dV = 2π r dA`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodyLoadSpec {
    pub body: String,
    /// Force per unit reference volume `[bx, by]`.
    pub force: [f64; 2],
    /// History of the load factor (a final value reached linearly, or `[[t, factor], …]`).
    pub factor: Option<RampSpec>,
}

/// A rigid body: in 2D a point, or a surface made of segments and arcs; in 3D a plane or a
/// sphere (`plane`, `sphere`: exactly one, and none of the 2D keys).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RigidSpec {
    pub name: String,
    /// A rigid point (e.g. a sharp corner used as a contact slave).
    pub point: Option<[f64; 2]>,
    /// A polyline surface, listed with the rigid body on the left (outward normal on the right).
    pub polyline: Option<Vec<[f64; 2]>>,
    /// A circular arc; counter-clockwise (`from_deg < to_deg`) is the outside of a disc.
    pub arc: Option<ArcSpec>,
    /// A composite outline: line and arc pieces joined end to end, listed with the rigid
    /// body on the left of the direction of travel (a block with a rounded corner, a drum
    /// with flats, a punch with fillets).
    pub outline: Option<Vec<PieceSpec>>,
    /// A regular polygon (a faceted drum): the outline through the vertices of a regular
    /// polygon inscribed in a circle, counter-clockwise (the rigid body inside).
    pub polygon: Option<PolygonSpec>,
    /// Round every vertex where two straight pieces meet (of a `polyline`, `polygon` or
    /// `outline`) by a tangent arc of this radius: C1 smoothing of a rigid outline. Its
    /// vertices are then no longer vertices (no implied vertex pair, and none can be named
    /// as a slave). Each arc takes `radius · tan(θ/2)` off both pieces at a turn of `θ`.
    pub fillet: Option<f64>,
    /// 3D only: a rigid half-space bounded by a plane.
    pub plane: Option<PlaneSpec>,
    /// 3D only: a rigid ball.
    pub sphere: Option<SphereSpec>,
    /// 3D only: a rigid round bar (an infinite circular cylinder).
    pub cylinder: Option<CylinderSpec>,
    /// Prescribed translation histories.
    #[serde(default, rename = "move")]
    pub motion: MotionSpec,
}

/// The slave side of a contact pair.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SlaveSpec {
    /// Nodes of a deformable body (in 3D a face, or nodes on one straight edge) …
    pub body: Option<String>,
    pub nodes: Option<NodeSelection>,
    /// … or a rigid point, …
    pub rigid: Option<String>,
    /// … or, with `rigid`, a vertex (point index) of a rigid polyline: the corner of that
    /// outline as a slave point. The contact then owns the vertex: slave nodes of the face
    /// segment the corner is paired with are not paired with the outline next to it.
    pub vertex: Option<usize>,
}

/// The master side of a contact pair.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MasterSpec {
    /// A face (`bottom`, `right`, `top`, `left`; in 3D `xmin` … `zmax` or a physical
    /// surface, several joined by `+` as one surface: `"zmax+xmin"`) of a deformable body …
    pub body: Option<String>,
    pub face: Option<String>,
    /// … or a rigid surface.
    pub rigid: Option<String>,
}

/// A node-to-segment contact pair.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    pub name: String,
    pub slave: SlaveSpec,
    pub master: MasterSpec,
    pub eps_n: f64,
    #[serde(default)]
    pub eps_t: f64,
    /// 3D pairs: `μ` over time as `[t, μ]` knots, linear between them and held beyond
    /// (e.g. frictionless while a body is pressed, rough while it is twisted:
    /// `[[0, 0], [1, 0], [1.1, 0.5]]`); given instead of `mu`.
    pub mu_path: Option<Vec<[f64; 2]>>,
    #[serde(default)]
    pub mu: f64,
    #[serde(default = "default_transfer")]
    pub transfer: TransferKind,
    /// Search radius: slaves farther than this from the master surface are not paired with
    /// it (default: twice the largest element edge of the model). Free ends and convex
    /// vertices are handled by rule, not by this radius.
    pub search_radius: Option<f64>,
    /// Node-to-segment in both directions (for a pair of two deformable bodies: slave nodes
    /// on the master face, and the master face's nodes on the slave nodes' face), each pass
    /// with half the penalties: a uniform pressure is transmitted between non-matching meshes
    /// (the contact patch test), which one pass does not.
    #[serde(default)]
    pub two_pass: bool,
    /// For a rigid master: its convex vertices are also rigid slave points against the face
    /// of the slave nodes (a pair `NAME/vertices` is added), so that a polygon's corner does
    /// not poke through the face between two nodes. `false` turns it off.
    #[serde(default = "yes")]
    pub vertices: bool,
    /// Allow slave points that start penetrating a rigid master (an initial interference on
    /// purpose). By default a scene whose rigid outline starts overlapping its slaves is
    /// refused: that is almost always an outline listed the wrong way round.
    #[serde(default)]
    pub allow_initial_penetration: bool,
    /// Slave nodes that start inside the master by at most 1 % of the smaller element at the
    /// interface (meshes that overlap by round-off or by the digits they were written to) are
    /// moved onto the master, strain-free, and the run says so (`true`, the default); deeper
    /// overlaps are refused as before. `false`: every overlap beyond round-off is left as it
    /// is (refused against a rigid master unless `allow_initial_penetration`).
    #[serde(default = "yes")]
    pub adjust_overclosure: bool,
    /// Interpolation of a deformable master face: `"none"` (straight segments, the default),
    /// `"hermite"` (C1 cubic segments through the nodes, tangents from the neighbours) or
    /// `"bezier"` (C1 quadratic Bézier arcs between the segments' midpoints, the nodes as
    /// control points: it cuts the face's corners). The normal no longer jumps at nodes. For a
    /// rigid master it is the smoothing of the slave nodes' face that the outline's convex
    /// vertices press on (the implied pair `NAME/vertices`; default `"hermite"`).
    #[serde(default)]
    pub master_smoothing: Option<crate::model::Smoothing>,
    /// How the constraints are enforced: `"penalty"` (the default; forces `ε_N ⟨−ζ⟩` and the
    /// penalised stick, errors of order force/ε) or `"augmented"` (augmented Lagrangian:
    /// Uzawa updates of the multipliers at converged increments, each increment solved again
    /// until the multipliers settle; the result no longer depends on ε within `augmented_tol`).
    #[serde(default)]
    pub enforcement: EnforcementKind,
    /// Augmented Lagrangian: the largest change of the pair's multipliers (normal and
    /// tangential), relative to its largest normal force, at which the updates stop.
    #[serde(default = "default_augmented_tol")]
    pub augmented_tol: f64,
    /// Augmented Lagrangian: most multiplier updates per increment; an increment still not
    /// converged then fails (and is cut back).
    #[serde(default = "default_augmented_max")]
    pub augmented_max: usize,
}

/// Enforcement of a contact pair's constraints.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum EnforcementKind {
    /// Penalty regularisation.
    #[default]
    Penalty,
    /// Augmented Lagrangian (Uzawa updates at converged increments).
    Augmented,
}

fn default_augmented_tol() -> f64 {
    1e-3
}

fn default_augmented_max() -> usize {
    30
}

fn yes() -> bool {
    true
}

fn default_transfer() -> TransferKind {
    TransferKind::Continuous
}

/// One load–displacement pair to report: a node set of a deformable body (`body` and
/// `nodes`: mean displacement of the set, sum of its reactions or loads) or a rigid body
/// (`rigid`: its prescribed travel, the sum of the contact forces it receives).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MonitorSpec {
    /// Column and curve name; unique among the monitors.
    pub label: String,
    /// Deformable body of the node set (with `nodes`).
    pub body: Option<String>,
    /// The node set (with `body`).
    pub nodes: Option<NodeSelection>,
    /// A rigid body instead of a node set.
    pub rigid: Option<String>,
    pub component: Component,
    /// 3D, with `body` and `nodes`: a point of an axis along `component`; the monitor then
    /// reports the set's turn about that axis (radians, in (−π, π]) and the moment of its
    /// forces about it, `Σ ((x − p) × f)` at the current positions: a twisting torque.
    pub about: Option<[f64; 3]>,
    /// Multiplies displacement and force (e.g. −1 to report a downward push as positive).
    #[serde(default = "unit")]
    pub sign: f64,
    /// Multiplies the force only (default 1): from the modelled part to what is reported,
    /// e.g. `1 / L` for the force per unit length of a slice `L` long.
    #[serde(default = "unit")]
    pub force_scale: f64,
}

fn unit() -> f64 {
    1.0
}
