//! A C1-smoothed segment of a deformable face: the cubic Hermite curve between the segment's
//! two nodes with tangents taken from their neighbours (Wriggers, Krstulovic-Opara & Korelc,
//! IJNME 51 (2001) 1469–1495, who build such segments from the neighbouring nodes; also
//! Padmanabhan & Laursen, FEAD 37 (2001) 173–198).
//!
//! Nodes `x0` (the neighbour before, if any), `x1`, `x2` (the segment), `x3` (the neighbour
//! after, if any). With `s = (ξ + 1)/2 ∈ [0, 1]`:
//!
//! `ρ(s) = h00 x1 + h10 T1 + h01 x2 + h11 T2`,
//! `h00 = 2s³ − 3s² + 1`, `h10 = s³ − 2s² + s`, `h01 = −2s³ + 3s²`, `h11 = s³ − s²`,
//!
//! with the node tangents (per unit `s`) along the central chords, scaled by this segment's
//! length `ℓ12` over the two segments' lengths:
//! `T1 = ℓ12 (x2 − x0)/(ℓ01 + ℓ12)`, `T2 = ℓ12 (x3 − x1)/(ℓ12 + ℓ23)`, and the chord `x2 − x1`
//! at a free end. Both segments meeting at a node take its tangent along the same chord
//! (`x3 − x1` at `x2`), so the face's tangent direction — and its normal — are continuous
//! across nodes (G1): a slave point crossing a node no longer sees the normal jump by the
//! kink angle, and a rigid vertex pressing on a bent face gets the bent face's normal, not
//! that of one facet. `ρ_1 = ∂ρ/∂ξ = ½ ∂ρ/∂s`.
//!
//! The closest point solves `(r_s − ρ(ξ))·ρ_1(ξ) = 0` by Newton's method, first on the real
//! parts (from the chord's projection), then two more steps in the scalar type `S`
//! ([`super::smooth_closest_xi`]): from a converged real root, Newton steps in dual numbers
//! give the exact first and second derivatives of `ξ` with respect to every node (the
//! implicit-function derivatives), so the contact kernel's tangent stays consistent.

use super::{smooth_arc_length, smooth_closest_xi, MasterSegment};
use crate::contact::scalar::{add, dot, re, scale, sub, Scalar, V2};

/// Cubic Hermite face segment `x1 → x2` with the neighbouring nodes `x0`, `x3` (`None` at a
/// free end).
#[derive(Debug, Clone, Copy)]
pub struct HermiteSegment<S: Scalar> {
    pub x0: Option<V2<S>>,
    pub x1: V2<S>,
    pub x2: V2<S>,
    pub x3: Option<V2<S>>,
}

fn norm<S: Scalar>(a: V2<S>) -> S {
    dot(a, a).sqrt()
}

impl<S: Scalar> HermiteSegment<S> {
    /// Node tangents `T1`, `T2` per unit `s`.
    fn tangents(&self) -> (V2<S>, V2<S>) {
        let chord = sub(self.x2, self.x1);
        let l12 = norm(chord);
        let t1 = match self.x0 {
            Some(x0) => scale(sub(self.x2, x0), l12 / (norm(sub(self.x1, x0)) + l12)),
            None => chord,
        };
        let t2 = match self.x3 {
            Some(x3) => scale(sub(x3, self.x1), l12 / (l12 + norm(sub(x3, self.x2)))),
            None => chord,
        };
        (t1, t2)
    }

    /// `ρ`, `ρ_1 = ∂ρ/∂ξ` and `ρ_11 = ∂²ρ/∂ξ²` at `ξ`.
    pub fn eval2(&self, xi: S) -> (V2<S>, V2<S>, V2<S>) {
        let (t1, t2) = self.tangents();
        let s = (xi + 1.0) * 0.5;
        let (s2, s3) = (s * s, s * s * s);
        let h = [
            s3 * 2.0 - s2 * 3.0 + 1.0,
            s3 - s2 * 2.0 + s,
            s2 * 3.0 - s3 * 2.0,
            s3 - s2,
        ];
        // d/ds and d²/ds² of the basis
        let dh = [
            s2 * 6.0 - s * 6.0,
            s2 * 3.0 - s * 4.0 + 1.0,
            s * 6.0 - s2 * 6.0,
            s2 * 3.0 - s * 2.0,
        ];
        let ddh = [s * 12.0 - 6.0, s * 6.0 - 4.0, S::from(6.0) - s * 12.0, s * 6.0 - 2.0];
        let comb = |w: &[S; 4]| {
            add(
                add(scale(self.x1, w[0]), scale(t1, w[1])),
                add(scale(self.x2, w[2]), scale(t2, w[3])),
            )
        };
        // dξ = 2 ds
        (
            comb(&h),
            scale(comb(&dh), S::from(0.5)),
            scale(comb(&ddh), S::from(0.25)),
        )
    }
}

impl<S: Scalar> MasterSegment<S> for HermiteSegment<S> {
    fn eval(&self, xi: S) -> (V2<S>, V2<S>) {
        let (rho, rho1, _) = self.eval2(xi);
        (rho, rho1)
    }

    fn closest_xi(&self, rs: V2<S>) -> S {
        let real = HermiteSegment::<f64> {
            x0: self.x0.map(re::<S>),
            x1: re(self.x1),
            x2: re(self.x2),
            x3: self.x3.map(re::<S>),
        };
        smooth_closest_xi(&|xi| real.eval2(xi), &|xi| self.eval2(xi), (real.x1, real.x2), rs)
    }

    fn length(&self) -> S {
        self.arc_length(S::from(-1.0), S::from(1.0))
    }

    fn arc_length(&self, from: S, to: S) -> S {
        smooth_arc_length(&|xi| self.eval(xi).1, from, to)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::geometry::SegmentGeom;

    fn seg(x0: Option<V2<f64>>, x3: Option<V2<f64>>) -> HermiteSegment<f64> {
        HermiteSegment {
            x0,
            x1: [0.0, 0.0],
            x2: [1.0, 0.1],
            x3,
        }
    }

    #[test]
    fn hermite_segment_interpolates_its_nodes_and_is_straight_on_a_straight_face() {
        let s = seg(Some([-1.0, -0.1]), Some([2.0, 0.2]));
        let (a, _) = s.eval(-1.0);
        let (b, _) = s.eval(1.0);
        assert!(norm(sub(a, [0.0, 0.0])) < 1e-15 && norm(sub(b, [1.0, 0.1])) < 1e-15);
        for xi in [-0.7, 0.0, 0.4] {
            let (p, t) = s.eval(xi);
            let (q, u) = SegmentGeom::linear([0.0, 0.0], [1.0, 0.1]).eval(xi);
            assert!(norm(sub(p, q)) < 1e-14 && norm(sub(t, u)) < 1e-14, "{xi}");
        }
    }

    #[test]
    fn neighbouring_segments_share_the_tangent_direction_at_their_node() {
        let (x0, x1, x2, x3, x4) = ([-1.0, 0.3], [0.0, 0.0], [1.0, 0.1], [1.6, 0.5], [2.0, 1.2]);
        let a = HermiteSegment {
            x0: Some(x0),
            x1,
            x2,
            x3: Some(x3),
        };
        let b = HermiteSegment {
            x0: Some(x1),
            x1: x2,
            x2: x3,
            x3: Some(x4),
        };
        let (pa, ta) = a.eval(1.0);
        let (pb, tb) = b.eval(-1.0);
        assert!(norm(sub(pa, pb)) < 1e-15);
        let cross = ta[0] * tb[1] - ta[1] * tb[0];
        assert!(cross.abs() < 1e-14 * norm(ta) * norm(tb) && dot(ta, tb) > 0.0);
    }

    #[test]
    fn closest_point_is_orthogonal_on_the_curve() {
        let s = seg(Some([-0.8, 0.4]), Some([1.7, 0.6]));
        for rs in [[0.3, 0.5], [0.8, -0.2], [0.05, 0.01]] {
            let xi = s.closest_xi(rs);
            let (p, t) = s.eval(xi);
            assert!(dot(sub(rs, p), t).abs() < 1e-13, "{rs:?}: ξ = {xi}");
        }
    }
}
