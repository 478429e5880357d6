//! The point kernel: tangent against finite differences, equilibrium, frame invariance,
//! return map.

use super::point::{History, PointProblem, DOFS, NODES};
use super::vec3::{cross, dot, norm, sub};
use crate::contact::law::ContactState;
use crate::model::ContactLaw;

/// A history that leaves the points of [`problem`] sticking (`‖T^tr‖ ≈ 0.4 μN`).
pub(super) const STICK: History = History {
    xi: [0.199, -0.301],
    traction: [0.5, -0.3],
};

pub(super) const LAW: ContactLaw = ContactLaw {
    eps_n: 2.1e3,
    eps_t: 1.7e3,
    mu: 0.3,
};

/// A flat facet that is not a parallelogram (`ρ_12 ∥ plane`, `a_αβ` varies).
const FLAT: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.2, 0.1, 0.0], [1.1, 0.9, 0.0], [-0.1, 1.0, 0.0]];
/// A parallelogram in `z = 0` (`ρ_12 = 0`, constant basis).
const PARALLELOGRAM: [[f64; 3]; 4] = [[0.0, 0.0, 0.0], [1.2, 0.1, 0.0], [1.3, 1.1, 0.0], [0.1, 1.0, 0.0]];

/// Slave above point `ξ = (0.2, −0.3)` of a flat facet ([`FLAT`]) or of the warped one, at
/// normal offset `d` (negative: penetrating).
pub(super) fn problem(warped: bool, d: f64, history: Option<History>, law: ContactLaw) -> PointProblem {
    on(
        if warped {
            super::projection_tests::warped().x
        } else {
            FLAT
        },
        d,
        history,
        law,
    )
}

/// The warped facet bent into a Nagata patch with nodal normals tilted off its own normal
/// (the slave placed off the patch).
fn bent(d: f64, history: Option<History>, law: ContactLaw) -> PointProblem {
    let x = super::projection_tests::warped().x;
    let tilt = [[-0.3, -0.3, 1.0], [0.3, -0.2, 1.0], [0.25, 0.3, 1.0], [-0.3, 0.2, 1.0]];
    let normals = tilt.map(|n| super::vec3::scale(n, 1.0 / super::vec3::norm(n)));
    on_bent(x, Some(super::nagata::bend_of(&normals)), d, history, law)
}

fn on(facet: [[f64; 3]; 4], d: f64, history: Option<History>, law: ContactLaw) -> PointProblem {
    on_bent(facet, None, d, history, law)
}

fn on_bent(
    facet: [[f64; 3]; 4],
    bend: Option<super::surface::Bend>,
    d: f64,
    history: Option<History>,
    law: ContactLaw,
) -> PointProblem {
    let f = super::surface::Facet::<f64> { x: facet, bend };
    let p = f.point([0.2, -0.3]).unwrap();
    let slave = std::array::from_fn(|c| p.rho[c] + d * p.normal[c]);
    PointProblem {
        history,
        bend,
        ..PointProblem::new(law, [slave, facet[0], facet[1], facet[2], facet[3]])
    }
}

/// The largest entry-wise difference between the tangent and central finite differences
/// of the residual (step `h = 1e-6` on every coordinate), relative to the largest entry of
/// the tangent; the state must stay the same at every perturbed position.
fn fd_error(p: &PointProblem, expect: ContactState) -> f64 {
    let mut r = [0.0; DOFS];
    let mut k = [0.0; DOFS * DOFS];
    let e = p.residual_tangent(&mut r, &mut k).unwrap();
    assert_eq!(e.state, expect);
    let mut r1 = [0.0; DOFS];
    p.residual(&mut r1).unwrap();
    let rmax = r.iter().fold(1e-300f64, |a, b| a.max(b.abs()));
    assert!(
        r.iter().zip(r1).all(|(a, b)| (a - b).abs() <= 1e-13 * rmax),
        "residual paths differ"
    );
    let h = 1e-6;
    let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let mut err: f64 = 0.0;
    for j in 0..DOFS {
        let (mut pp, mut pm) = (*p, *p);
        pp.x[j / 3][j % 3] += h;
        pm.x[j / 3][j % 3] -= h;
        let (mut rp, mut rm) = ([0.0; DOFS], [0.0; DOFS]);
        assert_eq!(pp.residual(&mut rp).unwrap().state, expect);
        assert_eq!(pm.residual(&mut rm).unwrap().state, expect);
        for i in 0..DOFS {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            err = err.max((fd - k[DOFS * i + j]).abs());
        }
    }
    if expect == ContactState::Open {
        assert_eq!(kmax, 0.0);
        return err;
    }
    err / kmax
}

/// Tangent = central finite differences of the residual (relative to max |K|, ≤ 1e-6) in
/// every state — open, first touch (stick without history), frictionless slip, stick with
/// a history, slip — on a flat facet, on a warped one (curvature terms `h_12`, `∇²ξ`) and on
/// that one bent into a Nagata patch (a full `h_αβ`; the bend's normals held fixed).
/// The open point has `r = K = 0` (exactly). Measured errors are printed.
#[test]
fn tangent_matches_finite_differences_in_every_state() {
    let frictionless = ContactLaw { mu: 0.0, ..LAW };
    let stick = STICK;
    let slip = History {
        xi: [0.0, 0.1],
        traction: [5.0, 3.0],
    };
    // flat, warped, and the warped facet bent into a Nagata patch
    for shape in ["flat", "warped", "bent"] {
        let make = |d: f64, h: Option<History>, law: ContactLaw| match shape {
            "bent" => bent(d, h, law),
            _ => problem(shape == "warped", d, h, law),
        };
        let cases = [
            ("open", make(0.01, Some(stick), LAW), ContactState::Open),
            ("first touch", make(-0.01, None, LAW), ContactState::Stick),
            (
                "frictionless",
                make(-0.01, Some(stick), frictionless),
                ContactState::Slip,
            ),
            ("stick", make(-0.01, Some(stick), LAW), ContactState::Stick),
            ("slip", make(-0.01, Some(slip), LAW), ContactState::Slip),
        ];
        for (name, p, state) in cases {
            let err = fd_error(&p, state);
            eprintln!("FD tangent, {shape}, {name}: relative error {err:.2e}");
            assert!(err < 1e-6, "{name}: {err:e}");
        }
    }
}

/// Equilibrium of the point's forces: the slave's force and the four facet nodes' forces
/// sum to zero (translation invariance of `ζ`, `ξ^α`; 1e-12 relative to the largest force),
/// and their moments about the origin vanish (1e-12), for the normal part alone (at the
/// closest point `∇_I ζ = −N_I n`, so `Σ x_I × f_I = (x_s − ρ) × N n = ζ n × N n = 0`) and
/// for the whole force: `ζ`, `ξ^α` are invariant under rotation, so `Σ x × ∇ξ^α = 0`; the
/// couple of a traction acting on the slave at the offset `ζ n` is balanced through the
/// `ζ n·δρ_α` term of `δξ^α` on the facet nodes (checked non-trivial: the slave's tangential
/// force has a moment about `ρ` of at least 1e-4 of the largest force). On the flat facet
/// the slave's force is `N n + T_α ρ^α` (1e-12): the sign convention.
#[test]
fn forces_balance_and_moments_vanish() {
    let hist = History {
        xi: [0.0, 0.1],
        traction: [5.0, 3.0],
    };
    for p in [
        problem(true, -0.01, Some(hist), LAW),
        problem(false, -0.02, Some(hist), LAW),
    ] {
        let (mut r, mut k) = ([0.0; DOFS], [0.0; DOFS * DOFS]);
        let e = p.residual_tangent(&mut r, &mut k).unwrap();
        assert_eq!(e.state, ContactState::Slip);
        let frictionless = PointProblem {
            history: None,
            law: ContactLaw { mu: 0.0, ..LAW },
            ..p
        };
        let mut rn = [0.0; DOFS];
        frictionless.residual(&mut rn).unwrap();
        let scale = r.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let (mut sum, mut mom_n, mut mom) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        for i in 0..NODES {
            let f = [r[3 * i], r[3 * i + 1], r[3 * i + 2]];
            let fnorm = [rn[3 * i], rn[3 * i + 1], rn[3 * i + 2]];
            let (m, mn) = (cross(p.x[i], f), cross(p.x[i], fnorm));
            for c in 0..3 {
                sum[c] += f[c];
                mom[c] += m[c];
                mom_n[c] += mn[c];
            }
        }
        assert!(norm(sum) < 1e-12 * scale, "sum {sum:?}");
        assert!(norm(mom_n) < 1e-12 * scale, "normal moment {mom_n:?}");
        assert!(norm(mom) < 1e-12 * scale, "moment {mom:?}");
        let n = e.projection.point.normal;
        let t_s: [f64; 3] = std::array::from_fn(|c| -r[c] - e.normal_force * n[c]);
        let couple = cross(n, t_s).map(|v| v * e.projection.gap);
        assert!(norm(couple) > 1e-4 * scale, "{couple:?}");
        if !p.x[1..].iter().any(|x| x[2] != 0.0) {
            // flat facet (h = 0): ∇_s ξ^α = ρ^α, the slave's force is N n + T_α ρ^α (T acts
            // on the slave, N pushes it out along n)
            let t = e.projection.point.vector(e.traction);
            let want: [f64; 3] = std::array::from_fn(|c| e.normal_force * n[c] + t[c]);
            assert!(norm(sub([-r[0], -r[1], -r[2]], want)) < 1e-12 * scale);
        }
        eprintln!(
            "balance: |sum| {:.1e}, |moment| {:.1e}, normal {:.1e} (force scale {scale:.1e})",
            norm(sum),
            norm(mom),
            norm(mom_n)
        );
    }
}

/// Rotation `R` (about (1, 2, 2)/3 by 0.7 rad) and translation of every position: the
/// history is convective (unchanged), the state is the same, each node's force rotates
/// (`r'_I = R r_I`) and each 3×3 block of the tangent is `R K_IJ Rᵀ`, to 1e-12 relative.
#[test]
fn forces_and_tangent_rotate_with_the_frame() {
    let (axis, th): ([f64; 3], f64) = ([1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0], 0.7);
    let (c, s) = (th.cos(), th.sin());
    let rot: [[f64; 3]; 3] = std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let kron = if i == j { c } else { 0.0 };
            let eps = [
                [0.0, -axis[2], axis[1]],
                [axis[2], 0.0, -axis[0]],
                [-axis[1], axis[0], 0.0],
            ];
            kron + s * eps[i][j] + (1.0 - c) * axis[i] * axis[j]
        })
    });
    let apply = |v: [f64; 3]| -> [f64; 3] { std::array::from_fn(|i| dot(rot[i], v)) };
    let hist = Some(History {
        xi: [0.0, 0.1],
        traction: [5.0, 3.0],
    });
    for (p, state) in [
        (problem(true, -0.01, hist, LAW), ContactState::Slip),
        (problem(true, -0.01, Some(STICK), LAW), ContactState::Stick),
    ] {
        let mut q = p;
        q.x = p.x.map(|x| {
            let y = apply(x);
            [y[0] + 3.0, y[1] - 1.0, y[2] + 0.5]
        });
        let (mut r, mut k, mut r2, mut k2) = ([0.0; DOFS], [0.0; DOFS * DOFS], [0.0; DOFS], [0.0; DOFS * DOFS]);
        assert_eq!(p.residual_tangent(&mut r, &mut k).unwrap().state, state);
        assert_eq!(q.residual_tangent(&mut r2, &mut k2).unwrap().state, state);
        let rs = r.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let ks = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for i in 0..NODES {
            let f = apply([r[3 * i], r[3 * i + 1], r[3 * i + 2]]);
            for a in 0..3 {
                assert!((f[a] - r2[3 * i + a]).abs() < 1e-12 * rs);
            }
            for j in 0..NODES {
                for a in 0..3 {
                    for b in 0..3 {
                        // (R K Rᵀ)_ab = R_ac K_cd R_bd
                        let mut v = 0.0;
                        for cc in 0..3 {
                            for d in 0..3 {
                                v += rot[a][cc] * k[DOFS * (3 * i + cc) + 3 * j + d] * rot[b][d];
                            }
                        }
                        assert!((v - k2[DOFS * (3 * i + a) + 3 * j + b]).abs() < 1e-12 * ks);
                    }
                }
            }
        }
    }
}

/// Stick → slip: a slave pressed 0.01 into a parallelogram is moved along `(1, 0.5, 0)/√1.25`
/// by 0.002 per increment, the history updated after each. While `ε_T |u| < μ N` the point
/// sticks with `t = −ε_T × (slide since first touch)` (1e-12 relative); after that it slips
/// with `‖T‖ = √(T_α a^αβ T_β) = μ N` to 1e-14 relative and `t` along the trial.
#[test]
fn stick_then_slip_puts_the_traction_on_the_cone() {
    let law = ContactLaw { mu: 0.2, ..LAW };
    let mut p = on(PARALLELOGRAM, -0.01, None, law);
    let start = p.x[0];
    let dir = [1.0 / 1.25f64.sqrt(), 0.5 / 1.25f64.sqrt(), 0.0];
    let mut seen = [false; 2];
    let mut first_touch = None;
    for step in 0..40 {
        let u = 0.002 * step as f64;
        p.x[0] = std::array::from_fn(|c| start[c] + u * dir[c]);
        let e = p.evaluate_f64().unwrap();
        let pt = &e.projection.point;
        let t = pt.vector(e.traction);
        let n = e.normal_force;
        assert!((n - law.eps_n * 0.01).abs() < 1e-9);
        match e.state {
            ContactState::Stick => {
                let slide = u - first_touch.unwrap_or(u);
                first_touch.get_or_insert(u);
                let want = dir.map(|d| -law.eps_t * slide * d);
                assert!(norm(sub(t, want)) <= 1e-12 * (1.0 + norm(want)), "{t:?} vs {want:?}");
                assert!(!seen[1], "stick after slip");
                seen[0] = true;
            }
            ContactState::Slip => {
                let rel = (pt.norm(e.traction) - law.mu * n).abs() / (law.mu * n);
                assert!(rel < 1e-14, "|T| - mu N: {rel:e}");
                let tr = pt.vector(e.trial);
                assert!(norm(cross(t, tr)) < 1e-12 * norm(t) * norm(tr) && dot(t, tr) > 0.0);
                assert!((norm(t) - law.mu * n).abs() < 1e-12 * n);
                seen[1] = true;
            }
            ContactState::Open => panic!("open"),
        }
        p.history = PointProblem::next_history(&e);
    }
    assert!(seen[0] && seen[1]);
}

/// Against a rigid cylinder (its axis tilted) and a rigid sphere, on their own convective
/// coordinates ([`super::cylinder`], [`super::sphere`]): the tangent equals central finite
/// differences of the residual (≤ 1e-6 of max |K|) in every state, the master's slots stay
/// zero, and the slave's force is `N n + T_α ∇_s ξ^α` with
/// `∇_s ξ^α = ρ_α / (a_αα − ζ h_αα)` (both charts are orthogonal: `a`, `h` diagonal; 1e-12);
/// in slip `|T| = μ N` (1e-12).
#[test]
fn against_a_rigid_cylinder_or_sphere_the_tangent_matches_finite_differences() {
    use super::cylinder::CylinderChart;
    use super::point::RigidChart;
    use super::sphere::SphereChart;
    let axis = [0.3, 1.0, 0.2];
    let centre = [0.1, -0.2, 1.0];
    let cylinder = RigidChart::Cylinder(CylinderChart {
        centre,
        axis: super::vec3::scale(axis, 1.0 / norm(axis)),
        radius: 0.8,
    });
    let sphere = RigidChart::Sphere(SphereChart::for_slave(centre, 0.8, centre, [0.3, 0.0, 0.1]));
    for chart in [cylinder, sphere] {
        let on_chart = |d: f64, history: Option<History>, law: ContactLaw| {
            let p = PointProblem {
                rigid: Some(chart),
                ..PointProblem::new(law, [[0.4, 0.1, 0.2], [0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]])
            };
            let at = p.evaluate_f64().unwrap().projection.point;
            let slave = std::array::from_fn(|c| at.rho[c] + d * at.normal[c]);
            let history = history.map(|h| History {
                xi: [at.xi[0] + h.xi[0], at.xi[1] + h.xi[1]],
                ..h
            });
            PointProblem {
                history,
                x: [slave, [0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]],
                ..p
            }
        };
        // histories relative to the slave's closest point
        let stick = History {
            xi: [-0.001, 0.001],
            traction: [0.5, -0.3],
        };
        let slip = History {
            xi: [-0.1, -0.05],
            traction: [5.0, 3.0],
        };
        let frictionless = ContactLaw { mu: 0.0, ..LAW };
        let cases = [
            ("open", on_chart(0.01, Some(stick), LAW), ContactState::Open),
            ("first touch", on_chart(-0.01, None, LAW), ContactState::Stick),
            (
                "frictionless",
                on_chart(-0.01, Some(stick), frictionless),
                ContactState::Slip,
            ),
            ("stick", on_chart(-0.01, Some(stick), LAW), ContactState::Stick),
            ("slip", on_chart(-0.01, Some(slip), LAW), ContactState::Slip),
        ];
        let kind = match chart {
            RigidChart::Cylinder(_) => "cylinder",
            RigidChart::Sphere(_) => "sphere",
        };
        for (name, p, state) in cases {
            let err = fd_error(&p, state);
            eprintln!("FD tangent, rigid {kind}, {name}: relative error {err:.2e}");
            assert!(err < 1e-6, "{kind}, {name}: {err:e}");
            let (mut r, mut k) = ([0.0; DOFS], [0.0; DOFS * DOFS]);
            let e = p.residual_tangent(&mut r, &mut k).unwrap();
            assert!(r[3..].iter().all(|&v| v == 0.0), "{kind}, {name}: the master's slots");
            let pt = &e.projection.point;
            let zeta = e.projection.gap;
            let share = |al: usize| e.traction[al] / (pt.metric[al][al] - zeta * pt.curvature[al][al]);
            let (n, [r1, r2]) = (pt.normal, pt.tangents);
            let want: [f64; 3] = std::array::from_fn(|c| e.normal_force * n[c] + share(0) * r1[c] + share(1) * r2[c]);
            let scale = r.iter().fold(1e-300f64, |a, b| a.max(b.abs()));
            assert!(
                norm(sub([-r[0], -r[1], -r[2]], want)) <= 1e-12 * scale,
                "{kind}, {name}"
            );
            if name == "slip" {
                let size = norm(pt.vector(e.traction));
                assert!((size - LAW.mu * e.normal_force).abs() <= 1e-12 * size, "{kind}: {size}");
            }
        }
    }
}
