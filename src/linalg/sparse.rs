//! Global sparse matrix in compressed-column form: the pattern is built once (and only grows
//! when contact couples new DOFs), values are refilled each iteration. The matrix holds the
//! pattern and the values only; the factorisations of a pattern, and the choice among them,
//! belong to [`super::chooser::LinearSolve`], which sees a new pattern by its
//! [`SparseMatrix::generation`].

use faer::sparse::{SymbolicSparseColMat, SymbolicSparseColMatRef};

/// Square sparse matrix with a fixed pattern.
pub struct SparseMatrix {
    pub n: usize,
    /// Row indices per column, sorted.
    cols: Vec<Vec<usize>>,
    pub(crate) col_ptr: Vec<usize>,
    pub(crate) row_idx: Vec<usize>,
    pub values: Vec<f64>,
    /// The pattern in faer's form (rebuilt with the pattern).
    symbolic: SymbolicSparseColMat<usize>,
    /// Counts the patterns this matrix has had (a factorisation is valid for one).
    generation: u64,
    /// The pattern given at construction (the elements'), which [`Self::extend`] grows.
    base: Vec<Vec<usize>>,
    /// Per stored entry: not in `base` (added by [`Self::extend`]).
    extension: Vec<bool>,
    /// The pattern holds entries beyond `base`.
    extended: bool,
    /// An extension entry was written by [`Self::add_to`] since the last
    /// [`Self::shrink_unused_extension`].
    extension_used: bool,
}

impl SparseMatrix {
    /// Pattern from a list of coupled index groups (each group couples all its members).
    pub fn new(n: usize, groups: &mut dyn Iterator<Item = Vec<usize>>) -> Self {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (i, c) in cols.iter_mut().enumerate() {
            c.push(i); // keep the diagonal even for DOFs nothing touches
        }
        for g in groups {
            for &c in &g {
                for &r in &g {
                    cols[c].push(r);
                }
            }
        }
        let mut m = SparseMatrix {
            n,
            base: Vec::new(),
            extension: Vec::new(),
            extended: false,
            extension_used: false,
            cols,
            col_ptr: Vec::new(),
            row_idx: Vec::new(),
            values: Vec::new(),
            symbolic: SymbolicSparseColMat::new_checked(0, 0, vec![0], None, Vec::new()),
            generation: 0,
        };
        m.compress();
        m.base = m.cols.clone();
        m.extension = vec![false; m.row_idx.len()];
        m
    }

    fn compress(&mut self) {
        self.col_ptr.clear();
        self.row_idx.clear();
        self.col_ptr.push(0);
        for c in &mut self.cols {
            c.sort_unstable();
            c.dedup();
            self.row_idx.extend_from_slice(c);
            self.col_ptr.push(self.row_idx.len());
        }
        self.values = vec![0.0; self.row_idx.len()];
        self.symbolic =
            SymbolicSparseColMat::new_checked(self.n, self.n, self.col_ptr.clone(), None, self.row_idx.clone());
        self.generation += 1;
    }

    /// The pattern's number: it changes whenever the pattern does (and the values are reset).
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The pattern in faer's form.
    pub fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        self.symbolic.as_ref()
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry `(r, c)` in `values`, if it is in the pattern.
    #[inline]
    pub fn index(&self, r: usize, c: usize) -> Option<usize> {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        s.binary_search(&r).ok().map(|k| self.col_ptr[c] + k)
    }

    /// Add entries to the pattern; returns whether it changed (values are reset then).
    pub fn extend(&mut self, entries: &[(usize, usize)]) -> bool {
        let mut changed = false;
        for &(r, c) in entries {
            if self.index(r, c).is_none() {
                self.cols[c].push(r);
                changed = true;
            }
        }
        if changed {
            self.compress();
            self.extension = (0..self.n)
                .flat_map(|c| {
                    self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]]
                        .iter()
                        .map(move |&r| (r, c))
                })
                .map(|(r, c)| self.base[c].binary_search(&r).is_err())
                .collect();
            self.extended = true;
            self.extension_used = true;
        }
        changed
    }

    /// `values[slot] += v`, noting whether the entry is one of [`Self::extend`]'s.
    #[inline]
    pub fn add_to(&mut self, slot: usize, v: f64) {
        self.values[slot] += v;
        self.extension_used |= self.extension[slot];
    }

    /// Drop the entries [`Self::extend`] added when none was written by [`Self::add_to`]
    /// since the last call, if the banded factorisation is in use (`banded`; its band is set by the
    /// widest entry). Contact couples the nodes of a point's last segment with those of its
    /// current one only in the increments where it crosses from one to the other (seed eqs.
    /// 2–4): kept, those entries would widen the band of a 120×4 strip from 13 to 23 for
    /// the rest of the run. Returns whether the pattern changed (the values are reset then,
    /// and the caller must recompute its slots). The general sparse LU keeps its pattern (a
    /// new symbolic analysis of a large model costs more than the fill it saves).
    pub fn shrink_unused_extension(&mut self, banded: bool) -> bool {
        let unused = !std::mem::take(&mut self.extension_used);
        if !unused || !banded || !self.extended {
            return false;
        }
        self.cols.clone_from(&self.base);
        self.compress();
        self.extension = vec![false; self.row_idx.len()];
        self.extended = false;
        true
    }

    pub fn clear_values(&mut self) {
        self.values.fill(0.0);
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for (c, xc) in x.iter().enumerate().take(self.n) {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[k]] += self.values[k] * xc;
            }
        }
    }
}

/// Sort `v[start..]` and drop its repeats (the neighbour list of one vertex being built at
/// the end of a flat adjacency list).
pub(crate) fn sort_dedup_tail<T: Ord + Copy>(v: &mut Vec<T>, start: usize) {
    v[start..].sort_unstable();
    let mut kept = start;
    for k in start..v.len() {
        if k == start || v[k] != v[kept - 1] {
            v[kept] = v[k];
            kept += 1;
        }
    }
    v.truncate(kept);
}
