//! Banded LU with partial pivoting after a reverse Cuthill–McKee ordering: the direct solver
//! for thin meshes (a strip a few elements thick), where a general sparse LU spends more
//! time in its bookkeeping than in arithmetic.
//!
//! The pattern (symmetric, as the assembler builds it) is renumbered by reverse
//! Cuthill–McKee (George & Liu, *Computer Solution of Large Sparse Positive Definite
//! Systems*, 1981, §4.3), which gives half-bandwidth `w ≈ 2·(nodes across + 1)` on a strip
//! meshed along its length. The permuted matrix `P A Pᵀ` is factorised as in LAPACK's
//! `dgbtf2` (row interchanges within the band; `U` has upper bandwidth `2w`), about
//! `2 n w (2w)` flops, and solved as `dgbtrs`. [`SparseMatrix`](super::sparse::SparseMatrix)
//! uses it when the band is narrow (see [`BandLu::worth_it`]) and faer's sparse LU otherwise.
//!
//! No crate in the dependency tree offers a banded LU (faer's sparse LU is general; LAPACK
//! bindings would add a system library), hence this short, tested implementation.

/// A singular (or numerically singular) pivot.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("zero pivot in column {0} of the banded LU (singular matrix)")]
pub struct ZeroPivot(pub usize);

/// Where Cuthill–McKee starts in each connected component.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Root {
    /// A pseudo-peripheral node (the classic choice).
    Node,
    /// The whole deepest level of the breadth-first search from a pseudo-peripheral node,
    /// e.g. the far end of a strip across its width: the levels then run straight across
    /// the strip instead of spreading as squares from a corner node, whose first levels
    /// hold a short edge and a long one and set the bandwidth of the whole strip.
    FarLevel,
}

/// Reverse Cuthill–McKee order of a symmetric pattern given by CSC `col_ptr`/`row_idx`:
/// returns `perm` with `perm[new] = old`. Each connected component starts from a
/// pseudo-peripheral node (repeated breadth-first searches from a minimum-degree node), or
/// from the deepest level seen from it (see [`Root`]).
pub fn reverse_cuthill_mckee(n: usize, col_ptr: &[usize], row_idx: &[usize], root: Root) -> Vec<usize> {
    let mut rcm = Rcm::new(n, col_ptr, row_idx);
    while rcm.order.len() < n {
        let s = rcm.pseudo_peripheral();
        let first = rcm.order.len();
        if root == Root::FarLevel {
            rcm.place_far_level(s);
        } else {
            rcm.order.push(s);
            rcm.placed[s] = true;
        }
        rcm.cuthill_mckee(first);
    }
    rcm.order.reverse();
    rcm.order
}

/// The working state of [`reverse_cuthill_mckee`]: the pattern, the degrees, the order so
/// far, and the scratch of the breadth-first searches (`level` is `usize::MAX` outside a
/// search).
struct Rcm<'a> {
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
    degree: Vec<usize>,
    placed: Vec<bool>,
    order: Vec<usize>,
    level: Vec<usize>,
    queue: Vec<usize>,
}

impl<'a> Rcm<'a> {
    fn new(n: usize, col_ptr: &'a [usize], row_idx: &'a [usize]) -> Self {
        let mut rcm = Rcm {
            col_ptr,
            row_idx,
            degree: Vec::new(),
            placed: vec![false; n],
            order: Vec::with_capacity(n),
            level: vec![usize::MAX; n],
            queue: Vec::with_capacity(n),
        };
        rcm.degree = (0..n).map(|v| rcm.adj(v).count()).collect();
        rcm
    }

    /// The neighbours of `v` (itself left out).
    fn adj(&self, v: usize) -> impl Iterator<Item = usize> + 'a {
        let row_idx: &'a [usize] = self.row_idx;
        row_idx[self.col_ptr[v]..self.col_ptr[v + 1]]
            .iter()
            .copied()
            .filter(move |&w| w != v)
    }

    /// Breadth-first levels from `s` within the unplaced nodes, leaving the search in
    /// `queue`: the lowest-degree node of the deepest level, and that depth.
    fn bfs(&mut self, s: usize) -> (usize, usize) {
        self.queue.clear();
        self.queue.push(s);
        self.level[s] = 0;
        let mut head = 0;
        while head < self.queue.len() {
            let v = self.queue[head];
            head += 1;
            for w in self.adj(v) {
                if !self.placed[w] && self.level[w] == usize::MAX {
                    self.level[w] = self.level[v] + 1;
                    self.queue.push(w);
                }
            }
        }
        let deepest = self.level[*self.queue.last().expect("s")];
        let last = (self.queue.iter().copied())
            .filter(|&v| self.level[v] == deepest)
            .min_by_key(|&v| self.degree[v])
            .expect("non-empty");
        for &v in self.queue.iter() {
            self.level[v] = usize::MAX;
        }
        (last, deepest)
    }

    /// A pseudo-peripheral node of the unplaced component of a minimum-degree node: move to
    /// the far end while the eccentricity grows (at most 8 searches).
    fn pseudo_peripheral(&mut self) -> usize {
        let start = (0..self.placed.len())
            .filter(|&v| !self.placed[v])
            .min_by_key(|&v| self.degree[v])
            .expect("a node left");
        let (mut far, mut depth) = self.bfs(start);
        let mut s = start;
        for _ in 0..8 {
            let (far2, d2) = self.bfs(far);
            s = far;
            if d2 <= depth {
                break;
            }
            far = far2;
            depth = d2;
        }
        s
    }

    /// Place the deepest level of the search from `s` ([`Root::FarLevel`]), in its own
    /// breadth-first order along it from its lowest-degree end, so that the next levels keep
    /// its order.
    fn place_far_level(&mut self, s: usize) {
        let (_, far_depth) = self.bfs(s);
        // `queue` still lists the search from s, in breadth-first order: its tail is the
        // deepest level (recompute the levels, which `bfs` reset)
        let mut depth_of = vec![0usize; self.queue.len()];
        for (k, &v) in self.queue.iter().enumerate() {
            self.level[v] = k;
        }
        for k in 1..self.queue.len() {
            let v = self.queue[k];
            depth_of[k] = (self.adj(v))
                .filter(|&w| self.level[w] < k)
                .map(|w| depth_of[self.level[w]] + 1)
                .min()
                .unwrap_or(0);
        }
        let mut far: Vec<usize> = (self.queue.iter().zip(&depth_of))
            .filter(|(_, &d)| d == far_depth)
            .map(|(&v, _)| v)
            .collect();
        for &v in self.queue.iter() {
            self.level[v] = usize::MAX;
        }
        far.sort_unstable_by_key(|&w| (self.degree[w], w));
        for &v in &far {
            self.level[v] = 0;
        }
        for &start in &far {
            if self.placed[start] {
                continue;
            }
            let mut head = self.order.len();
            self.order.push(start);
            self.placed[start] = true;
            while head < self.order.len() {
                let v = self.order[head];
                head += 1;
                let mut along: Vec<usize> = (self.adj(v))
                    .filter(|&w| self.level[w] == 0 && !self.placed[w])
                    .collect();
                along.sort_unstable_by_key(|&w| (self.degree[w], w));
                for w in along {
                    self.placed[w] = true;
                    self.order.push(w);
                }
            }
        }
        for &v in &far {
            self.level[v] = usize::MAX;
        }
    }

    /// Cuthill–McKee from the nodes placed from `order[first]` on: the unplaced neighbours of
    /// each, in order of increasing degree.
    fn cuthill_mckee(&mut self, first: usize) {
        let mut head = first;
        let mut nbrs = Vec::new();
        while head < self.order.len() {
            let v = self.order[head];
            head += 1;
            nbrs.clear();
            nbrs.extend(self.adj(v).filter(|&w| !self.placed[w]));
            nbrs.sort_unstable_by_key(|&w| (self.degree[w], w));
            for &w in &nbrs {
                self.placed[w] = true;
                self.order.push(w);
            }
        }
    }
}

/// Reverse Cuthill–McKee on the *compressed* pattern: unknowns with identical adjacency
/// (the two displacement components of a node, whose columns the elements always fill
/// alike) are merged into one supervariable, the quotient graph is ordered by
/// [`reverse_cuthill_mckee`] and each supervariable expanded in place (its unknowns in
/// ascending order). Returns `perm[new] = old`.
///
/// On the DOF graph itself RCM's breadth-first levels cut across nodes and are about twice
/// as wide as the node levels: the 120×4 strip (5 nodes across) gets half-bandwidth 21–23
/// from plain RCM and 13 from this one, a third of the factorisation's `2 n kl ku` flops.
/// Supervariables are the compressed graph of sparse orderings (Ashcraft, "Compressed graphs
/// and the minimum degree algorithm", SIAM J. Sci. Comput. 16, 1995).
pub fn supervariable_rcm(n: usize, col_ptr: &[usize], row_idx: &[usize], root: Root) -> Vec<usize> {
    let mut group = vec![usize::MAX; n];
    let mut members: Vec<Vec<usize>> = Vec::new();
    let mut seen: std::collections::HashMap<&[usize], usize> = std::collections::HashMap::new();
    for (v, g) in group.iter_mut().enumerate() {
        let pattern = &row_idx[col_ptr[v]..col_ptr[v + 1]];
        let id = *seen.entry(pattern).or_insert_with(|| {
            members.push(Vec::new());
            members.len() - 1
        });
        members[id].push(v);
        *g = id;
    }
    let m = members.len();
    let mut q_ptr = Vec::with_capacity(m + 1);
    let mut q_idx = Vec::new();
    q_ptr.push(0);
    for mem in &members {
        let v = mem[0];
        let start = q_idx.len();
        q_idx.extend(row_idx[col_ptr[v]..col_ptr[v + 1]].iter().map(|&r| group[r]));
        super::sparse::sort_dedup_tail(&mut q_idx, start);
        q_ptr.push(q_idx.len());
    }
    reverse_cuthill_mckee(m, &q_ptr, &q_idx, root)
        .into_iter()
        .flat_map(|g| members[g].iter().copied())
        .collect()
}

/// Half-bandwidths `(kl, ku)` of the pattern `col_ptr`/`row_idx` renumbered by `perm`
/// (`perm[new] = old`).
pub fn band_widths(n: usize, col_ptr: &[usize], row_idx: &[usize], perm: &[usize]) -> (usize, usize) {
    let mut inv = vec![0; n];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    let (mut kl, mut ku) = (0, 0);
    for c in 0..n {
        for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
            let (i, j) = (inv[r], inv[c]);
            kl = kl.max(i.saturating_sub(j));
            ku = ku.max(j.saturating_sub(i));
        }
    }
    (kl, ku)
}

/// LU factors of a band matrix in LAPACK band storage (column `j` holds rows
/// `j − kl − ku ..= j + kl` at offsets `0 ..= 2kl + ku`).
#[derive(Debug, Clone, Default)]
pub struct BandLu {
    pub n: usize,
    pub kl: usize,
    pub ku: usize,
    ab: Vec<f64>,
    ipiv: Vec<usize>,
    /// What the last factorisation's pivots say of the determinant, gathered as it went.
    pivots: PivotSigns,
}

/// The pivots of an LU as the factorisation meets them: the parity of the negative pivots
/// plus row interchanges (the determinant's sign), and the smallest and largest magnitude.
#[derive(Debug, Clone, Copy, Default)]
struct PivotSigns {
    odd: bool,
    min_abs: f64,
    max_abs: f64,
}

impl PivotSigns {
    fn start() -> Self {
        PivotSigns {
            odd: false,
            min_abs: f64::INFINITY,
            max_abs: 0.0,
        }
    }

    #[inline(always)]
    fn add(&mut self, pivot: f64, interchanged: bool) {
        self.odd ^= (pivot < 0.0) ^ interchanged;
        self.min_abs = self.min_abs.min(pivot.abs());
        self.max_abs = self.max_abs.max(pivot.abs());
    }
}

impl BandLu {
    /// Whether a band of half-width `w` on `n` unknowns is cheaper than the general sparse
    /// LU: narrow bands only, and bounded storage. Measured against faer's LU on the
    /// strip-channel meshes, which all take the band: 24×1 7 vs 21 µs per factorisation,
    /// 120×4 0.25 vs 0.64 ms, 240×8 4.1 vs 6.1 ms; the `hertz` block (40×30, square) stays
    /// with faer.
    pub fn worth_it(n: usize, w: usize) -> bool {
        w <= 40 && n.saturating_mul(3 * w + 1) <= 50_000_000
    }

    /// Band storage for `n` unknowns with `kl` sub- and `ku` super-diagonals.
    pub fn new(n: usize, kl: usize, ku: usize) -> Self {
        BandLu {
            n,
            kl,
            ku,
            ab: vec![0.0; n * (2 * kl + ku + 1)],
            ipiv: vec![0; n],
            pivots: PivotSigns::default(),
        }
    }

    fn ld(&self) -> usize {
        2 * self.kl + self.ku + 1
    }

    /// Position of entry `(i, j)` (`j − kl − ku ≤ i ≤ j + kl`) in the storage.
    #[inline]
    pub fn slot(&self, i: usize, j: usize) -> usize {
        j * self.ld() + self.kl + self.ku + i - j
    }

    /// Zero the storage before the matrix is written with [`BandLu::add`].
    pub fn clear(&mut self) {
        self.ab.fill(0.0);
    }

    /// `A[i][j] += v` (inside the band).
    #[inline]
    pub fn add(&mut self, slot: usize, v: f64) {
        self.ab[slot] += v;
    }

    /// Factorise in place (`dgbtf2`): `P A = L U` with row interchanges inside the band
    /// (with AVX2 where the processor has it: [`crate::cpu`]).
    pub fn factorize(&mut self) -> Result<(), ZeroPivot> {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::wide_vectors() {
            // SAFETY: the processor has AVX2 (detected at run time).
            return unsafe { self.factorize_avx2() };
        }
        self.factorize_in_place()
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn factorize_avx2(&mut self) -> Result<(), ZeroPivot> {
        self.factorize_in_place()
    }

    #[inline(always)]
    fn factorize_in_place(&mut self) -> Result<(), ZeroPivot> {
        let (n, kl, ld) = (self.n, self.kl, self.ld());
        let kv = self.kl + self.ku;
        let mut ju = 0;
        self.pivots = PivotSigns::start();
        for j in 0..n {
            let km = kl.min(n - 1 - j);
            let col = j * ld + kv;
            let mut p = 0;
            let mut best = self.ab[col].abs();
            for r in 1..=km {
                let a = self.ab[col + r].abs();
                if a > best {
                    best = a;
                    p = r;
                }
            }
            self.ipiv[j] = j + p;
            if best == 0.0 || !best.is_finite() {
                return Err(ZeroPivot(j));
            }
            ju = ju.max((j + self.ku + p).min(n - 1));
            if p != 0 {
                for c in j..=ju {
                    let base = c * ld + kv;
                    self.ab.swap(base + j - c, base + j + p - c);
                }
            }
            self.pivots.add(self.ab[col], p != 0);
            let inv = 1.0 / self.ab[col];
            for r in 1..=km {
                self.ab[col + r] *= inv;
            }
            // rank-one update of the columns right of j (each column's rows j+1 ..= j+km
            // are contiguous, and lie after column j's multipliers in the storage)
            let (left, right) = self.ab.split_at_mut((j + 1) * ld);
            let l = &left[col + 1..=col + km];
            // the first column right of j starts at `kv − 1` of `right`, each next one
            // `ld − 1` further on
            let update = ColumnUpdate {
                first: kv - 1,
                stride: ld - 1,
                columns: ju - j,
            };
            macro_rules! fixed_heights {
                ($($k:literal)*) => {
                    match km {
                        $($k => update.fixed::<$k>(right, l.try_into().expect("km multipliers")),)*
                        _ => update.any(right, l),
                    }
                };
            }
            fixed_heights!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32 33 34 35 36 37 38 39 40);
        }
        Ok(())
    }

    /// The determinant's sign of the last factorisation
    /// ([`super::inertia::Inertia::from_lu`]), from the pivots gathered while it ran.
    pub fn inertia(&self) -> Option<super::inertia::Inertia> {
        let p = self.pivots;
        super::inertia::Inertia::from_lu(p.odd, (p.min_abs, p.max_abs))
    }

    /// Solve `A x = b` in place with the factors (`dgbtrs`).
    pub fn solve(&self, b: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if crate::cpu::wide_vectors() {
            // SAFETY: the processor has AVX2 (detected at run time).
            return unsafe { self.solve_avx2(b) };
        }
        self.solve_in_place(b)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn solve_avx2(&self, b: &mut [f64]) {
        self.solve_in_place(b)
    }

    #[inline(always)]
    fn solve_in_place(&self, b: &mut [f64]) {
        let (n, kl, ld) = (self.n, self.kl, self.ld());
        let kv = self.kl + self.ku;
        for j in 0..n {
            let p = self.ipiv[j];
            if p != j {
                b.swap(j, p);
            }
            let bj = b[j];
            let col = j * ld + kv;
            for r in 1..=kl.min(n - 1 - j) {
                b[j + r] -= self.ab[col + r] * bj;
            }
        }
        for j in (0..n).rev() {
            let col = j * ld + kv;
            b[j] /= self.ab[col];
            let bj = b[j];
            let lo = j.saturating_sub(kv);
            for (bi, u) in b[lo..j].iter_mut().zip(&self.ab[col + lo - j..col]) {
                *bi -= u * bj;
            }
        }
    }
}

#[path = "band_update.rs"]
mod update;
use update::ColumnUpdate;

#[cfg(test)]
#[path = "band_tests.rs"]
mod tests;
