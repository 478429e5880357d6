//! Small meshes of hexahedra, assembled densely inside the tests: patch tests (linear and
//! finite strain, distorted elements), locking in bending and near incompressibility.

use super::tests::{materials, YOUNG};
use super::*;
use nalgebra::{DMatrix, DVector, Matrix3};

pub(super) struct Mesh {
    pub nodes: Vec<[f64; 3]>,
    pub elems: Vec<[usize; 8]>,
}

/// A structured block of `n` elements over `[0, size]`, node `(i, j, k)` numbered
/// `i + (n₀+1)(j + (n₁+1) k)`, elements in Gmsh/VTK order.
pub(super) fn block(n: [usize; 3], size: [f64; 3]) -> Mesh {
    let id = |i: usize, j: usize, k: usize| i + (n[0] + 1) * (j + (n[1] + 1) * k);
    let mut nodes = vec![[0.0; 3]; (n[0] + 1) * (n[1] + 1) * (n[2] + 1)];
    for k in 0..=n[2] {
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                let f = [i as f64 / n[0] as f64, j as f64 / n[1] as f64, k as f64 / n[2] as f64];
                nodes[id(i, j, k)] = std::array::from_fn(|c| f[c] * size[c]);
            }
        }
    }
    let mut elems = Vec::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let c = HEX8_NODES.map(|p| {
                    let o = p.map(|v| usize::from(v > 0.0));
                    id(i + o[0], j + o[1], k + o[2])
                });
                elems.push(c);
            }
        }
    }
    Mesh { nodes, elems }
}

/// Global internal force and tangent at the global displacements `u` (`α` per element, kept
/// from call to call as a solver would).
fn assemble(
    kind: Hex8Kind,
    m: &Material,
    mesh: &Mesh,
    u: &DVector<f64>,
    alphas: &mut [[f64; EAS_COUNT]],
) -> (DVector<f64>, DMatrix<f64>) {
    let n = u.len();
    let (mut r, mut k) = (DVector::zeros(n), DMatrix::zeros(n, n));
    for (el, al) in mesh.elems.iter().zip(alphas.iter_mut()) {
        let x = el.map(|i| mesh.nodes[i]);
        let ue = el.map(|i| [u[3 * i], u[3 * i + 1], u[3 * i + 2]]);
        let (mut re, mut ke) = ([0.0; 24], [0.0; 576]);
        hex8_residual_tangent(kind, m, &x, &ue, al, &mut re, Some(&mut ke)).unwrap();
        let dof = |a: usize| 3 * el[a / 3] + a % 3;
        for a in 0..24 {
            r[dof(a)] += re[a];
            for b in 0..24 {
                k[(dof(a), dof(b))] += ke[24 * a + b];
            }
        }
    }
    (r, k)
}

/// Newton's method for `R(u) = f` with the DOFs `fixed` held at their values in `u`; from a
/// zero state `linear` takes one step with the tangent at rest (the linear response).
pub(super) fn solve(
    kind: Hex8Kind,
    m: &Material,
    mesh: &Mesh,
    fixed: &[bool],
    f: &DVector<f64>,
    u: &mut DVector<f64>,
    linear: bool,
) {
    let free: Vec<usize> = (0..u.len()).filter(|&i| !fixed[i]).collect();
    let mut alphas = vec![[0.0; EAS_COUNT]; mesh.elems.len()];
    let zero = DVector::zeros(u.len());
    let mut first = None;
    for it in 0..30 {
        let (r, k) = assemble(kind, m, mesh, if linear { &zero } else { u }, &mut alphas);
        let g = if linear { &k * &*u - f } else { r - f };
        let gf = DVector::from_iterator(free.len(), free.iter().map(|&i| g[i]));
        let g0 = *first.get_or_insert(gf.amax());
        assert!(it < 25, "Newton did not converge: {:.3e} of {g0:.3e}", gf.amax());
        let kf = DMatrix::from_fn(free.len(), free.len(), |a, b| k[(free[a], free[b])]);
        let du = kf.lu().solve(&gf).unwrap();
        for (a, &i) in free.iter().enumerate() {
            u[i] -= du[a];
        }
        // converged: a step this small leaves an error of order its square
        if linear || du.amax() <= 1e-9 * u.amax() {
            return;
        }
    }
}

/// Deterministic pseudo-random numbers in `[−1, 1]`.
pub(super) fn jitter(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// Patch test (Irons; Taylor, Simo & Zienkiewicz): a 3×3×3 patch of the unit cube with every
/// node moved by up to 0.08 (a quarter of an element) in each direction, the boundary nodes
/// displaced by a homogeneous deformation `x = F X + c`, the eight interior nodes free.
/// Both kinds and materials, a small `F − I` (1e-4, linear solve with the tangent at rest)
/// and a finite one (stretches up to ≈ 1.3, Newton): the interior nodes land on `F X + c`,
/// every Gauss point carries the homogeneous strain `½(FᵀF − I)` and `α = 0`. Tolerances
/// 1e-9 of `|F − I|` (measured: nodes ≤ 7e-16, strains ≤ 1e-11, `α` ≤ 1e-16).
#[test]
fn distorted_patch_reproduces_homogeneous_states() {
    let mut mesh = block([3, 3, 3], [1.0; 3]);
    let mut seed = 7u64;
    for p in &mut mesh.nodes {
        for v in p.iter_mut() {
            *v += 0.08 * jitter(&mut seed);
        }
    }
    let on_boundary = |i: usize| {
        let (a, b, c) = (i % 4, (i / 4) % 4, i / 16);
        [a, b, c].iter().any(|&v| v == 0 || v == 3)
    };
    let fixed: Vec<bool> = (0..3 * mesh.nodes.len()).map(|d| on_boundary(d / 3)).collect();
    let general = Matrix3::new(0.25, 0.1, -0.05, -0.08, -0.15, 0.12, 0.06, 0.2, 0.1);
    for (scale, linear) in [(4e-4, true), (1.0, false)] {
        let f_minus_i = general * scale;
        let exact =
            |p: &[f64; 3]| f_minus_i * nalgebra::Vector3::from(*p) + nalgebra::Vector3::new(0.1, -0.2, 0.05) * scale;
        let c = Matrix3::identity() + f_minus_i;
        let e_hom = 0.5 * (c.transpose() * c - Matrix3::identity());
        for m in materials(0.3) {
            for kind in [Hex8Kind::Hex8, Hex8Kind::Hex8Eas] {
                // the boundary at the homogeneous state, the interior off it (at rest in the
                // linear case; moved off by up to 0.02 in the finite one)
                let mut u = DVector::zeros(3 * mesh.nodes.len());
                for (i, p) in mesh.nodes.iter().enumerate() {
                    if on_boundary(i) {
                        u.rows_mut(3 * i, 3).copy_from(&exact(p));
                    } else if !linear {
                        let off = nalgebra::Vector3::from_fn(|_, _| 0.02 * jitter(&mut seed));
                        u.rows_mut(3 * i, 3).copy_from(&(exact(p) + off));
                    }
                }
                solve(kind, &m, &mesh, &fixed, &DVector::zeros(u.len()), &mut u, linear);
                let mut err = 0.0f64;
                for (i, p) in mesh.nodes.iter().enumerate() {
                    err = err.max((u.rows(3 * i, 3) - exact(p)).amax());
                }
                let mut strain_err = 0.0f64;
                let mut alpha_max = 0.0f64;
                for el in &mesh.elems {
                    let x = el.map(|i| mesh.nodes[i]);
                    let ue = el.map(|i| [u[3 * i], u[3 * i + 1], u[3 * i + 2]]);
                    let geo = Hex8Geometry::new(kind, &x).unwrap();
                    // from a non-zero guess: α = 0 must be found, not kept
                    let (mut al, mut r) = ([1e-3; EAS_COUNT], [0.0; 24]);
                    hex8_residual_tangent_with(kind, &m, &geo, &ue, &mut al, &mut r, None).unwrap();
                    if kind == Hex8Kind::Hex8Eas {
                        alpha_max = al.iter().fold(alpha_max, |a, b| a.max(b.abs()));
                    }
                    for e in hex8_gauss_strains(&geo, &ue, &al).unwrap() {
                        let t = crate::element::material3d::strain_tensor(&e);
                        strain_err = strain_err.max((t - e_hom).amax());
                    }
                }
                let size = f_minus_i.amax();
                println!("patch {kind:?} {m:?} |F−I| {size:.1e}: node error {:.2e}, strain error {:.2e}, max |α| {alpha_max:.1e} (relative)", err / size, strain_err / size);
                assert!(err <= 1e-9 * size && strain_err <= 1e-9 * size && alpha_max <= 1e-9 * size);
            }
        }
    }
}

/// End load of the block of [`beam_deflection`].
#[derive(Clone, Copy)]
enum Load {
    /// A force `P` along `z` shared by the four tip nodes.
    Shear(f64),
    /// A moment `M` about `y`: the consistent nodal forces of `σ_xx = M (z − ½)/I` on the tip
    /// face, `±M/2` along `x` at its top and bottom nodes (`h = 1`).
    Moment(f64),
}

/// An `n × 1 × 1` block `[0, len] × [0, 1] × [0, 1]`, linear response (`linear`) or Newton.
/// Root: `u_x = u_z = 0` at its four nodes, `u_y = 0` at one (the section contracts freely),
/// or with `plane_strain` `u_y = 0` at every node.
struct Beam {
    n: usize,
    len: f64,
    load: Load,
    plane_strain: bool,
    linear: bool,
}

/// The mean tip deflection `u_z` of a [`Beam`].
fn beam_deflection(kind: Hex8Kind, m: &Material, beam: &Beam) -> f64 {
    let mesh = block([beam.n, 1, 1], [beam.len, 1.0, 1.0]);
    let dofs = 3 * mesh.nodes.len();
    let at_root = |i: usize| mesh.nodes[i][0] == 0.0;
    let tip: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&i| mesh.nodes[i][0] == beam.len)
        .collect();
    let fixed: Vec<bool> = (0..dofs)
        .map(|d| match d % 3 {
            1 => beam.plane_strain || d == 1,
            _ => at_root(d / 3),
        })
        .collect();
    let mut f = DVector::zeros(dofs);
    for &i in &tip {
        match beam.load {
            Load::Shear(p) => f[3 * i + 2] = 0.25 * p,
            Load::Moment(m) => f[3 * i] = if mesh.nodes[i][2] > 0.5 { 0.5 } else { -0.5 } * m,
        }
    }
    let mut u = DVector::zeros(dofs);
    solve(kind, m, &mesh, &fixed, &f, &mut u, beam.linear);
    tip.iter().map(|&i| u[3 * i + 2]).sum::<f64>() / tip.len() as f64
}

/// Timoshenko's tip deflection of a cantilever `len` long, square unit section, under `p`:
/// `δ = PL³/(3EI) + PL/(κGA)`, `κ = 5/6`.
fn timoshenko(len: f64, p: f64, nu: f64) -> f64 {
    let shear = YOUNG / (2.0 * (1.0 + nu));
    p * len.powi(3) / (3.0 * YOUNG / 12.0) + p * len / (5.0 / 6.0 * shear)
}

/// No shear locking: a cantilever `L/h = 10` (square section) of 10 × 1 × 1 cubes under an
/// end shear force, linear response (tangent at rest). Reference: Timoshenko (the shear
/// part is 0.8 % of it). EAS within 2 % (measured 0.9960); the plain trilinear element locks
/// (measured 0.650; ≤ 0.8 asserted). With 5 elements of aspect 2: EAS within 2 % (0.9880),
/// plain ≤ 0.5 (0.371). The EAS answer under a small load by Newton's method with Neo-Hooke
/// (δ/L ≈ 1e-4) agrees with the linear one to 1e-3.
#[test]
fn a_one_layer_cantilever_does_not_lock_in_bending() {
    let (nu, len) = (0.3, 10.0);
    let m = materials(nu)[0];
    let beam = |n, p, linear| Beam {
        n,
        len,
        load: Load::Shear(p),
        plane_strain: false,
        linear,
    };
    let mut ratios = Vec::new();
    for (n, plain_max) in [(10, 0.8), (5, 0.5)] {
        let eas = beam_deflection(Hex8Kind::Hex8Eas, &m, &beam(n, 1.0, true)) / timoshenko(len, 1.0, nu);
        let plain = beam_deflection(Hex8Kind::Hex8, &m, &beam(n, 1.0, true)) / timoshenko(len, 1.0, nu);
        println!("cantilever {n}x1x1, ν = {nu}: δ/δ_Timoshenko EAS {eas:.4}, plain {plain:.4}");
        assert!((eas - 1.0).abs() <= 0.02, "EAS {eas}");
        assert!(plain <= plain_max, "plain {plain}");
        ratios.push(eas);
    }
    let small = 2e-3;
    let nh = materials(nu)[1];
    let newton = beam_deflection(Hex8Kind::Hex8Eas, &nh, &beam(10, small, false)) / timoshenko(len, small, nu);
    println!(
        "cantilever 10x1x1 Neo-Hooke Newton at δ/L ≈ 1e-4: {newton:.6} (linear {:.6})",
        ratios[0]
    );
    assert!((newton - ratios[0]).abs() <= 1e-3);
}

/// No volumetric (nor shear) locking: pure bending of a 4 × 1 × 1 block (`L = 10`, elements
/// of aspect 2.5) by an end moment, linear response, `ν = 0.3` and `ν = 0.4999`, free
/// section and plane strain. Reference: the exact elasticity solution (Saint-Venant's pure
/// bending, `κ = M/(E'I)`: `u_x = κ x z`, `u_y = −ν κ y z`, `u_z = −κ/2 (x² + ν (z² − y²))`
/// with centroidal `y, z` and `E' = E`; in plane strain `u_y = 0`,
/// `u_z = −κ/2 (x² + ν/(1−ν) z²)`, `E' = E/(1 − ν²)`), which the root restraints admit on a
/// square section; the tip deflection at the corners is `M L²/(2E'I)` relative to the root.
/// The EAS element contains it exactly (its enhanced modes are the gradients of Wilson's
/// bubbles, module documentation), and so does the solid-shell (assumed shears sampled where
/// the bending's spurious shear vanishes, the thickness mode for the Poisson strain): 1e-8 relative (measured ≤ 1.5e-9 at ν = 0.4999,
/// conditioning λ/μ = 5000). The plain element locks: ratio ≤ 0.3 with a free section (it is
/// shear locking: 0.281 and 0.267), ≤ 0.01 in plane strain at ν = 0.4999 (volumetric:
/// 0.0008; 0.293 at ν = 0.3).
#[test]
fn pure_bending_is_exact_also_near_incompressibility() {
    let (len, moment, inertia) = (10.0, 1.0, 1.0 / 12.0);
    for (nu, plane_strain, plain_max) in [
        (0.3, false, 0.3),
        (0.4999, false, 0.3),
        (0.3, true, 0.3),
        (0.4999, true, 0.01),
    ] {
        let modulus = if plane_strain { YOUNG / (1.0 - nu * nu) } else { YOUNG };
        let exact = -moment * len * len / (2.0 * modulus * inertia);
        let m = materials(nu)[1];
        let beam = Beam {
            n: 4,
            len,
            load: Load::Moment(moment),
            plane_strain,
            linear: true,
        };
        let eas = beam_deflection(Hex8Kind::Hex8Eas, &m, &beam) / exact;
        let shell = beam_deflection(Hex8Kind::SolidShell, &m, &beam) / exact;
        let plain = beam_deflection(Hex8Kind::Hex8, &m, &beam) / exact;
        println!(
            "pure bending 4x1x1, ν = {nu}, plane strain {plane_strain}: δ/δ_exact EAS {eas:.12}, solid-shell {shell:.12}, plain {plain:.4}"
        );
        assert!((eas - 1.0).abs() <= 1e-8, "EAS {eas}");
        assert!((shell - 1.0).abs() <= 1e-8, "solid-shell {shell}");
        assert!(plain <= plain_max, "plain {plain}");
    }
}

/// Near incompressibility under a varying moment: the cantilever of the shear-locking test
/// at `ν = 0.4999`, 10 × 1 × 1 and 20 × 1 × 1, against Timoshenko's deflection (`G = E/3`).
/// EAS-21 within 1 % (measured 0.9955 and 0.9977; its first nine modes alone gave 0.939 and
/// 0.950: the bilinear part of the volumetric strain, module documentation); the plain
/// element ≤ 0.5 (measured 0.39 and 0.48).
#[test]
fn a_nearly_incompressible_cantilever_does_not_lock() {
    let (nu, len) = (0.4999, 10.0);
    let m = materials(nu)[0];
    let beam = |n| Beam {
        n,
        len,
        load: Load::Shear(1.0),
        plane_strain: false,
        linear: true,
    };
    for n in [10, 20] {
        let eas = beam_deflection(Hex8Kind::Hex8Eas, &m, &beam(n)) / timoshenko(len, 1.0, nu);
        let plain = beam_deflection(Hex8Kind::Hex8, &m, &beam(n)) / timoshenko(len, 1.0, nu);
        println!("cantilever {n}x1x1, ν = {nu}: δ/δ_Timoshenko EAS {eas:.4}, plain {plain:.4}");
        assert!((eas - 1.0).abs() <= 0.01, "EAS {eas}");
        assert!(plain <= 0.5, "plain {plain}");
    }
}
