//! Per-call cost of the kernels (issue 8, item 3):
//! * the element kernel: one EAS quadrilateral, residual with and without tangent,
//!   St. Venant–Kirchhoff and Neo-Hooke, warm-started `α` (as in a Newton iteration, where
//!   `α` of the last evaluation is the starting guess);
//! * the contact-point kernel (residual and tangent by second-order dual numbers): a slave
//!   node on a face segment that it reached from the neighbouring segment (4 node slots,
//!   8 DOFs), in stick and in slip, for each history-transfer scheme;
//! * the hexahedron (plain and EAS-21), residual with and without tangent, warm-started `α`;
//! * the 3D node-to-surface kernel (residual and tangent by first-order dual numbers and the
//!   closed-form variations, 15 DOFs): a slave node penetrating a warped bilinear facet with
//!   a friction history, in stick and in slip, and the residual alone.
//!
//! Run: `cargo bench --bench kernels` (figures in docs/performance.md).

use contrail::contact::point::{Closed, Path, PointProblem, SegSource, SlaveSource, MAX_NODES};
use contrail::contact::transfer::StoredTraction;
use contrail::contact3d::point::{History, PointProblem as PointProblem3, DOFS as DOFS3};
use contrail::element::hex8::{hex8_residual_tangent_with, Hex8Geometry, Hex8Kind, EAS_COUNT};
use contrail::element::material::{lame, Material};
use contrail::element::quad::{quad_residual_tangent_with, ElementKind, QuadGeometry};
use contrail::model::contact::{ContactLaw, TransferKind};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

const X: [[f64; 2]; 4] = [[0.0, 0.0], [1.3, 0.1], [1.1, 0.9], [-0.1, 0.7]];
const U: [[f64; 2]; 4] = [[0.0, 0.0], [0.12, 0.05], [0.02, 0.21], [-0.08, 0.03]];

fn bench(c: &mut Criterion) {
    let (l, m) = lame(2.1e4, 0.3);
    let materials = [
        ("svk", Material::SaintVenantKirchhoff { lambda: l, mu: m }),
        ("neo-hooke", Material::NeoHookean { lambda: l, mu: m }),
    ];
    let mut g = c.benchmark_group("element");
    for (name, mat) in &materials {
        for kind in [ElementKind::Q4, ElementKind::Q4Eas] {
            // as the assembler builds it (closed-form α for St. Venant–Kirchhoff)
            let geo = QuadGeometry::for_material(kind, mat, &X).expect("valid element");
            let mut alpha = [0.0; 4];
            let (mut r, mut k) = ([0.0; 8], [0.0; 64]);
            // converged α for U, then a slightly different u: the local Newton starts warm
            quad_residual_tangent_with(kind, mat, &geo, &U, &mut alpha, &mut r, None).expect("evaluates");
            let mut u = U;
            u[2][0] += 1e-4;
            g.bench_function(format!("{kind:?}/{name}/residual+tangent"), |b| {
                b.iter(|| {
                    let mut a = alpha;
                    quad_residual_tangent_with(kind, mat, &geo, black_box(&u), &mut a, &mut r, Some(&mut k))
                        .expect("evaluates");
                    black_box((&r, &k));
                })
            });
            g.bench_function(format!("{kind:?}/{name}/residual"), |b| {
                b.iter(|| {
                    let mut a = alpha;
                    quad_residual_tangent_with(kind, mat, &geo, black_box(&u), &mut a, &mut r, None)
                        .expect("evaluates");
                    black_box(&r);
                })
            });
        }
    }
    // the general path (local Newton on α) for the material with a constant tangent
    let (kind, mat) = (ElementKind::Q4Eas, &materials[0].1);
    let geo = QuadGeometry::new(kind, &X).expect("valid element");
    let mut alpha = [0.0; 4];
    let (mut r, mut k) = ([0.0; 8], [0.0; 64]);
    quad_residual_tangent_with(kind, mat, &geo, &U, &mut alpha, &mut r, None).expect("evaluates");
    let mut u = U;
    u[2][0] += 1e-4;
    g.bench_function("Q4Eas/svk-local-newton/residual+tangent", |b| {
        b.iter(|| {
            let mut a = alpha;
            quad_residual_tangent_with(kind, mat, &geo, black_box(&u), &mut a, &mut r, Some(&mut k))
                .expect("evaluates");
            black_box((&r, &k));
        })
    });
    g.finish();

    hexahedron(c, &materials);

    let mut g = c.benchmark_group("contact-point");
    for scheme in [
        TransferKind::Straightforward,
        TransferKind::Continuous,
        TransferKind::PathLength,
    ] {
        for (state, mu) in [("stick", 1e3), ("slip", 0.05)] {
            let p = crossing_point(scheme, mu);
            let (mut r, mut k) = ([0.0; 8], [0.0; 64]);
            g.bench_function(format!("{scheme:?}/{state}"), |b| {
                b.iter(|| black_box(black_box(&p).residual_tangent(&mut r, &mut k)))
            });
        }
    }
    g.finish();

    let mut g = c.benchmark_group("contact-point-3d");
    for (state, mu) in [("stick", 1e3), ("slip", 0.05)] {
        let p = surface_point(mu);
        let (mut r, mut k) = ([0.0; DOFS3], [0.0; DOFS3 * DOFS3]);
        g.bench_function(format!("{state}/residual+tangent"), |b| {
            b.iter(|| black_box(black_box(&p).residual_tangent(&mut r, &mut k)))
        });
        g.bench_function(format!("{state}/residual"), |b| {
            b.iter(|| black_box(black_box(&p).residual(&mut r)))
        });
    }
    g.finish();
}

/// A distorted hexahedron's reference nodes and displacements (every strain component
/// nonzero).
const X3: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.1, 0.05, 0.0],
    [1.0, 0.9, 0.1],
    [-0.05, 1.0, 0.0],
    [0.0, 0.1, 1.0],
    [1.0, 0.0, 1.1],
    [1.05, 1.0, 0.95],
    [0.0, 0.95, 1.0],
];

/// The hexahedra: plain and EAS-21, both materials, residual with and without tangent, `α`
/// warm from a displacement 1e-4 away (as in a Newton iteration).
fn hexahedron(c: &mut Criterion, materials: &[(&str, Material)]) {
    let u0: [[f64; 3]; 8] = std::array::from_fn(|i| std::array::from_fn(|a| 0.02 * ((3 * i + a) as f64).sin()));
    let mut g = c.benchmark_group("hexahedron");
    for (name, mat) in materials {
        for kind in [Hex8Kind::Hex8, Hex8Kind::Hex8Eas] {
            let geo = Hex8Geometry::new(kind, &X3).expect("valid element");
            let mut alpha = [0.0; EAS_COUNT];
            let (mut r, mut k) = ([0.0; 24], [0.0; 576]);
            hex8_residual_tangent_with(kind, mat, &geo, &u0, &mut alpha, &mut r, None).expect("evaluates");
            let mut u = u0;
            u[2][0] += 1e-4;
            g.bench_function(format!("{kind:?}/{name}/residual+tangent"), |b| {
                b.iter(|| {
                    let mut a = alpha;
                    hex8_residual_tangent_with(kind, mat, &geo, black_box(&u), &mut a, &mut r, Some(&mut k))
                        .expect("evaluates");
                    black_box((&r, &k));
                })
            });
            g.bench_function(format!("{kind:?}/{name}/residual"), |b| {
                b.iter(|| {
                    let mut a = alpha;
                    hex8_residual_tangent_with(kind, mat, &geo, black_box(&u), &mut a, &mut r, None)
                        .expect("evaluates");
                    black_box(&r);
                })
            });
        }
    }
    g.finish();
}

/// A slave 0.01 into a warped facet above `ξ = (0.2, −0.3)`, with the history of a point
/// that was at `ξ = (0.1, −0.25)` carrying a traction (stick for a large `μ`, slip for a
/// small one).
fn surface_point(mu: f64) -> PointProblem3 {
    use contrail::contact3d::surface::Facet;
    let facet = [
        [-1.0, -1.1, 0.05],
        [1.2, -0.9, -0.1],
        [0.9, 1.0, 0.2],
        [-1.1, 0.8, -0.05],
    ];
    let p = Facet::<f64>::flat(facet).point([0.2, -0.3]).unwrap();
    let slave = std::array::from_fn(|c| p.rho[c] - 0.01 * p.normal[c]);
    let law = ContactLaw {
        eps_n: 2.1e3,
        eps_t: 1.7e3,
        mu,
    };
    PointProblem3 {
        history: Some(History {
            xi: [0.1, -0.25],
            traction: [0.4, -0.2],
        }),
        ..PointProblem3::new(law, [slave, facet[0], facet[1], facet[2], facet[3]])
    }
}

/// Slot 0 the slave (penetrating), 1–2 the current segment B, 3 the far node of the segment A
/// it was on at the last converged increment.
fn crossing_point(scheme: TransferKind, mu: f64) -> PointProblem {
    let mut x = [[0.0; 2]; MAX_NODES];
    x[0] = [0.31, 0.02];
    x[1] = [0.0, 0.001];
    x[2] = [0.8, -0.01];
    x[3] = [-0.5, 0.004];
    PointProblem {
        law: ContactLaw {
            eps_n: 2.1e3,
            eps_t: 1.7e3,
            mu,
        },
        scheme,
        x,
        n_nodes: 4,
        slave: SlaveSource::Node(0),
        seg_b: SegSource::Face([1, 2]),
        closed: Some(Closed {
            stored: StoredTraction {
                xi: 0.93,
                t1: 0.8,
                a11: 0.0626,
                slave: [0.3, 0.018],
                tangent: [1.0, 0.0],
            },
            seg_a: SegSource::Face([3, 1]),
            path: Path {
                direction: 1,
                between: 0.0,
            },
            touch_gap: None,
        }),
        multiplier: None,
        at_vertex: None,
        rule: contrail::contact::decision::Rule::Penalty,
        kink: contrail::contact::decision::Kink::Open,
        warm: false,
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
