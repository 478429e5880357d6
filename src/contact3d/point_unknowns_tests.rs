//! The point kernel under the contact Newton's rule ([`super::decision`]): the mixed arrays
//! against the penalty's, the linearised penalty forces against finite differences, and
//! the decision by the force unknowns.

use super::decision::{SurfaceForces, SurfaceRule};
use super::point::{History, PointEval, PointProblem, SurfaceLinearization, DOFS};
use super::point_tests::{problem, LAW, STICK};
use crate::contact::law::ContactState;

const SLIP: History = History {
    xi: [0.0, 0.1],
    traction: [5.0, 3.0],
};

struct Arrays {
    r: [f64; DOFS],
    r_eq: [f64; DOFS],
    k: [f64; DOFS * DOFS],
    lin: SurfaceLinearization,
    e: PointEval<f64>,
}

fn arrays(p: &PointProblem) -> Arrays {
    let (mut r, mut r_eq, mut k) = ([0.0; DOFS], [0.0; DOFS], [0.0; DOFS * DOFS]);
    let mut lin = SurfaceLinearization::default();
    let e = p.local(&mut r, &mut r_eq, &mut k, &mut lin).unwrap();
    Arrays { r, r_eq, k, lin, e }
}

/// The penalty's own forces at `p` as force unknowns: `N_ε` and `T_α ρ^α`.
fn own_forces(p: &PointProblem) -> SurfaceForces {
    let e = p.evaluate_f64().unwrap();
    SurfaceForces {
        normal: e.normal_force,
        tangential: e.projection.point.vector(e.traction),
    }
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// With the penalty's own forces as unknowns and a small weight (`ρ = 0.01`), the point
/// decides as the penalty rule does, and its residuals and tangent are the penalty's (1e-12
/// relative): the mixed method changes how Newton gets to a solution, not the solution. Its
/// complementarity residuals vanish (1e-9 relative to the forces). Stick, slip, first touch
/// and frictionless, flat and warped facets.
#[test]
fn with_the_penalty_forces_as_unknowns_the_arrays_are_the_penalty_arrays() {
    let frictionless = crate::model::ContactLaw { mu: 0.0, ..LAW };
    for warped in [false, true] {
        for (name, p) in [
            ("stick", problem(warped, -0.01, Some(STICK), LAW)),
            ("slip", problem(warped, -0.01, Some(SLIP), LAW)),
            ("first touch", problem(warped, -0.01, None, LAW)),
            ("frictionless", problem(warped, -0.01, Some(STICK), frictionless)),
        ] {
            let penalty = arrays(&p);
            let mixed = arrays(&PointProblem {
                rule: SurfaceRule::AlartCurnier {
                    forces: own_forces(&p),
                    rho_n: 0.01,
                    rho_t: 0.01,
                },
                ..p
            });
            assert_eq!(mixed.e.state, penalty.e.state, "{name}");
            let (rmax, kmax) = (max_abs(&penalty.r), max_abs(&penalty.k));
            assert!(max_diff(&mixed.r, &penalty.r) <= 1e-12 * rmax, "{name}: r");
            assert!(max_diff(&mixed.r_eq, &penalty.r) <= 1e-12 * rmax, "{name}: r_eq");
            assert!(max_diff(&mixed.k, &penalty.k) <= 1e-12 * kmax, "{name}: k");
            let c = mixed.e.complementarity;
            assert!(
                c[0].abs() + c[1].abs() <= 1e-9 * penalty.e.normal_force,
                "{name}: C = {c:?}"
            );
            assert_eq!(penalty.e.complementarity, [0.0; 2], "{name}");
        }
    }
}

/// The linearised penalty forces `∇N_ε` and `∇(T_α ρ^α)` that update the force unknowns are
/// the derivatives of the penalty forces (central differences, step 1e-6: 1e-6 relative to
/// the largest gradient entry), in stick and slip on the warped facet; the values are the
/// penalty's forces.
#[test]
fn the_linearised_forces_match_finite_differences() {
    for (name, p, state) in [
        ("stick", problem(true, -0.01, Some(STICK), LAW), ContactState::Stick),
        ("slip", problem(true, -0.01, Some(SLIP), LAW), ContactState::Slip),
    ] {
        let a = arrays(&p);
        assert_eq!(a.e.state, state, "{name}");
        let own = own_forces(&p);
        assert_eq!(a.lin.normal, own.normal);
        assert!(max_diff(&a.lin.tangential, &own.tangential) <= 1e-14 * max_abs(&own.tangential));
        let scale = max_abs(&a.lin.d_normal).max(a.lin.d_tangential.iter().map(|g| max_abs(g)).fold(0.0, f64::max));
        let h = 1e-6;
        let mut err: f64 = 0.0;
        for j in 0..DOFS {
            let (mut pp, mut pm) = (p, p);
            pp.x[j / 3][j % 3] += h;
            pm.x[j / 3][j % 3] -= h;
            let (fp, fm) = (own_forces(&pp), own_forces(&pm));
            err = err.max(((fp.normal - fm.normal) / (2.0 * h) - a.lin.d_normal[j]).abs());
            for c in 0..3 {
                let fd = (fp.tangential[c] - fm.tangential[c]) / (2.0 * h);
                err = err.max((fd - a.lin.d_tangential[c][j]).abs());
            }
        }
        eprintln!("linearised forces, {name}: relative error {:.2e}", err / scale);
        assert!(err <= 1e-6 * scale, "{name}: {:e}", err / scale);
    }
}

/// A stiff tangential penalty (`ρ_T = 1e-3`): the trial traction of this iterate overshoots
/// Coulomb's cone, the penalty rule would slip; the force unknown, inside the cone, keeps the
/// point stuck, and the residuals are then the stick penalty's with the unknowns' own
/// `r_eq`. An open point with force unknowns left (lifted off, unit weights): `r`, `k`
/// zero, `r_eq` their force, and their complementarity residuals are the unknowns
/// themselves.
#[test]
fn a_small_weight_decides_by_the_force_unknowns() {
    let hist = History {
        xi: [0.199, -0.301],
        traction: [40.0, -30.0],
    };
    let p = problem(true, -0.01, Some(hist), LAW);
    let penalty = arrays(&p);
    assert_eq!(penalty.e.state, ContactState::Slip);
    let own = own_forces(&problem(true, -0.01, Some(STICK), LAW));
    let stuck = arrays(&PointProblem {
        rule: SurfaceRule::AlartCurnier {
            forces: own,
            rho_n: 1e-3,
            rho_t: 1e-3,
        },
        ..p
    });
    assert_eq!(stuck.e.state, ContactState::Stick);
    assert_eq!(stuck.e.traction, stuck.e.trial);
    assert!(max_diff(&stuck.r_eq, &stuck.r) > 1e-3 * max_abs(&stuck.r));
    // lifted off with unit weights (the augmented force is the penalty's): open, whatever
    // the unknowns say
    let lifted = problem(true, 0.01, Some(STICK), LAW);
    let open = arrays(&PointProblem {
        rule: SurfaceRule::AlartCurnier {
            forces: own,
            rho_n: 1.0,
            rho_t: 1.0,
        },
        ..lifted
    });
    assert_eq!(open.e.state, ContactState::Open);
    assert_eq!((max_abs(&open.r), max_abs(&open.k)), (0.0, 0.0));
    assert!(max_abs(&open.r_eq) > 0.5 * own.normal);
    let c = open.e.complementarity;
    let t = own.tangential.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((c[0] - own.normal).abs() < 1e-12 * own.normal && (c[1] - t).abs() < 1e-12 * t);
}

/// The condensed tangent is the Newton matrix of the mixed system: with force unknowns
/// `λ̄` that are not the penalty's (a tenth more normal force, a tangential force turned out
/// of the trial's direction), `k = ∂r_eq/∂x|_λ̄ + G(x)ᵀ ∇λ_ε` — the change of the unknowns'
/// residual at fixed unknowns (central differences, step 1e-6) plus the unknowns' own
/// linearised correction (`G(x)ᵀ v`: the residual of unit unknowns, linear in them) — to
/// 1e-6 relative, in stick and slip on the warped facet, with weights 1 and 0.01.
#[test]
fn the_condensed_tangent_is_the_mixed_systems_newton_matrix() {
    for (name, p) in [
        ("stick", problem(true, -0.01, Some(STICK), LAW)),
        ("slip", problem(true, -0.01, Some(SLIP), LAW)),
    ] {
        let own = own_forces(&p);
        let unknowns = SurfaceForces {
            normal: 1.1 * own.normal,
            tangential: [own.tangential[1], -own.tangential[0], 0.3 * own.tangential[2]],
        };
        for rho in [1.0, 0.01] {
            let with = |x: &PointProblem, forces: SurfaceForces| PointProblem {
                rule: SurfaceRule::AlartCurnier {
                    forces,
                    rho_n: rho,
                    rho_t: rho,
                },
                ..*x
            };
            let a = arrays(&with(&p, unknowns));
            // G(x)ᵀ v from the residual of unit unknowns
            let unit = |normal: f64, c: Option<usize>| {
                let mut t = [0.0; 3];
                if let Some(c) = c {
                    t[c] = 1.0;
                }
                arrays(&with(&p, SurfaceForces { normal, tangential: t })).r_eq
            };
            let g = [
                unit(1.0, None),
                unit(0.0, Some(0)),
                unit(0.0, Some(1)),
                unit(0.0, Some(2)),
            ];
            let h = 1e-6;
            let kmax = max_abs(&a.k);
            let mut err: f64 = 0.0;
            for j in 0..DOFS {
                let (mut pp, mut pm) = (with(&p, unknowns), with(&p, unknowns));
                pp.x[j / 3][j % 3] += h;
                pm.x[j / 3][j % 3] -= h;
                let (ap, am) = (arrays(&pp), arrays(&pm));
                assert_eq!((ap.e.state, am.e.state), (a.e.state, a.e.state), "{name}");
                let v = [
                    a.lin.d_normal[j],
                    a.lin.d_tangential[0][j],
                    a.lin.d_tangential[1][j],
                    a.lin.d_tangential[2][j],
                ];
                for i in 0..DOFS {
                    let fd = (ap.r_eq[i] - am.r_eq[i]) / (2.0 * h);
                    let gv: f64 = g.iter().zip(v).map(|(g, v)| g[i] * v).sum();
                    err = err.max((fd + gv - a.k[DOFS * i + j]).abs());
                }
            }
            eprintln!(
                "condensed tangent, {name}, ρ = {rho}: relative error {:.2e}",
                err / kmax
            );
            assert!(err <= 1e-6 * kmax, "{name}, ρ = {rho}: {:e}", err / kmax);
        }
    }
}
