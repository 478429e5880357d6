//! Fillets: C1 smoothing of a rigid outline by a tangent arc of a chosen radius at every
//! vertex where two straight pieces meet (`[[rigid]] fillet = r`).
//!
//! ```text
//!        d1 →        P1  ╮  arc of radius r, tangent to both pieces
//!   ━━━━━━━━━━━━━━━━━━●   ╲
//!                     ┆ L  ● P2      L = r tan(|θ|/2) taken off both pieces at V
//!                     V ┈┈  ┃ d2     (θ: the turn from d1 to d2)
//! ```
//!
//! The body lies on the left of travel: at a left turn (a convex vertex) the arc's centre
//! is on the left and it runs counter-clockwise (the body inside the circle); at a right turn
//! (a concave vertex) the centre is on the right and it runs clockwise (the body outside),
//! as every arc of an outline ([`crate::model::rigid`]).

use crate::model::Piece;
use crate::scene::build_pairs::VERTEX_TURN;

fn unit(a: [f64; 2], b: [f64; 2]) -> ([f64; 2], f64) {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l = d[0].hypot(d[1]);
    ([d[0] / l, d[1] / l], l)
}

/// The arc of radius `r` at the joint `v` of a straight piece along `d1` and the next one,
/// turning by `turn` radians, and the length `L` it takes off both pieces.
fn joint_arc(v: [f64; 2], d1: [f64; 2], turn: f64, r: f64) -> (Piece, f64) {
    let l = r * (0.5 * turn.abs()).tan();
    let p1 = [v[0] - l * d1[0], v[1] - l * d1[1]];
    let side = turn.signum(); // +1: centre on the left of d1
    let centre = [p1[0] - side * r * d1[1], p1[1] + side * r * d1[0]];
    let theta0 = (p1[1] - centre[1]).atan2(p1[0] - centre[0]);
    (
        Piece::Arc {
            centre,
            radius: r,
            theta0,
            theta1: theta0 + turn,
        },
        l,
    )
}

/// `pieces` with a tangent arc of radius `r` at every joint of two straight pieces that
/// turns by more than [`VERTEX_TURN`]. Errors (a sentence) when `r` is not positive or an
/// arc needs more of a piece than there is.
pub fn fillet(pieces: &[Piece], r: f64) -> Result<Vec<Piece>, String> {
    if !(r > 0.0 && r.is_finite()) {
        return Err(format!("fillet = {r}: the radius must be positive"));
    }
    let n = pieces.len();
    let mut trim = vec![[0.0f64; 2]; n]; // taken off the start and the end of each piece
    let mut arcs: Vec<Option<Piece>> = vec![None; n]; // the arc after piece k
    for k in 1..n {
        let (Piece::Segment { a: a1, b: b1 }, Piece::Segment { a: a2, b: b2 }) = (pieces[k - 1], pieces[k]) else {
            continue;
        };
        let ((d1, _), (d2, _)) = (unit(a1, b1), unit(a2, b2));
        let turn = (d1[0] * d2[1] - d1[1] * d2[0]).atan2(d1[0] * d2[0] + d1[1] * d2[1]);
        if turn.abs() <= VERTEX_TURN {
            continue;
        }
        let (arc, l) = joint_arc(b1, d1, turn, r);
        trim[k - 1][1] = l;
        trim[k][0] = l;
        arcs[k - 1] = Some(arc);
    }
    let mut out = Vec::with_capacity(2 * n);
    for (k, p) in pieces.iter().enumerate() {
        match *p {
            Piece::Segment { a, b } => {
                let (d, len) = unit(a, b);
                let [s, e] = trim[k];
                if s + e > len * (1.0 + 1e-12) {
                    return Err(format!(
                        "fillet = {r} needs {:.6} of straight piece {k} ({:.6} at its start, {:.6} at its end) but it is {len:.6} long: take a smaller radius",
                        s + e,
                        s,
                        e
                    ));
                }
                if len - s - e > 1e-12 * len {
                    out.push(Piece::Segment {
                        a: [a[0] + s * d[0], a[1] + s * d[1]],
                        b: [b[0] - e * d[0], b[1] - e * d[1]],
                    });
                }
            }
            arc => out.push(arc),
        }
        if let Some(arc) = arcs[k] {
            out.push(arc);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-12
    }

    #[test]
    fn a_fillet_is_tangent_to_both_pieces_and_runs_the_right_way() {
        // the strip-channel's block: top face travelling −x, then the wall down (a left turn)
        let pieces = [
            Piece::Segment {
                a: [20.0, 0.0],
                b: [6.5, 0.0],
            },
            Piece::Segment {
                a: [6.5, 0.0],
                b: [6.5, -40.0],
            },
        ];
        let f = fillet(&pieces, 0.5).unwrap();
        assert_eq!(f.len(), 3);
        let Piece::Arc {
            centre,
            radius,
            theta0,
            theta1,
        } = f[1]
        else {
            panic!("{f:?}")
        };
        assert!(close(centre, [7.0, -0.5]) && radius == 0.5);
        assert!(theta1 > theta0, "convex vertex: counter-clockwise (the block inside)");
        // the pieces join end to end with the same tangent direction
        for w in f.windows(2) {
            let (pa, ta) = w[0].eval(1.0);
            let (pb, tb) = w[1].eval(-1.0);
            assert!(close(pa, pb), "{w:?}");
            let cross = ta[0] * tb[1] - ta[1] * tb[0];
            assert!(
                cross.abs() < 1e-12 * ta[0].hypot(ta[1]) * tb[0].hypot(tb[1]) && ta[0] * tb[0] + ta[1] * tb[1] > 0.0
            );
        }
        // a right turn (concave vertex: a seat) runs clockwise
        let seat = [
            Piece::Segment {
                a: [0.0, 0.0],
                b: [1.0, 0.0],
            },
            Piece::Segment {
                a: [1.0, 0.0],
                b: [2.0, -1.0],
            },
        ];
        let Piece::Arc { theta0, theta1, .. } = fillet(&seat, 0.3).unwrap()[1] else {
            panic!()
        };
        assert!(theta1 < theta0);
    }

    #[test]
    fn a_fillet_larger_than_its_pieces_is_refused_and_tangent_joints_are_kept() {
        let pieces = [
            Piece::Segment {
                a: [0.0, 0.0],
                b: [1.0, 0.0],
            },
            Piece::Segment {
                a: [1.0, 0.0],
                b: [1.0, 1.0],
            },
        ];
        let e = fillet(&pieces, 2.0).unwrap_err();
        assert!(e.contains("smaller radius"), "{e}");
        assert!(fillet(&pieces, 0.0).is_err());
        // collinear pieces: no vertex, nothing inserted
        let straight = [
            Piece::Segment {
                a: [0.0, 0.0],
                b: [1.0, 0.0],
            },
            Piece::Segment {
                a: [1.0, 0.0],
                b: [2.0, 0.0],
            },
        ];
        assert_eq!(fillet(&straight, 0.1).unwrap(), straight.to_vec());
    }
}
