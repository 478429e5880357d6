//! A smooth master face from its facets: Nagata patches (Nagata, "Simple local interpolation
//! of surfaces using normal vectors", CAGD 22 (2005) 9–21; for frictional contact: Neto,
//! Oliveira, Menezes & Alves, CMAME 271 (2014) 296–320).
//!
//! Each node of the face gets a **nodal normal**, the area-weighted mean of the normals of
//! the facets around it ([`FacetBends`]). Each edge `a → b` becomes the quadratic
//! `x(s) = x_a + s d − s(1 − s) c` (`d = x_b − x_a`) whose tangents at both ends are
//! normal to the nodal normals `n_a`, `n_b`: `n_a·c = n_a·d`, `n_b·c = −n_b·d`. With
//! `v = (n_a + n_b)/2`, `w = (n_a − n_b)/2` (`v ⊥ w`) these read `v·c = w·d`, `w·c = v·d`;
//! Nagata's least `c` in the plane of the normals is `v (w·d)/|v|² + w (v·d)/|w|²`. Its
//! second part is ill-posed as the normals approach each other (no curve is tangent to two
//! parallel planes unless the chord lies in them; on a flat face barely strained, `v·d` is
//! strain and round-off, `|w|²` is round-off, and the bulge is anything); it is left out:
//!
//! `c = v (w·d)/|v|² = Q d`, `Q = v wᵀ / |v|²`,
//!
//! a 3×3 matrix of the normals alone ([`edge_matrix`]). Where the chord is normal to `v` —
//! every chord of a sphere, by `(x_a + x_b)·(x_b − x_a) = |x_b|² − |x_a|²` — this is Nagata's
//! curve, tangent at both ends; elsewhere the end tangents miss the nodal planes by the
//! angle `v·d / |d|`, second order in the edge length on a smooth surface. The edge bulges
//! by `|c|/4 ≤ |d| tan(θ/2)/4`, `θ` the normals' angle, so a flat face stays flat. A facet is
//! then the patch `ρ(ξ) = N_I x_I − Σ_e φ_e(ξ) c_e` ([`super::surface::Bend`]): its edges
//! are the shared edge curves (the face stays closed), its tangent planes at the nodes are
//! (nearly) those of the nodal normals, so the normal no longer jumps by the angle between
//! facets at an edge.
//!
//! Normals more than 60° apart (`n_a·n_b < ½`) are a **crease** (a corner of the body, not a
//! curved face): the edge stays straight (`Q = 0`), for both facets at it.
//!
//! The nodal normals and each edge's `Q` are computed once per attempt at an increment, from
//! the positions it starts from (as the search grid is), and are data while Newton iterates
//! ([`FacetBends`]): `c_e = Q_e d_e` on the current chord. The residual is then a function of
//! the positions alone, the point kernel's tangent is its exact derivative, and a point's
//! stencil stays its slave and four facet nodes. The price is a lag: the patches' tangent
//! planes at the nodes are those of the increment's start (a master turned by `δ` in an
//! increment tilts each bulge by `δ`). With normals recomputed at every iterate instead
//! (their turn with the neighbouring nodes left out of the tangent), Newton diverged near
//! convergence: the bulge moves with the neighbours' positions at the same order as with
//! the facet's own.

use super::surface::{Bend, EDGES};
use super::vec3::{add, cross, dot, norm, scale, sub};
use std::collections::HashMap;

/// Normals more than this cosine apart (60°) are a crease: the edge stays straight. A feature
/// angle of this project's choosing, not Nagata's: without one, a face joined round a box's
/// corner (`face = "zmax+xmin"`) would be rounded off by a quarter of the edge. No scene here
/// comes near it (the hemisphere's neighbouring normals differ by ≤ 12°).
pub const CREASE_COS: f64 = 0.5;

/// `Q = v wᵀ / |v|²` of an edge with unit nodal normals `na` at its start and `nb` at its end
/// (zero across a crease; see the module docs).
pub fn edge_matrix(na: [f64; 3], nb: [f64; 3]) -> [[f64; 3]; 3] {
    if dot(na, nb) < CREASE_COS {
        return [[0.0; 3]; 3];
    }
    let v = scale(add(na, nb), 0.5);
    let w = scale(sub(na, nb), 0.5);
    let v2 = dot(v, v);
    v.map(|vi| w.map(|wj| vi * wj / v2))
}

/// The bend of a facet with unit nodal normals `normals` (node order).
pub fn bend_of(normals: &[[f64; 3]; 4]) -> Bend {
    Bend {
        q: EDGES.map(|(a, b)| edge_matrix(normals[a], normals[b])),
    }
}

/// The bends of one face's facets: its nodes' normals (the area-weighted mean of their
/// facets' normals) and each facet's [`Bend`], at the positions of the last [`Self::update`].
#[derive(Debug, Clone, Default)]
pub struct FacetBends {
    /// Global node id → index into `normals`.
    index: HashMap<usize, usize>,
    normals: Vec<[f64; 3]>,
    bends: Vec<Bend>,
}

impl FacetBends {
    /// The face's nodes (no normals yet: every facet bilinear).
    pub fn new(facets: &[[usize; 4]]) -> Self {
        let mut index = HashMap::new();
        for &n in facets.iter().flatten() {
            let next = index.len();
            index.entry(n).or_insert(next);
        }
        FacetBends {
            normals: vec![[0.0; 3]; index.len()],
            index,
            bends: vec![Bend { q: [[[0.0; 3]; 3]; 4] }; facets.len()],
        }
    }

    /// Recompute the normals and bends at positions `position(node)`: each facet adds its
    /// area vector `½ (x_3 − x_1) × (x_4 − x_2)` to its four nodes, each sum is made unit,
    /// then each facet's edges get their `Q` ([`bend_of`]).
    pub fn update(&mut self, facets: &[[usize; 4]], position: impl Fn(usize) -> [f64; 3]) {
        self.normals.iter_mut().for_each(|n| *n = [0.0; 3]);
        for f in facets {
            let x = f.map(&position);
            let area = scale(cross(sub(x[2], x[0]), sub(x[3], x[1])), 0.5);
            for n in f {
                let k = self.index[n];
                self.normals[k] = add(self.normals[k], area);
            }
        }
        for n in &mut self.normals {
            let length = norm(*n);
            if length > 0.0 {
                *n = scale(*n, 1.0 / length);
            }
        }
        for (bend, f) in self.bends.iter_mut().zip(facets) {
            *bend = bend_of(&f.map(|n| self.normals[self.index[&n]]));
        }
    }

    /// The bend of facet `f`.
    pub fn of(&self, f: usize) -> Bend {
        self.bends[f]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact3d::surface::Facet;

    /// Four nodes on the unit sphere's lower half, at the directions `(tan a, tan b, −1)` of
    /// the angle pairs `(a, b)` given in units of 10°: an irregular quadrilateral (no symmetry
    /// hides an edge's formula), its radial normals its nodal normals.
    fn sphere_quad(angles: [[f64; 2]; 4]) -> [[f64; 3]; 4] {
        let d = 10f64.to_radians();
        angles.map(|[a, b]| {
            let v = [(a * d).tan(), (b * d).tan(), -1.0];
            scale(v, 1.0 / norm(v))
        })
    }

    /// Four nodes on the unit sphere, normals radial: the patch's edges are tangent to the
    /// nodal planes at the nodes (`ρ_α·n_I = 0` along the edge at each end, 1e-14), and its
    /// midpoint lies nearer to the sphere than the bilinear facet's (a 20° facet: the flat
    /// one sags by 1.5 %, the patch by < 0.1 %).
    #[test]
    fn a_patch_of_a_sphere_is_tangent_to_the_nodal_normals_and_close_to_the_sphere() {
        let x = sphere_quad([[-1.0, -0.7], [-1.2, 1.0], [0.8, 1.1], [1.0, -1.0]]);
        let bend = bend_of(&x);
        let facet = Facet { x, bend: Some(bend) };
        for (i, xi) in crate::contact3d::surface::NODE_XI.iter().enumerate() {
            let t = facet.tangents(*xi);
            for ta in t {
                assert!(dot(ta, x[i]).abs() < 1e-14, "node {i}: {}", dot(ta, x[i]));
            }
        }
        let sag = |f: &Facet<f64>| 1.0 - norm(f.position([0.0, 0.0]));
        let flat = Facet::flat(x);
        assert!(sag(&flat) > 0.015, "flat sag {}", sag(&flat));
        assert!(sag(&facet).abs() < 1e-3, "patch sag {}", sag(&facet));
    }

    /// Past its edges a patch goes on along the edge's tangent plane: position and tangents
    /// are continuous at `|ξ^α| = 1` (1e-8 across a step of 2e-9), and a point far out on
    /// the extension lies on the straight continuation (no curl back).
    #[test]
    fn a_patch_is_continued_by_its_tangent_past_its_edges() {
        let x = sphere_quad([[-1.0, -1.0], [-1.0, 1.0], [1.0, 1.0], [1.0, -1.0]]);
        let facet = Facet {
            x,
            bend: Some(bend_of(&x)),
        };
        for edge in [[1.0, 0.3], [-1.0, 0.3], [0.3, 1.0], [0.3, -1.0]] {
            let step = |s: f64| edge.map(|v: f64| if v.abs() == 1.0 { v * (1.0 + s) } else { v });
            let (inside, outside) = (step(-1e-9), step(1e-9));
            assert!(norm(sub(facet.position(inside), facet.position(outside))) < 1e-8);
            let (ti, to) = (facet.tangents(inside), facet.tangents(outside));
            assert!(norm(sub(ti[0], to[0])) < 1e-8 && norm(sub(ti[1], to[1])) < 1e-8);
            // linear in the outward coordinate beyond the edge
            let (p1, p2, p3) = (
                facet.position(step(0.5)),
                facet.position(step(1.0)),
                facet.position(step(1.5)),
            );
            assert!(norm(sub(add(p1, p3), scale(p2, 2.0))) < 1e-12);
        }
    }

    /// Normals more than 60° apart (a box's edge) leave the edge straight; so do parallel
    /// normals; normals 1e-6 apart on a chord tilted out of their plane by 1e-3 (a flat face
    /// barely strained) bulge by no more than `|w| |d| / |v|` (1e-6 of the chord), where
    /// Nagata's full formula would bulge by 500 chords.
    #[test]
    fn creases_and_nearly_parallel_normals_keep_nearly_straight_edges() {
        let up = [0.0, 0.0, 1.0];
        let side = [1.0, 0.0, 0.0];
        assert_eq!(edge_matrix(up, side), [[0.0; 3]; 3]);
        let q = edge_matrix(up, up);
        assert!(q.iter().flatten().all(|v| v.abs() < 1e-15));
        let tipped = scale([2e-6, 0.0, 1.0], 1.0 / norm([2e-6, 0.0, 1.0]));
        let d = [1.0, 0.0, 1e-3];
        let c: [f64; 3] = edge_matrix(up, tipped).map(|row| dot(row, d));
        assert!(norm(c) <= 1.01e-6 * norm(d), "bulge {}", norm(c));
    }
}
