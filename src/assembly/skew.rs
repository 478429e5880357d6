//! Skew supports: a node's displacement prescribed along a unit direction `n` only,
//! `g(u) = u_I · n − v(t) = 0`, the component along `t = (−n_y, n_x)` free.
//!
//! The classical transformation method: the node's two DOFs keep their free equations
//! `(a, b)` (so the solver's displacement updates stay one-to-one on global DOFs), and the
//! assembler works in the node's local frame `R = [n t]` on them:
//!
//! - the free residual at `(a, b)` is `F = c g n + (t · r) t`, `r` the node's global residual
//!   and `c` a stiffness scale (Young's modulus of the node's body, so that `c g` is a force):
//!   the constraint's residual along `n`, equilibrium along `t`. Its norm is that of the local
//!   vector `(c g, t · r)`;
//! - the tangent becomes `Tᵀ K T` (`T` the identity but for the node's block `R`), whose row
//!   and column `a` (the local `n`) are then replaced by `c` on the diagonal: the constraint's
//!   linearisation `c Δu_n = −c g`, eliminated symmetrically — the column is kept and moved
//!   to the right-hand side in [`Skew::solve`] (`b_i −= K_in Δu_n`);
//! - the solution is turned back to global components, `Δu_I = R Δu_L`.
//!
//! After a full Newton step the linear constraint holds exactly. The reaction along `n` is
//! `n · r` (the node's DOFs are listed with the prescribed ones, so that sums of reactions
//! include it).

use crate::linalg::sparse::SparseMatrix;
use crate::model::Model;

/// One skew-supported node in the free equations.
#[derive(Debug, Clone)]
pub struct SkewDof {
    pub node: usize,
    /// The unit direction `n` of the prescribed displacement.
    pub n: [f64; 2],
    /// Free equations of the node's x and y DOFs (local `n` and `t` once turned).
    pub eqs: [usize; 2],
    /// Index into [`Model::skew`].
    pub spec: usize,
    /// Stiffness scale `c` of the constraint row (Young's modulus of the node's body).
    pub scale: f64,
}

impl SkewDof {
    fn t(&self) -> [f64; 2] {
        [-self.n[1], self.n[0]]
    }
}

/// The skew supports of a model and what the last assembly left for the solve.
#[derive(Debug, Clone, Default)]
pub struct Skew {
    pub dofs: Vec<SkewDof>,
    /// `g = u · n − v(t)` per skew node at the last assembly.
    gap: Vec<f64>,
    /// Per skew node: the column `K_in` (local frame, `i` not a constrained row) of the last
    /// tangent, taken out of the matrix by the elimination.
    columns: Vec<Vec<(usize, f64)>>,
    /// Per free equation: the local-`n` row of a skew node (replaced by the constraint).
    constrained: Vec<bool>,
    /// Per global DOF: of a skew node.
    turned: Vec<bool>,
}

/// Young's modulus of the body that holds `node`.
fn young_of(model: &Model, node: usize) -> f64 {
    let body = model
        .bodies
        .iter()
        .find(|b| (b.first_node..b.first_node + b.node_count).contains(&node));
    match body.map(|b| b.material) {
        Some(
            crate::element::material::Material::SaintVenantKirchhoff { lambda, mu }
            | crate::element::material::Material::NeoHookean { lambda, mu },
        ) => mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu),
        None => 1.0,
    }
}

impl Skew {
    /// The skew nodes of `model` with the free equations `eq` of their DOFs (both free).
    pub fn new(model: &Model, eq: &[Option<usize>], n_free: usize) -> Self {
        let mut constrained = vec![false; n_free];
        let mut turned = vec![false; eq.len()];
        let dofs: Vec<SkewDof> = model
            .skew
            .iter()
            .enumerate()
            .map(|(spec, s)| {
                let eqs = [2 * s.node, 2 * s.node + 1].map(|d| eq[d].expect("a skew node's DOFs are free"));
                constrained[eqs[0]] = true;
                turned[2 * s.node] = true;
                turned[2 * s.node + 1] = true;
                SkewDof {
                    node: s.node,
                    n: s.direction,
                    eqs,
                    spec,
                    scale: young_of(model, s.node),
                }
            })
            .collect();
        Skew {
            gap: vec![0.0; dofs.len()],
            columns: vec![Vec::new(); dofs.len()],
            dofs,
            constrained,
            turned,
        }
    }

    /// Whether global DOF `d` is one of a skew node's.
    pub fn turns(&self, d: usize) -> bool {
        self.turned.get(d).copied().unwrap_or(false)
    }

    pub fn is_empty(&self) -> bool {
        self.dofs.is_empty()
    }

    /// The constraint residuals `g = u_I · n − v(t)` at displacements `u`, time `t`.
    pub fn update_gaps(&mut self, model: &Model, u: &[f64], t: f64) {
        for (g, s) in self.gap.iter_mut().zip(&self.dofs) {
            let ui = [u[2 * s.node], u[2 * s.node + 1]];
            *g = ui[0] * s.n[0] + ui[1] * s.n[1] - model.skew[s.spec].ramp.at(t);
        }
    }

    /// The free residual `F = c g n + (t · r) t` of skew node `k` from its global residual
    /// `r` (global components).
    pub fn residual(&self, k: usize, r: [f64; 2]) -> [f64; 2] {
        let s = &self.dofs[k];
        let t = s.t();
        let (cg, rt) = (s.scale * self.gap[k], t[0] * r[0] + t[1] * r[1]);
        [cg * s.n[0] + rt * t[0], cg * s.n[1] + rt * t[1]]
    }

    /// Turn the tangent into the skew nodes' local frames (`Tᵀ K T`) and eliminate their
    /// constraint rows and columns (diagonal `c`), keeping the columns for [`Self::solve`].
    /// The pattern is symmetric (element and contact blocks couple all DOFs of their nodes),
    /// so the columns of row `a` are the rows of column `a`, and those of `b` the same.
    pub fn transform(&mut self, m: &mut SparseMatrix) {
        let rows = |m: &SparseMatrix, c: usize| m.row_idx[m.col_ptr[c]..m.col_ptr[c + 1]].to_vec();
        for s in &self.dofs {
            let ([a, b], n, t) = (s.eqs, s.n, s.t());
            // columns: K R
            for i in rows(m, a) {
                let (sa, sb) = (slot(m, i, a), slot(m, i, b));
                let (ka, kb) = (m.values[sa], m.values[sb]);
                m.values[sa] = ka * n[0] + kb * n[1];
                m.values[sb] = ka * t[0] + kb * t[1];
            }
            // rows: Rᵀ (K R)
            for j in rows(m, a) {
                let (sa, sb) = (slot(m, a, j), slot(m, b, j));
                let (ka, kb) = (m.values[sa], m.values[sb]);
                m.values[sa] = n[0] * ka + n[1] * kb;
                m.values[sb] = t[0] * ka + t[1] * kb;
            }
        }
        for (k, s) in self.dofs.iter().enumerate() {
            let a = s.eqs[0];
            self.columns[k].clear();
            for i in rows(m, a) {
                if i == a {
                    continue;
                }
                let (col, row) = (slot(m, i, a), slot(m, a, i));
                if !self.constrained[i] {
                    self.columns[k].push((i, m.values[col]));
                }
                m.values[col] = 0.0;
                m.values[row] = 0.0;
            }
            let d = slot(m, a, a);
            m.values[d] = s.scale;
        }
    }

    /// Before the solve: the right-hand side `b` (global components at the skew nodes) into
    /// the local frames, and the known `Δu_n = b_a / c` moved to the right (`b_i −= K_in Δu_n`).
    pub fn to_local(&self, b: &mut [f64]) {
        for s in &self.dofs {
            let ([a, bb], n, t) = (s.eqs, s.n, s.t());
            let (x, y) = (b[a], b[bb]);
            b[a] = n[0] * x + n[1] * y;
            b[bb] = t[0] * x + t[1] * y;
        }
        for (s, column) in self.dofs.iter().zip(&self.columns) {
            let du_n = b[s.eqs[0]] / s.scale;
            for &(i, k) in column {
                b[i] -= k * du_n;
            }
        }
    }

    /// After the solve: the local solution at the skew nodes back to global components
    /// (`Δu_I = n Δu_n + t Δu_t`).
    pub fn to_global(&self, x: &mut [f64]) {
        for s in &self.dofs {
            let ([a, b], n, t) = (s.eqs, s.n, s.t());
            let (un, ut) = (x[a], x[b]);
            x[a] = n[0] * un + t[0] * ut;
            x[b] = n[1] * un + t[1] * ut;
        }
    }
}

fn slot(m: &SparseMatrix, r: usize, c: usize) -> usize {
    m.index(r, c).expect("the pattern couples both DOFs of a node alike")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3×3 symmetric system whose DOFs 0, 1 are a skew node along `n`: the eliminated,
    /// turned solve gives `Δu · n = −g` and equilibrium along `t` (checked against the dense
    /// constrained solution by hand, to 1e-12).
    #[test]
    fn eliminated_solve_meets_the_constraint_and_equilibrium_along_t() {
        let groups = vec![vec![0usize, 1, 2]];
        let mut m = SparseMatrix::new(3, &mut groups.into_iter());
        let k = [[4.0, 1.0, -1.0], [1.0, 3.0, 0.5], [-1.0, 0.5, 2.0]];
        for (c, col) in k.iter().enumerate() {
            for (r, v) in col.iter().enumerate() {
                let s = m.index(r, c).unwrap();
                m.values[s] = *v;
            }
        }
        let a = std::f64::consts::FRAC_PI_6;
        let n = [a.cos(), a.sin()];
        let mut sk = Skew {
            dofs: vec![SkewDof {
                node: 0,
                n,
                eqs: [0, 1],
                spec: 0,
                scale: 7.0,
            }],
            gap: vec![0.2],
            columns: vec![Vec::new()],
            constrained: vec![true, false, false],
            turned: vec![true, true, false],
        };
        let r = [0.3, -0.1, 0.4];
        let f = sk.residual(0, [r[0], r[1]]);
        let mut b = vec![-f[0], -f[1], -r[2]];
        sk.transform(&mut m);
        sk.to_local(&mut b);
        // dense solve of the reduced 3×3 (the matrix is small)
        let mut dense = [[0.0; 3]; 3];
        for (c, col) in dense.iter_mut().enumerate() {
            for (rr, v) in col.iter_mut().enumerate() {
                *v = m.values[m.index(rr, c).unwrap()];
            }
        }
        let x = solve3(dense, [b[0], b[1], b[2]]);
        let mut du = x.to_vec();
        sk.to_global(&mut du);
        let t = [-n[1], n[0]];
        assert!((du[0] * n[0] + du[1] * n[1] + 0.2).abs() < 1e-12);
        // linearised equilibrium along t and at DOF 2: t · (r + K du) = 0, r_2 + (K du)_2 = 0
        let kdu: Vec<f64> = (0..3).map(|i| (0..3).map(|j| k[j][i] * du[j]).sum()).collect();
        assert!((t[0] * (r[0] + kdu[0]) + t[1] * (r[1] + kdu[1])).abs() < 1e-12);
        assert!((r[2] + kdu[2]).abs() < 1e-12);
    }

    /// `dense[c][r]` column-major; Cramer's rule.
    fn solve3(d: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
        let a = |r: usize, c: usize| d[c][r];
        let det = |m: &dyn Fn(usize, usize) -> f64| {
            m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
                + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
        };
        let d0 = det(&a);
        let mut x = [0.0; 3];
        for (k, xk) in x.iter_mut().enumerate() {
            let m = |r: usize, c: usize| if c == k { b[r] } else { a(r, c) };
            *xk = det(&m) / d0;
        }
        x
    }
}
