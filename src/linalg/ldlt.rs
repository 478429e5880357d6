//! Sparse `LDLᵀ` factorisation (faer's supernodal Cholesky) for tangents that are
//! symmetric: frictionless contact on hyperelastic bodies (the large-model punch, Hertz).
//!
//! Ordering: faer's approximate minimum degree (AMD), and, where the mesh nodes are known,
//! the geometric nested dissection of [`super::dissection`]; both are analysed and the one
//! whose factorisation costs fewer flops is kept ([`factor_flops`]). Nested dissection wins
//! on 3D meshes, where minimum degree fills far more (docs/large-models.md).
//!
//! A symmetric tangent needs half the storage and about half the flops of an LU of the same
//! ordering, and AMD on the symmetric pattern fills less than the COLAMD ordering faer's LU
//! is restricted to (docs/large-models.md: 8.1 against 12.4 × nnz(A) at 1e5 unknowns). The
//! plan is chosen only for a structurally symmetric pattern, and each factorisation first
//! checks the values: an entry differing from its mirror by more than
//! [`SYMMETRY_TOLERANCE`] (friction, a slip tangent) means the LU is used. `LDLᵀ` pivots on
//! the diagonal only, so a solve whose normwise backward error exceeds
//! [`BACKWARD_ERROR_LIMIT`] (an indefinite iterate with a tiny pivot) or a zero pivot is
//! reported as a failure and the caller repeats it with the LU.

use super::aggregation::MeshNodes;
use super::dissection::nested_dissection;
use super::inertia::Inertia;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLdltRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, LdltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

/// Largest relative difference `|a_ij − a_ji| ≤ tol · max(|a_ij|, |a_ji|)` (plus an absolute
/// floor of `tol · max|a|`) accepted as symmetric. The element and frictionless contact
/// kernels produce symmetric blocks to round-off.
pub const SYMMETRY_TOLERANCE: f64 = 1e-12;

/// Largest normwise backward error `‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞)` accepted from the
/// factorisation (an LU with partial pivoting reaches ~1e-16 here).
pub const BACKWARD_ERROR_LIMIT: f64 = 1e-10;

/// Why a symmetric solve was not made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LdltFailure {
    /// The values are not symmetric to [`SYMMETRY_TOLERANCE`].
    Unsymmetric,
    /// A pivot was exactly zero.
    ZeroPivot,
    /// The solve's backward error exceeded [`BACKWARD_ERROR_LIMIT`] (the value).
    Inaccurate(f64),
}

/// Counts of the symmetric factorisations of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LdltStats {
    /// Patterns for which an `LDLᵀ` plan was made (symbolic analyses).
    pub plans: usize,
    /// Solves made with `LDLᵀ`.
    pub solves: usize,
    /// Stored values of the last plan's factor.
    pub factor_nnz: usize,
    /// Solves that fell back to the LU (each retires its plan).
    pub fallbacks: usize,
    /// Why the last fallback happened.
    pub last_failure: Option<LdltFailure>,
    /// The ordering of the last plan.
    pub ordering: Option<Ordering>,
    /// Flops of one factorisation with the last plan's ordering, and with the other one
    /// analysed (when one was).
    pub flops: (f64, Option<f64>),
}

/// The fill-reducing ordering of an `LDLᵀ` plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordering {
    /// faer's approximate minimum degree.
    MinimumDegree,
    /// Geometric nested dissection of the mesh ([`super::dissection`]).
    NestedDissection,
}

impl Ordering {
    pub fn name(self) -> &'static str {
        match self {
            Ordering::MinimumDegree => "minimum degree",
            Ordering::NestedDissection => "nested dissection",
        }
    }
}

/// The symmetric factorisation of one pattern: mirror map, AMD-ordered symbolic analysis and
/// the numeric storage, kept across factorisations (no allocation per solve).
pub struct LdltPlan {
    /// `(k, k_mirror)` for each strictly-upper stored entry.
    mirror: Vec<(usize, usize)>,
    symbolic: SymbolicCholesky<usize>,
    /// The ordering kept, its flops per factorisation and those of the other one analysed.
    pub ordering: Ordering,
    pub flops: (f64, Option<f64>),
    factored: bool,
    l_values: Vec<f64>,
    scratch: MemBuffer,
    x: Vec<f64>,
    /// Work space of [`backward_error`].
    work: (Vec<f64>, Vec<f64>),
}

impl LdltPlan {
    /// The plan of a pattern, or `None` when the pattern is not structurally symmetric, the
    /// first `values` are not symmetric (no symbolic analysis is made then) or faer's
    /// symbolic analysis fails. With the mesh `nodes`, the cheaper of minimum degree and
    /// nested dissection is kept.
    pub fn new(
        n: usize,
        col_ptr: &[usize],
        row_idx: &[usize],
        values: &[f64],
        nodes: Option<&MeshNodes>,
        par: Par,
    ) -> Option<Self> {
        let mirror = mirror_map(n, col_ptr, row_idx)?;
        if !symmetric(&mirror, values) {
            return None;
        }
        let sym = SymbolicSparseColMatRef::new_checked(n, n, col_ptr, None, row_idx);
        let (ordering, symbolic, flops) = cheapest_analysis(sym, nodes)?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_ldlt_scratch::<f64>(par, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, par),
        ]);
        let scratch = MemBuffer::try_new(req).ok()?;
        let l_values = vec![0.0; symbolic.len_val()];
        Some(LdltPlan {
            mirror,
            symbolic,
            ordering,
            flops,
            factored: false,
            l_values,
            scratch,
            x: vec![0.0; n],
            work: (vec![0.0; n], vec![0.0; n]),
        })
    }

    /// Whether a factorisation has been made (the factor holds an earlier tangent's).
    pub fn factored(&self) -> bool {
        self.factored
    }

    /// `x ← (L D Lᵀ)⁻¹ x` with the last factorisation, no check (a preconditioner).
    pub fn precondition(&mut self, x: &mut [f64], par: Par) {
        let n = x.len();
        LdltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(x, n, 1),
            par,
            MemStack::new(&mut self.scratch),
        );
    }

    /// The inertia of the last factorisation: the negative entries of `D`
    /// ([`Inertia::from_pivots`]; the diagonal of each column of a simplicial factor, of each
    /// supernode's diagonal block of a supernodal one).
    pub fn inertia(&self) -> Inertia {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let col_ptr = s.col_ptr();
                let values = &self.l_values;
                Inertia::from_pivots((0..s.ncols()).map(move |j| values[col_ptr[j]]))
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let factor = SupernodalLdltRef::new(s, &self.l_values);
                Inertia::from_pivots((0..s.n_supernodes()).flat_map(move |k| {
                    let block = factor.supernode(k).val();
                    (0..block.ncols()).map(move |j| block[(j, j)])
                }))
            }
        }
    }

    /// Whether the factor is supernodal (faer chooses by the pattern).
    #[cfg(test)]
    pub fn is_supernodal(&self) -> bool {
        matches!(self.symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_))
    }

    /// Number of stored values of the factor `L` (and `D`).
    pub fn factor_nnz(&self) -> usize {
        self.l_values.len()
    }

    /// Factorise `A` (pattern `sym`, values `values`, read from its upper triangle); refuses
    /// values that are not symmetric.
    pub fn factorize(
        &mut self,
        sym: SymbolicSparseColMatRef<'_, usize>,
        values: &[f64],
        par: Par,
    ) -> Result<(), LdltFailure> {
        if !symmetric(&self.mirror, values) {
            return Err(LdltFailure::Unsymmetric);
        }
        let a = SparseColMatRef::new(sym, values);
        self.symbolic
            .factorize_numeric_ldlt(
                &mut self.l_values,
                a,
                Side::Upper,
                LdltRegularization::default(),
                par,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|_| LdltFailure::ZeroPivot)?;
        self.factored = true;
        Ok(())
    }

    /// Solve `A x = b` in place with the last factorisation of `A` (pattern `sym`, values
    /// `values`), checking the solution's backward error; `b` is left as it was on failure.
    pub fn solve(
        &mut self,
        sym: SymbolicSparseColMatRef<'_, usize>,
        values: &[f64],
        b: &mut [f64],
        par: Par,
    ) -> Result<(), LdltFailure> {
        self.x.copy_from_slice(b);
        let n = self.x.len();
        LdltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(&mut self.x, n, 1),
            par,
            MemStack::new(&mut self.scratch),
        );
        let (r, row_sum) = &mut self.work;
        let eta = backward_error(sym, values, &self.x, b, r, row_sum);
        if eta.is_nan() || eta > BACKWARD_ERROR_LIMIT {
            return Err(LdltFailure::Inaccurate(eta));
        }
        b.copy_from_slice(&self.x);
        Ok(())
    }
}

/// Flops of one factorisation with the ordering kept, and with the other one analysed.
type Flops = (f64, Option<f64>);

/// The symbolic analysis of `sym` by minimum degree and, with `nodes`, by nested
/// dissection: the one of fewer flops, its ordering and flops, and the other's flops.
fn cheapest_analysis(
    sym: SymbolicSparseColMatRef<'_, usize>,
    nodes: Option<&MeshNodes>,
) -> Option<(Ordering, SymbolicCholesky<usize>, Flops)> {
    let analyse = |ordering: SymmetricOrdering<'_, usize>| {
        factorize_symbolic_cholesky(sym, Side::Upper, ordering, Default::default()).ok()
    };
    let amd = analyse(SymmetricOrdering::Amd);
    let nd = nodes.and_then(|nodes| {
        let n = sym.nrows();
        let forward = nested_dissection(n, sym.col_ptr(), sym.row_idx(), nodes);
        let mut inverse = vec![0; n];
        for (k, &i) in forward.iter().enumerate() {
            inverse[i] = k;
        }
        analyse(SymmetricOrdering::Custom(PermRef::new_checked(&forward, &inverse, n)))
    });
    match (amd, nd) {
        (Some(a), Some(d)) => {
            let (fa, fd) = (factor_flops(&a), factor_flops(&d));
            Some(match fd < fa {
                true => (Ordering::NestedDissection, d, (fd, Some(fa))),
                false => (Ordering::MinimumDegree, a, (fa, Some(fd))),
            })
        }
        (Some(a), None) => {
            let f = factor_flops(&a);
            Some((Ordering::MinimumDegree, a, (f, None)))
        }
        (None, Some(d)) => {
            let f = factor_flops(&d);
            Some((Ordering::NestedDissection, d, (f, None)))
        }
        (None, None) => None,
    }
}

/// Flops of one numeric factorisation with the symbolic analysis `s`: `Σ_j m_j²` over the
/// columns `j` of `L`, `m_j` the entries below the diagonal (each column's update of the
/// trailing matrix costs `m_j (m_j + 1)` multiply-adds; Duff, Erisman & Reid, *Direct
/// Methods for Sparse Matrices*, §10.2).
pub fn factor_flops(s: &SymbolicCholesky<usize>) -> f64 {
    let sq = |m: usize| (m as f64) * (m as f64);
    match s.raw() {
        SymbolicCholeskyRaw::Simplicial(l) => {
            let cp = l.col_ptr();
            (0..l.ncols()).map(|j| sq((cp[j + 1] - cp[j]).saturating_sub(1))).sum()
        }
        SymbolicCholeskyRaw::Supernodal(l) => {
            let (begin, end, rows) = (l.supernode_begin(), l.supernode_end(), l.col_ptr_for_row_idx());
            let mut flops = 0.0;
            for s in 0..l.n_supernodes() {
                let (width, below) = (end[s] - begin[s], rows[s + 1] - rows[s]);
                flops += (0..width).map(|t| sq(width - t - 1 + below)).sum::<f64>();
            }
            flops
        }
    }
}

/// Whether `values` are symmetric to [`SYMMETRY_TOLERANCE`] over the `mirror` pairs.
pub fn symmetric(mirror: &[(usize, usize)], values: &[f64]) -> bool {
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let floor = SYMMETRY_TOLERANCE * scale;
    mirror.iter().all(|&(k, m)| {
        let (a, b) = (values[k], values[m]);
        (a - b).abs() <= SYMMETRY_TOLERANCE * a.abs().max(b.abs()) + floor
    })
}

/// For each strictly-upper entry `k = (r, c)`, `r < c`, the position of `(c, r)`; `None` when
/// one is missing (rows sorted within each column).
pub fn mirror_map(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> Option<Vec<(usize, usize)>> {
    let mut mirror = Vec::with_capacity(row_idx.len() / 2);
    for c in 0..n {
        for k in col_ptr[c]..col_ptr[c + 1] {
            let r = row_idx[k];
            if r >= c {
                continue;
            }
            let col_r = &row_idx[col_ptr[r]..col_ptr[r + 1]];
            let m = col_ptr[r] + col_r.binary_search(&c).ok()?;
            mirror.push((k, m));
        }
    }
    // every strictly-lower entry is some upper entry's mirror iff the counts agree
    let lower = (0..n)
        .map(|c| row_idx[col_ptr[c]..col_ptr[c + 1]].iter().filter(|&&r| r > c).count())
        .sum::<usize>();
    (lower == mirror.len()).then_some(mirror)
}

/// Normwise backward error `‖b − A x‖∞ / (‖A‖∞ ‖x‖∞ + ‖b‖∞)` of a solution `x` (Rigal and
/// Gaches; Higham, *Accuracy and Stability of Numerical Algorithms*, eq. 7.23), `A` stored
/// whole (both triangles); `r` and `row_sum` are work space of length `n`.
pub fn backward_error(
    sym: SymbolicSparseColMatRef<'_, usize>,
    values: &[f64],
    x: &[f64],
    b: &[f64],
    r: &mut [f64],
    row_sum: &mut [f64],
) -> f64 {
    let n = x.len();
    r.copy_from_slice(b);
    row_sum.fill(0.0);
    let (col_ptr, row_idx) = (sym.col_ptr(), sym.row_idx());
    for c in 0..n {
        for k in col_ptr[c]..col_ptr[c + 1] {
            let i = row_idx[k];
            r[i] -= values[k] * x[c];
            row_sum[i] += values[k].abs();
        }
    }
    let norm = |v: &[f64]| v.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    let denominator = norm(row_sum) * norm(x) + norm(b);
    if denominator == 0.0 {
        return 0.0;
    }
    norm(r) / denominator
}
