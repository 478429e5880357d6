//! A C1-smoothed segment of a deformable face by quadratic Bézier arcs (Wriggers,
//! Krstulovic-Opara & Korelc, IJNME 51 (2001) 1469–1495, who smooth a face by Bézier
//! polynomials as well as by Hermite ones): over each node the arc from the midpoint of the
//! segment before it to the midpoint of the segment after it, with the node as the middle
//! control point. This is the uniform quadratic B-spline of the nodes: it is C1 everywhere,
//! passes through the segments' midpoints and *cuts* each corner of the face instead of
//! passing through the node (at a node the curve is `(x₀ + 6x₁ + x₂)/8`, inside a convex
//! corner by `|x₀ − 2x₁ + x₂|/8`); on a straight face it is the face.
//!
//! Nodes `x0` (the neighbour before, if any), `x1`, `x2` (the segment), `x3` (the neighbour
//! after, if any); midpoints `m01`, `m12`, `m23`. The segment `ξ ∈ [−1, 1]` carries the second
//! half of `x1`'s arc for `ξ ≤ 0` and the first half of `x2`'s for `ξ ≥ 0`:
//!
//! `ξ ≤ 0`: `ρ = (1−s)² m01 + 2s(1−s) x1 + s² m12`, `s = 1 + ξ/2`;
//! `ξ ≥ 0`: `ρ = (1−s)² m12 + 2s(1−s) x2 + s² m23`, `s = ξ/2`.
//!
//! Both halves meet at `m12` with `ρ_1 = (x2 − x1)/2`, and neighbouring segments meet at the
//! quarter points of the node's arc with `ρ_1 = (x3 − x1)/4` on both sides (C1 in the
//! parameter, not only G1). At a free end the missing neighbour is the reflection of the
//! other (`x0 = 2x1 − x2`): the end half is then the straight line from the end node to
//! the midpoint, so the curve still ends at the end node. The curvature jumps at `ξ = 0` and
//! at the segment ends (a quadratic spline is C1, not C2).
//!
//! The closest point is found as for the Hermite segment ([`super::smooth_closest_xi`]).
//! Each segment couples its four nodes, as the Hermite one does.

use super::{smooth_arc_length, smooth_closest_xi, MasterSegment};
use crate::contact::scalar::{add, scale, sub, Scalar, V2};

/// Quadratic-Bézier face segment `x1 → x2` with the neighbouring nodes `x0`, `x3` (`None`
/// at a free end).
#[derive(Debug, Clone, Copy)]
pub struct BezierSegment<S: Scalar> {
    pub x0: Option<V2<S>>,
    pub x1: V2<S>,
    pub x2: V2<S>,
    pub x3: Option<V2<S>>,
}

fn mid<S: Scalar>(a: V2<S>, b: V2<S>) -> V2<S> {
    scale(add(a, b), S::from(0.5))
}

/// The reflection of `b` about `a`, `2a − b` (the phantom neighbour of a free end).
fn reflect<S: Scalar>(a: V2<S>, b: V2<S>) -> V2<S> {
    sub(scale(a, S::from(2.0)), b)
}

/// `ρ`, `dρ/ds`, `d²ρ/ds²` of the quadratic Bézier `p0, p1, p2` at `s`.
fn quadratic<S: Scalar>(p: [V2<S>; 3], s: S) -> (V2<S>, V2<S>, V2<S>) {
    let t = S::from(1.0) - s;
    let rho = add(add(scale(p[0], t * t), scale(p[1], s * t * 2.0)), scale(p[2], s * s));
    let d = scale(add(scale(sub(p[1], p[0]), t), scale(sub(p[2], p[1]), s)), S::from(2.0));
    let dd = scale(add(sub(p[0], scale(p[1], S::from(2.0))), p[2]), S::from(2.0));
    (rho, d, dd)
}

impl<S: Scalar> BezierSegment<S> {
    /// `ρ`, `ρ_1 = ∂ρ/∂ξ` and `ρ_11` at `ξ` (the half `ξ ≤ 0` or `ξ > 0`, extended past the
    /// segment's ends by its own polynomial).
    pub fn eval2(&self, xi: S) -> (V2<S>, V2<S>, V2<S>) {
        let x0 = self.x0.unwrap_or_else(|| reflect(self.x1, self.x2));
        let x3 = self.x3.unwrap_or_else(|| reflect(self.x2, self.x1));
        let m12 = mid(self.x1, self.x2);
        let (ctrl, s) = if xi.re() <= 0.0 {
            ([mid(x0, self.x1), self.x1, m12], xi * 0.5 + 1.0)
        } else {
            ([m12, self.x2, mid(self.x2, x3)], xi * 0.5)
        };
        let (rho, d, dd) = quadratic(ctrl, s);
        // dξ = 2 ds
        (rho, scale(d, S::from(0.5)), scale(dd, S::from(0.25)))
    }

    fn real(&self) -> BezierSegment<f64> {
        use crate::contact::scalar::re;
        BezierSegment {
            x0: self.x0.map(re::<S>),
            x1: re(self.x1),
            x2: re(self.x2),
            x3: self.x3.map(re::<S>),
        }
    }
}

impl<S: Scalar> MasterSegment<S> for BezierSegment<S> {
    fn eval(&self, xi: S) -> (V2<S>, V2<S>) {
        let (rho, rho1, _) = self.eval2(xi);
        (rho, rho1)
    }

    fn closest_xi(&self, rs: V2<S>) -> S {
        let real = self.real();
        smooth_closest_xi(&|xi| real.eval2(xi), &|xi| self.eval2(xi), (real.x1, real.x2), rs)
    }

    fn length(&self) -> S {
        self.arc_length(S::from(-1.0), S::from(1.0))
    }

    fn arc_length(&self, from: S, to: S) -> S {
        // the curvature jumps at ξ = 0: integrate each polynomial half on its own
        let zero = S::from(0.0);
        if from.re() < 0.0 && to.re() > 0.0 {
            smooth_arc_length(&|xi| self.eval(xi).1, from, zero) + smooth_arc_length(&|xi| self.eval(xi).1, zero, to)
        } else if from.re() > 0.0 && to.re() < 0.0 {
            -self.arc_length(to, from)
        } else {
            smooth_arc_length(&|xi| self.eval(xi).1, from, to)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::scalar::dot;

    fn norm(a: V2<f64>) -> f64 {
        dot(a, a).sqrt()
    }

    #[test]
    fn bezier_segment_cuts_the_corner_through_the_midpoint_and_is_the_face_when_straight() {
        let s = BezierSegment {
            x0: Some([-1.0, 0.5]),
            x1: [0.0, 0.0],
            x2: [1.0, 0.0],
            x3: Some([2.0, 0.5]),
        };
        let (m, t) = s.eval(0.0);
        assert!(norm(sub(m, [0.5, 0.0])) < 1e-15 && norm(sub(t, [0.5, 0.0])) < 1e-15);
        let (a, _) = s.eval(-1.0);
        // (x0 + 6 x1 + x2) / 8
        assert!(norm(sub(a, [0.0, 0.0625])) < 1e-15, "{a:?}");
        let straight = BezierSegment {
            x0: Some([-2.0, 0.0]),
            x1: [0.0, 0.0],
            x2: [1.0, 0.0],
            x3: None,
        };
        for xi in [-1.0, -0.4, 0.3, 1.0] {
            let (p, _) = straight.eval(xi);
            assert!(
                p[1].abs() < 1e-15 && (-0.125 - 1e-15..=1.0 + 1e-15).contains(&p[0]),
                "{xi}: {p:?}"
            );
        }
        // a free end ends at the end node, straight to the midpoint
        let (end, t_end) = straight.eval(1.0);
        assert!(norm(sub(end, [1.0, 0.0])) < 1e-15 && norm(sub(t_end, [0.5, 0.0])) < 1e-15);
    }

    #[test]
    fn neighbouring_bezier_segments_meet_with_the_same_tangent() {
        let x = [[-1.0, 0.3], [0.0, 0.0], [1.0, 0.1], [1.6, 0.5], [2.0, 1.2]];
        let a = BezierSegment {
            x0: Some(x[0]),
            x1: x[1],
            x2: x[2],
            x3: Some(x[3]),
        };
        let b = BezierSegment {
            x0: Some(x[1]),
            x1: x[2],
            x2: x[3],
            x3: Some(x[4]),
        };
        let (pa, ta) = a.eval(1.0);
        let (pb, tb) = b.eval(-1.0);
        assert!(norm(sub(pa, pb)) < 1e-15 && norm(sub(ta, tb)) < 1e-15);
        // and within the segment at ξ = 0
        let (p0, t0) = a.eval(-1e-13);
        let (p1, t1) = a.eval(1e-13);
        assert!(norm(sub(p0, p1)) < 1e-12 && norm(sub(t0, t1)) < 1e-12);
    }

    #[test]
    fn bezier_closest_point_is_orthogonal_and_the_length_is_the_arc() {
        let s = BezierSegment {
            x0: Some([-0.8, 0.4]),
            x1: [0.0, 0.0],
            x2: [1.0, 0.1],
            x3: Some([1.7, 0.6]),
        };
        for rs in [[0.3, 0.5], [0.8, -0.2], [0.05, 0.01], [0.5, 0.05]] {
            let xi = s.closest_xi(rs);
            let (p, t) = s.eval(xi);
            assert!(dot(sub(rs, p), t).abs() < 1e-13, "{rs:?}: ξ = {xi}");
        }
        // polyline of 2000 pieces
        let n = 2000;
        let pts: Vec<V2<f64>> = (0..=n).map(|i| s.eval(-1.0 + 2.0 * i as f64 / n as f64).0).collect();
        let poly: f64 = pts.windows(2).map(|w| norm(sub(w[1], w[0]))).sum();
        assert!((s.length() - poly).abs() < 1e-6, "{} vs {poly}", s.length());
        let part = s.arc_length(-0.5, 0.7) + s.arc_length(0.7, 1.0) + s.arc_length(-1.0, -0.5);
        assert!((part - s.length()).abs() < 1e-12);
    }
}
