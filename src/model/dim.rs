//! The spatial dimension of a model, chosen once per model at compile time: [`Plane`] (2D:
//! quadrilaterals in plane strain, plane stress or the axisymmetric setting) or [`Solid`] (3D:
//! hexahedra). Nodes, DOFs (`dof = D · node + component`), elements, faces and the element
//! kernels' local arrays are the dimension's associated types, so that the model, the
//! assembly and the Newton/stepping layers are written once, generic over `S: Dim`, and
//! monomorphised: the 2D code runs exactly the fixed-size arrays it ran before.
//!
//! The contact layer sees a model through two views: [`Dim::plane`] (node-to-segment pairs;
//! the model itself in 2D, an empty 2D model in 3D) and [`Dim::solid`] (node-to-surface
//! pairs, `Model::surface_contacts`; the model in 3D, `None` in 2D). Rigid outlines and skew
//! supports are 2D only.

use super::{Body, Model};
use crate::element::hex8::{hex8_hourglass_holds, hex8_residual_tangent_with, Hex8Geometry, Hex8Kind, EAS_COUNT};
use crate::element::quad::{
    hourglass_holds, quad_residual_tangent_with, ElementError, ElementKind, Kinematics, QuadGeometry,
};
use std::fmt::Debug;
use std::sync::LazyLock;

/// A fixed-size array that can be made filled with one value (the element kernels' local
/// buffers and scatter maps).
pub trait Filled<T>: Copy + Send + Sync + AsRef<[T]> + AsMut<[T]> + Debug {
    fn filled(v: T) -> Self;
}

impl<T: Copy + Send + Sync + Debug, const N: usize> Filled<T> for [T; N] {
    fn filled(v: T) -> Self {
        [v; N]
    }
}

/// The spatial dimension of a model (see the module documentation).
pub trait Dim: Copy + Clone + Debug + Default + PartialEq + Eq + Send + Sync + 'static {
    /// Coordinates per node, displacement components per node.
    const D: usize;
    /// Nodes per element (4: quadrilateral, 8: hexahedron).
    const NODES: usize;
    /// Enhanced-strain parameters per element (flat storage: `alphas[ALPHAS · e ..]`).
    const ALPHAS: usize;
    /// `"2d"` or `"3d"`.
    const NAME: &'static str;
    /// `[f64; D]`.
    type Point: Filled<f64> + PartialEq;
    /// The nodes of an element, in the kernel's order.
    type Cell: Filled<usize> + PartialEq;
    /// A boundary face: a segment `[a, b]` in 2D, a quadrilateral in 3D.
    type Face: Filled<usize> + PartialEq;
    /// The element formulation of a body.
    type Kind: Copy + Debug + PartialEq + Send + Sync;
    /// How the mesh stands for the body (plane strain, …; nothing in 3D).
    type Kinematics: Copy + Debug + PartialEq + Default + Send + Sync;
    /// The enhanced parameters of one element.
    type Alpha: Filled<f64>;
    /// Element residual (`D · NODES`) and tangent (its square, row-major), and the tangent's
    /// value slots in the global matrix.
    type Re: Filled<f64>;
    type Ke: Filled<f64>;
    type Slots: Filled<u32>;
    /// The reference geometry of one element, computed once.
    type Geometry: Debug + Clone + Send + Sync;

    /// The enhanced parameters per element of a flat vector (`ALPHAS` each).
    fn alphas_mut(flat: &mut [f64]) -> &mut [Self::Alpha];
    fn alphas(flat: &[f64]) -> &[Self::Alpha];
    /// The reference geometry of an element with nodes `x` of body `body`.
    fn geometry(body: &Body<Self>, x: &[Self::Point]) -> Result<Self::Geometry, ElementError>;
    /// Residual `re`, tangent `ke` (when asked) and stored energy of one element on the
    /// displacements `u` of its nodes `nodes`; `alpha` is the local iteration's start and end.
    fn kernel(
        body: &Body<Self>,
        geo: &Self::Geometry,
        nodes: &Self::Cell,
        u: &[f64],
        alpha: &mut Self::Alpha,
        re: &mut Self::Re,
        ke: Option<&mut Self::Ke>,
    ) -> Result<f64, ElementError>;
    /// Whether the body's elements hold their hourglass modes from increment to increment.
    fn holds_hourglass(kind: &Self::Kind) -> bool;
    /// Set the holds of an element for the next increment from the converged `u`.
    fn hold_hourglass(body: &Body<Self>, geo: &mut Self::Geometry, nodes: &Self::Cell, u: &[f64]);
    /// The measure of the element's forces beyond the continuum's own (1 in plane strain and
    /// 3D, the thickness in plane stress, `2π R` in the axisymmetric setting), for the
    /// round-off floor of the internal forces.
    fn force_measure(kinematics: &Self::Kinematics, x: &[Self::Point]) -> f64;
    /// The longest element edge.
    fn longest_edge(x: &[Self::Point]) -> f64;
    /// The model as the dimension-erased reference observers take.
    fn model_ref(m: &Model<Self>) -> ModelRef<'_>;
    /// The 2D view of the model the contact layer works on: the model itself in 2D, an empty
    /// model in 3D (no contact in 3D yet).
    fn plane(m: &Model<Self>) -> &Model<Plane>;
    /// The 3D view of the model the surface-contact layer works on (`contact3d`): the model
    /// itself in 3D, `None` in 2D.
    fn solid(m: &Model<Self>) -> Option<&Model<Solid>>;
}

/// Two dimensions: quadrilaterals (`element::quad`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Plane;

/// Three dimensions: hexahedra (`element::hex8`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Solid;

/// The element formulation of a 3D body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SolidKind {
    pub kind: Hex8Kind,
    /// Hold the enhanced shear modes against hourglassing in compression
    /// ([`hex8_hourglass_holds`]); the counterpart of [`ElementKind::Q4EasSafe`].
    pub hold: bool,
}

impl SolidKind {
    /// The 3D formulation of a scene's element key: `q4` → plain trilinear, `q4-eas` and
    /// `q4-eas-stab` → EAS-21, `q4-eas-safe` (the default) → EAS-21 with the holds,
    /// `solid-shell` → the solid-shell (ANS and five enhanced modes).
    pub fn from_element(kind: ElementKind) -> Self {
        match kind {
            ElementKind::Q4 => SolidKind {
                kind: Hex8Kind::Hex8,
                hold: false,
            },
            ElementKind::Q4Eas | ElementKind::Q4EasStab => SolidKind {
                kind: Hex8Kind::Hex8Eas,
                hold: false,
            },
            ElementKind::Q4EasSafe => SolidKind {
                kind: Hex8Kind::Hex8Eas,
                hold: true,
            },
            ElementKind::SolidShell => SolidKind {
                kind: Hex8Kind::SolidShell,
                hold: false,
            },
        }
    }

    /// As a recording names it: `hex8`, `hex8-eas` or `hex8-eas-safe`.
    pub fn name(self) -> &'static str {
        match (self.kind, self.hold) {
            (Hex8Kind::Hex8, _) => "hex8",
            (Hex8Kind::Hex8Eas, false) => "hex8-eas",
            (Hex8Kind::Hex8Eas, true) => "hex8-eas-safe",
            (Hex8Kind::SolidShell, _) => "solid-shell",
        }
    }
}

/// A model of either dimension, for the layers that take it at run time (observers).
#[derive(Debug, Clone, Copy)]
pub enum ModelRef<'a> {
    Plane(&'a Model<Plane>),
    Solid(&'a Model<Solid>),
}

impl<'a> ModelRef<'a> {
    /// The 2D view: the model in 2D, an empty model in 3D ([`Dim::plane`]).
    pub fn plane(self) -> &'a Model<Plane> {
        match self {
            ModelRef::Plane(m) => m,
            ModelRef::Solid(m) => Solid::plane(m),
        }
    }

    pub fn dim(self) -> usize {
        match self {
            ModelRef::Plane(_) => 2,
            ModelRef::Solid(_) => 3,
        }
    }

    pub fn name(self) -> &'a str {
        match self {
            ModelRef::Plane(m) => &m.name,
            ModelRef::Solid(m) => &m.name,
        }
    }

    pub fn monitors(self) -> &'a [super::Monitor] {
        match self {
            ModelRef::Plane(m) => &m.monitors,
            ModelRef::Solid(m) => &m.monitors,
        }
    }

    pub fn node_count(self) -> usize {
        match self {
            ModelRef::Plane(m) => m.nodes.len(),
            ModelRef::Solid(m) => m.nodes.len(),
        }
    }
}

/// An owned model of either dimension (a model handed to another thread).
#[derive(Debug, Clone)]
pub enum AnyModel {
    Plane(Model<Plane>),
    Solid(Model<Solid>),
}

impl AnyModel {
    pub fn view(&self) -> ModelRef<'_> {
        match self {
            AnyModel::Plane(m) => ModelRef::Plane(m),
            AnyModel::Solid(m) => ModelRef::Solid(m),
        }
    }
}

impl ModelRef<'_> {
    pub fn to_owned(self) -> AnyModel {
        match self {
            ModelRef::Plane(m) => AnyModel::Plane(m.clone()),
            ModelRef::Solid(m) => AnyModel::Solid(m.clone()),
        }
    }
}

static EMPTY_PLANE: LazyLock<Model<Plane>> = LazyLock::new(Model::default);

fn pair_distance<const N: usize>(p: &[f64; N], q: &[f64; N]) -> f64 {
    p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt()
}

impl Dim for Plane {
    const D: usize = 2;
    const NODES: usize = 4;
    const ALPHAS: usize = 4;
    const NAME: &'static str = "2d";
    type Point = [f64; 2];
    type Cell = [usize; 4];
    type Face = [usize; 2];
    type Kind = ElementKind;
    type Kinematics = Kinematics;
    type Alpha = [f64; 4];
    type Re = [f64; 8];
    type Ke = [f64; 64];
    type Slots = [u32; 64];
    type Geometry = QuadGeometry;

    fn alphas_mut(flat: &mut [f64]) -> &mut [[f64; 4]] {
        flat.as_chunks_mut::<4>().0
    }

    fn alphas(flat: &[f64]) -> &[[f64; 4]] {
        flat.as_chunks::<4>().0
    }

    fn geometry(body: &Body<Plane>, x: &[[f64; 2]]) -> Result<QuadGeometry, ElementError> {
        let x: [[f64; 2]; 4] = std::array::from_fn(|i| x[i]);
        QuadGeometry::with_kinematics(body.kind, &body.material, body.kinematics, &x)
    }

    #[inline]
    fn kernel(
        body: &Body<Plane>,
        geo: &QuadGeometry,
        nodes: &[usize; 4],
        u: &[f64],
        alpha: &mut [f64; 4],
        re: &mut [f64; 8],
        ke: Option<&mut [f64; 64]>,
    ) -> Result<f64, ElementError> {
        let ue: [[f64; 2]; 4] = nodes.map(|n| [u[2 * n], u[2 * n + 1]]);
        quad_residual_tangent_with(body.kind, &body.material, geo, &ue, alpha, re, ke)
    }

    fn holds_hourglass(kind: &ElementKind) -> bool {
        *kind == ElementKind::Q4EasSafe
    }

    fn hold_hourglass(body: &Body<Plane>, geo: &mut QuadGeometry, nodes: &[usize; 4], u: &[f64]) {
        let ue: [[f64; 2]; 4] = nodes.map(|n| [u[2 * n], u[2 * n + 1]]);
        let holds = hourglass_holds(geo, &body.material, &ue);
        geo.set_alpha_penalty(holds, &body.material);
    }

    fn force_measure(kinematics: &Kinematics, x: &[[f64; 2]]) -> f64 {
        match kinematics {
            Kinematics::PlaneStrain => 1.0,
            Kinematics::PlaneStress { thickness } => *thickness,
            Kinematics::Axisymmetric => 2.0 * std::f64::consts::PI * x.iter().map(|p| p[0]).fold(0.0, f64::max),
        }
    }

    fn longest_edge(x: &[[f64; 2]]) -> f64 {
        let mut h = 0.0f64;
        for i in 0..4 {
            let (a, b) = (x[i], x[(i + 1) % 4]);
            h = h.max((a[0] - b[0]).hypot(a[1] - b[1]));
        }
        h
    }

    fn model_ref(m: &Model<Plane>) -> ModelRef<'_> {
        ModelRef::Plane(m)
    }

    fn plane(m: &Model<Plane>) -> &Model<Plane> {
        m
    }

    fn solid(_: &Model<Plane>) -> Option<&Model<Solid>> {
        None
    }
}

/// The twelve edges of a hexahedron (Gmsh/VTK node order).
pub const HEX8_EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

impl Dim for Solid {
    const D: usize = 3;
    const NODES: usize = 8;
    const ALPHAS: usize = EAS_COUNT;
    const NAME: &'static str = "3d";
    type Point = [f64; 3];
    type Cell = [usize; 8];
    type Face = [usize; 4];
    type Kind = SolidKind;
    type Kinematics = ();
    type Alpha = [f64; EAS_COUNT];
    type Re = [f64; 24];
    type Ke = [f64; 576];
    type Slots = [u32; 576];
    type Geometry = Hex8Geometry;

    fn alphas_mut(flat: &mut [f64]) -> &mut [[f64; EAS_COUNT]] {
        flat.as_chunks_mut::<EAS_COUNT>().0
    }

    fn alphas(flat: &[f64]) -> &[[f64; EAS_COUNT]] {
        flat.as_chunks::<EAS_COUNT>().0
    }

    fn geometry(body: &Body<Solid>, x: &[[f64; 3]]) -> Result<Hex8Geometry, ElementError> {
        let x: [[f64; 3]; 8] = std::array::from_fn(|i| x[i]);
        Ok(Hex8Geometry::new(body.kind.kind, &x)?)
    }

    #[inline]
    fn kernel(
        body: &Body<Solid>,
        geo: &Hex8Geometry,
        nodes: &[usize; 8],
        u: &[f64],
        alpha: &mut [f64; EAS_COUNT],
        re: &mut [f64; 24],
        ke: Option<&mut [f64; 576]>,
    ) -> Result<f64, ElementError> {
        let ue: [[f64; 3]; 8] = nodes.map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
        Ok(hex8_residual_tangent_with(
            body.kind.kind,
            &body.material,
            geo,
            &ue,
            alpha,
            re,
            ke,
        )?)
    }

    fn holds_hourglass(kind: &SolidKind) -> bool {
        kind.hold && kind.kind == Hex8Kind::Hex8Eas
    }

    fn hold_hourglass(body: &Body<Solid>, geo: &mut Hex8Geometry, nodes: &[usize; 8], u: &[f64]) {
        let ue: [[f64; 3]; 8] = nodes.map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
        let holds = hex8_hourglass_holds(geo, &body.material, &ue);
        geo.set_alpha_penalty(holds);
    }

    fn force_measure(_: &(), _: &[[f64; 3]]) -> f64 {
        1.0
    }

    fn longest_edge(x: &[[f64; 3]]) -> f64 {
        HEX8_EDGES
            .iter()
            .map(|[a, b]| pair_distance(&x[*a], &x[*b]))
            .fold(0.0, f64::max)
    }

    fn model_ref(m: &Model<Solid>) -> ModelRef<'_> {
        ModelRef::Solid(m)
    }

    fn plane(_: &Model<Solid>) -> &Model<Plane> {
        &EMPTY_PLANE
    }

    fn solid(m: &Model<Solid>) -> Option<&Model<Solid>> {
        Some(m)
    }
}
