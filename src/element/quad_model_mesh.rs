//! Test support for the plane-stress and axisymmetric elements: a structured mesh, a dense
//! assembly of the element kernels and a Newton solve with prescribed displacements (the
//! tests of `quad_axisym_tests.rs` and `quad_plane_stress_tests.rs` run whole small problems
//! without the model, assembler or solver of the crate).

use super::{quad_residual_tangent_with, ElementKind, Kinematics, QuadGeometry};
use crate::element::material::Material;
use nalgebra::{DMatrix, DVector};

/// Nodes and counter-clockwise quadrilaterals.
pub(super) struct Mesh {
    pub nodes: Vec<[f64; 2]>,
    pub elements: Vec<[usize; 4]>,
}

impl Mesh {
    /// `nx × ny` elements on the grid `xs × ys` (node `(i, j)` is `j (nx + 1) + i`).
    pub fn grid(xs: &[f64], ys: &[f64]) -> Mesh {
        let nx = xs.len() - 1;
        let nodes = ys.iter().flat_map(|&y| xs.iter().map(move |&x| [x, y])).collect();
        let mut elements = Vec::new();
        for j in 0..ys.len() - 1 {
            for i in 0..nx {
                let n0 = j * (nx + 1) + i;
                elements.push([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1]);
            }
        }
        Mesh { nodes, elements }
    }

    /// The node nearest to `p`.
    pub fn node_at(&self, p: [f64; 2]) -> usize {
        let d = |q: &[f64; 2]| (q[0] - p[0]).hypot(q[1] - p[1]);
        (0..self.nodes.len())
            .min_by(|&a, &b| d(&self.nodes[a]).total_cmp(&d(&self.nodes[b])))
            .unwrap()
    }
}

/// `n + 1` equally spaced values from `a` to `b`.
pub(super) fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// The global internal force and tangent at `u` (element `α` updated in place).
fn assemble(
    mesh: &Mesh,
    geos: &[QuadGeometry],
    kind: ElementKind,
    material: &Material,
    u: &DVector<f64>,
    alphas: &mut [[f64; 4]],
) -> (DVector<f64>, DMatrix<f64>) {
    let n = 2 * mesh.nodes.len();
    let (mut r, mut k) = (DVector::zeros(n), DMatrix::zeros(n, n));
    for ((el, geo), al) in mesh.elements.iter().zip(geos).zip(alphas.iter_mut()) {
        let ue = el.map(|i| [u[2 * i], u[2 * i + 1]]);
        let (mut re, mut ke) = ([0.0; 8], [0.0; 64]);
        quad_residual_tangent_with(kind, material, geo, &ue, al, &mut re, Some(&mut ke)).unwrap();
        for a in 0..8 {
            let ga = 2 * el[a / 2] + a % 2;
            r[ga] += re[a];
            for b in 0..8 {
                k[(ga, 2 * el[b / 2] + b % 2)] += ke[8 * a + b];
            }
        }
    }
    (r, k)
}

/// Solution of `R(u) = f` with the DOFs `fixed` prescribed (global DOF `2 node + c`, value),
/// in `steps` equal increments of `fixed` and `f`, each by Newton's method (two corrections
/// past `|R − f|` ≤ 1e-6 of `max |R|` on the free DOFs); returns `u` and the reactions `R(u) − f` (zero on the free DOFs).
pub(super) fn solve_in_steps(
    mesh: &Mesh,
    kind: ElementKind,
    material: &Material,
    kinematics: Kinematics,
    fixed: &[(usize, f64)],
    f: &DVector<f64>,
    steps: usize,
) -> (DVector<f64>, DVector<f64>) {
    let geos: Vec<QuadGeometry> = mesh
        .elements
        .iter()
        .map(|el| QuadGeometry::with_kinematics(kind, material, kinematics, &el.map(|i| mesh.nodes[i])).unwrap())
        .collect();
    let n = 2 * mesh.nodes.len();
    let mut u = DVector::zeros(n);
    let mut is_fixed = vec![false; n];
    for &(d, _) in fixed {
        is_fixed[d] = true;
    }
    let free: Vec<usize> = (0..n).filter(|&d| !is_fixed[d]).collect();
    let mut alphas = vec![[0.0; 4]; mesh.elements.len()];
    for step in 1..=steps {
        let load = step as f64 / steps as f64;
        for &(d, v) in fixed {
            u[d] = load * v;
        }
        let fs = f * load;
        // past 1e-6 of max |R| two more corrections: the quadratic rate takes the error to
        // round-off (E = ½(FᵀF − I) loses 1e-16/|E| of the strain to cancellation)
        let mut after = None;
        for _ in 0..30 {
            let (r, k) = assemble(mesh, &geos, kind, material, &u, &mut alphas);
            let res = &r - &fs;
            let rf = DVector::from_iterator(free.len(), free.iter().map(|&d| res[d]));
            if after.is_none() && rf.amax() <= 1e-6 * r.amax() {
                after = Some(2);
            }
            if after == Some(0) {
                if step == steps {
                    return (u, res);
                }
                break;
            }
            after = after.map(|a| a - 1);
            let kf = DMatrix::from_fn(free.len(), free.len(), |a, b| k[(free[a], free[b])]);
            let du = kf.lu().solve(&rf).expect("singular stiffness");
            for (a, &d) in free.iter().enumerate() {
                u[d] -= du[a];
            }
        }
        let converged = after == Some(0);
        assert!(converged, "Newton did not converge in step {step}");
    }
    unreachable!()
}

/// [`solve_in_steps`] in one step.
pub(super) fn solve(
    mesh: &Mesh,
    kind: ElementKind,
    material: &Material,
    kinematics: Kinematics,
    fixed: &[(usize, f64)],
    f: &DVector<f64>,
) -> (DVector<f64>, DVector<f64>) {
    solve_in_steps(mesh, kind, material, kinematics, fixed, f, 1)
}

/// Residual, tangent and energy of one element on a prepared geometry.
pub(super) fn eval(
    kind: ElementKind,
    m: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
) -> ([f64; 8], [f64; 64], f64) {
    let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
    let e = quad_residual_tangent_with(kind, m, geo, u, &mut a, &mut r, Some(&mut k)).unwrap();
    (r, k, e)
}

/// The largest difference between the tangent and the central difference (h = 1e-6) of
/// the residual, and between the residual and that of the energy, relative to `max |K|`.
pub(super) fn fd_errors(kind: ElementKind, m: &Material, geo: &QuadGeometry, u: [[f64; 2]; 4]) -> (f64, f64) {
    let (r, k, _) = eval(kind, m, geo, &u);
    let h = 1e-6;
    let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let (mut ek, mut er) = (0.0f64, 0.0f64);
    for j in 0..8 {
        let (mut up, mut um) = (u, u);
        up[j / 2][j % 2] += h;
        um[j / 2][j % 2] -= h;
        let ((rp, _, ep), (rm, _, em)) = (eval(kind, m, geo, &up), eval(kind, m, geo, &um));
        for i in 0..8 {
            ek = ek.max(((rp[i] - rm[i]) / (2.0 * h) - k[8 * i + j]).abs() / kmax);
        }
        er = er.max(((ep - em) / (2.0 * h) - r[j]).abs() / kmax);
    }
    (ek, er)
}

/// Eigenvalues of an element tangent, ascending.
pub(super) fn eigenvalues(k: &[f64; 64]) -> Vec<f64> {
    let mut ev: Vec<f64> = nalgebra::SMatrix::<f64, 8, 8>::from_row_slice(k)
        .symmetric_eigenvalues()
        .iter()
        .copied()
        .collect();
    ev.sort_by(f64::total_cmp);
    ev
}

/// The five-element patch of MacNeal & Harder (Finite Elem. Anal. Des. 1 (1985) 3–20,
/// fig. 2: 0.24 × 0.12, four distorted interior nodes), shifted by `dx` along x; nodes 0–3
/// are the boundary, 4–7 the interior.
pub(super) fn patch(dx: f64) -> Mesh {
    let nodes = [
        [0.0, 0.0],
        [0.24, 0.0],
        [0.24, 0.12],
        [0.0, 0.12],
        [0.04, 0.02],
        [0.18, 0.03],
        [0.16, 0.08],
        [0.08, 0.08],
    ];
    Mesh {
        nodes: nodes.iter().map(|p| [p[0] + dx, p[1]]).collect(),
        elements: vec![[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7], [4, 5, 6, 7]],
    }
}
