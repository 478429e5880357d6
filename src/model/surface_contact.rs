//! 3D contact pairs resolved to indices: slave nodes of a deformable body against the
//! bilinear facets of another body's face, or against a rigid analytic surface (a plane or a
//! sphere moved by a prescribed translation). Node-to-surface in the covariant description
//! (Konyukhov & Schweizerhof, Comput Mech 35 (2005)); the kernels are in `contact3d`.
//!
//! Penalties in 3D are per unit area: a slave node's normal force is `N = ε_N A_s ⟨−ζ⟩`
//! with `A_s` its tributary area on its face in the reference configuration (a quarter of
//! each face quadrilateral it is a corner of), so `ε_N` is a pressure per unit penetration
//! and the penalty's error does not depend on the mesh size ([`SurfacePair::law_of`]).
//! A slave side that is a straight edge (nodes on one line, [`SlaveMeasure::Length`]) weighs
//! its nodes by their tributary lengths instead: `ε_N` per unit length, the force of a 2D
//! point per unit thickness along the edge.

use super::contact::{ContactLaw, Smoothing};
use super::ramp::Ramp;
use crate::contact3d::transfer::Scheme;

/// A 3D contact pair (one pass; a two-pass interface is two pairs, the second named
/// `NAME/second-pass` as in 2D).
#[derive(Debug, Clone)]
pub struct SurfacePair {
    pub name: String,
    /// Slave nodes (global ids).
    pub slaves: Vec<usize>,
    /// Per slave: its tributary area `A_s` on its face (reference configuration), or its
    /// tributary length on an edge slave ([`SurfacePair::measure`]).
    pub areas: Vec<f64>,
    /// What `areas` measure.
    pub measure: SlaveMeasure,
    pub master: SurfaceMaster,
    /// `ε_N`, `ε_T` per unit area, `μ` (with a `friction` history: its largest value).
    pub law: ContactLaw,
    /// `μ(t)` where the friction coefficient changes over the run (frictionless while a body
    /// is pressed, then rough while it is twisted); `None`: `law.mu` throughout.
    pub friction: Option<Ramp>,
    pub transfer: Scheme,
    /// A deformable master's interpolation: [`Smoothing::None`] (bilinear facets) or
    /// [`Smoothing::Nagata`] (`contact3d::nagata`).
    pub smoothing: Smoothing,
    /// Slaves farther than this from every facet (or the rigid surface) are not paired.
    pub search_radius: f64,
}

impl SurfacePair {
    /// The law of slave `is`: the penalties times its tributary area.
    pub fn law_of(&self, is: usize) -> ContactLaw {
        let a = self.areas.get(is).copied().unwrap_or(1.0);
        ContactLaw {
            eps_n: self.law.eps_n * a,
            eps_t: self.law.eps_t * a,
            mu: self.law.mu,
        }
    }

    /// The law of slave `is` at time `t`: [`Self::law_of`] with `μ(t)` where the pair has a
    /// friction history.
    pub fn law_at(&self, is: usize, t: f64) -> ContactLaw {
        let law = self.law_of(is);
        match &self.friction {
            Some(mu) => ContactLaw { mu: mu.at(t), ..law },
            None => law,
        }
    }
}

/// What a 3D pair's slave weights measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SlaveMeasure {
    /// Tributary areas on a face: penalties per unit area.
    #[default]
    Area,
    /// Tributary lengths along a straight edge: penalties per unit length.
    Length,
}

/// What the slaves of a 3D pair press on.
#[derive(Debug, Clone)]
pub enum SurfaceMaster {
    /// The quadrilateral facets of a deformable body's face (counter-clockwise seen from
    /// outside: outward normal).
    Facets { body: usize, facets: Vec<[usize; 4]> },
    /// A rigid analytic surface.
    Rigid(RigidSurface),
}

/// A rigid analytic surface moved by a prescribed translation.
#[derive(Debug, Clone)]
pub struct RigidSurface {
    pub name: String,
    pub shape: RigidSurfaceShape,
    pub motion: [Ramp; 3],
}

impl RigidSurface {
    /// The translation at time `t`.
    pub fn offset(&self, t: f64) -> [f64; 3] {
        [self.motion[0].at(t), self.motion[1].at(t), self.motion[2].at(t)]
    }
}

/// The shape of a rigid surface in its reference position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RigidSurfaceShape {
    /// The plane through `point` with unit outward `normal` (the rigid body is behind it).
    Plane { point: [f64; 3], normal: [f64; 3] },
    /// A rigid ball: the outside of the sphere `centre`, `radius` is the contact surface.
    Sphere { centre: [f64; 3], radius: f64 },
    /// A rigid round bar: the outside of the infinite circular cylinder through `point` along
    /// the unit `axis`, `radius`.
    Cylinder {
        point: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
}
