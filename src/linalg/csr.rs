//! Compressed sparse rows for the algebraic multigrid hierarchy ([`super::amg`]): product
//! with a vector, transpose, and the sparse product (Gustavson's row-by-row algorithm with a
//! dense marker). Column indices within a row are in no particular order.

/// A sparse matrix stored by rows.
#[derive(Debug, Clone, Default)]
pub struct Csr {
    pub nrows: usize,
    pub ncols: usize,
    /// Start of each row in `idx`/`val` (`nrows + 1` entries).
    pub ptr: Vec<usize>,
    pub idx: Vec<usize>,
    pub val: Vec<f64>,
}

impl Csr {
    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        for (r, yr) in y.iter_mut().enumerate().take(self.nrows) {
            let mut s = 0.0;
            for k in self.ptr[r]..self.ptr[r + 1] {
                s += self.val[k] * x[self.idx[k]];
            }
            *yr = s;
        }
    }

    /// `y += A x`.
    pub fn mul_add(&self, x: &[f64], y: &mut [f64]) {
        for (r, yr) in y.iter_mut().enumerate().take(self.nrows) {
            let mut s = 0.0;
            for k in self.ptr[r]..self.ptr[r + 1] {
                s += self.val[k] * x[self.idx[k]];
            }
            *yr += s;
        }
    }

    /// `r = b − A x`.
    pub fn residual(&self, x: &[f64], b: &[f64], r: &mut [f64]) {
        for (i, ri) in r.iter_mut().enumerate().take(self.nrows) {
            let mut s = b[i];
            for k in self.ptr[i]..self.ptr[i + 1] {
                s -= self.val[k] * x[self.idx[k]];
            }
            *ri = s;
        }
    }

    /// The diagonal (zero where the pattern has none).
    pub fn diagonal(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.nrows];
        for (r, dr) in d.iter_mut().enumerate() {
            for k in self.ptr[r]..self.ptr[r + 1] {
                if self.idx[k] == r {
                    *dr += self.val[k];
                }
            }
        }
        d
    }

    /// `Aᵀ`, rows sorted by column.
    pub fn transpose(&self) -> Csr {
        let mut count = vec![0usize; self.ncols + 1];
        for &c in &self.idx {
            count[c + 1] += 1;
        }
        for c in 0..self.ncols {
            count[c + 1] += count[c];
        }
        let ptr = count.clone();
        let mut next = count;
        let mut idx = vec![0; self.idx.len()];
        let mut val = vec![0.0; self.val.len()];
        for r in 0..self.nrows {
            for k in self.ptr[r]..self.ptr[r + 1] {
                let c = self.idx[k];
                idx[next[c]] = r;
                val[next[c]] = self.val[k];
                next[c] += 1;
            }
        }
        Csr {
            nrows: self.ncols,
            ncols: self.nrows,
            ptr,
            idx,
            val,
        }
    }

    /// `A B` (Gustavson: each row of the product accumulated in a dense row with a marker).
    pub fn matmul(&self, b: &Csr) -> Csr {
        self.matmul_then(b, |_, _, v| v)
    }

    /// `A B` with each entry of the product passed through `f(row, col, value)` (used to fuse
    /// the prolongator smoothing `P = P₀ − ω D⁻¹ A P₀` into the product; `f` sees every
    /// column that `A B` has in that row).
    pub fn matmul_then(&self, b: &Csr, f: impl Fn(usize, usize, f64) -> f64) -> Csr {
        assert_eq!(self.ncols, b.nrows, "inner dimensions");
        let mut marker = vec![usize::MAX; b.ncols];
        let mut acc = vec![0.0; b.ncols];
        let mut ptr = Vec::with_capacity(self.nrows + 1);
        let mut idx = Vec::new();
        let mut val = Vec::new();
        ptr.push(0);
        for r in 0..self.nrows {
            let start = idx.len();
            for k in self.ptr[r]..self.ptr[r + 1] {
                let (m, a) = (self.idx[k], self.val[k]);
                for l in b.ptr[m]..b.ptr[m + 1] {
                    let c = b.idx[l];
                    if marker[c] != r {
                        marker[c] = r;
                        acc[c] = 0.0;
                        idx.push(c);
                    }
                    acc[c] += a * b.val[l];
                }
            }
            for &c in &idx[start..] {
                val.push(f(r, c, acc[c]));
            }
            ptr.push(idx.len());
        }
        Csr {
            nrows: self.nrows,
            ncols: b.ncols,
            ptr,
            idx,
            val,
        }
    }

    /// The entry `(r, c)` (zero when not stored).
    pub fn get(&self, r: usize, c: usize) -> f64 {
        (self.ptr[r]..self.ptr[r + 1])
            .filter(|&k| self.idx[k] == c)
            .map(|k| self.val[k])
            .sum()
    }
}

#[cfg(test)]
impl Csr {
    /// The nonzero entries of dense rows (tests of this module and of the multigrid).
    pub(crate) fn from_dense_rows<R: AsRef<[f64]>>(m: &[R]) -> Csr {
        let mut a = Csr {
            nrows: m.len(),
            ncols: m.first().map_or(0, |r| r.as_ref().len()),
            ptr: vec![0],
            ..Default::default()
        };
        for row in m {
            for (c, &v) in row.as_ref().iter().enumerate() {
                if v != 0.0 {
                    a.idx.push(c);
                    a.val.push(v);
                }
            }
            a.ptr.push(a.idx.len());
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dense(a: &Csr) -> Vec<Vec<f64>> {
        (0..a.nrows)
            .map(|r| (0..a.ncols).map(|c| a.get(r, c)).collect())
            .collect()
    }

    #[test]
    fn product_transpose_and_residual_match_dense_arithmetic() {
        let a = Csr::from_dense_rows(&[vec![2.0, 0.0, -1.0], vec![0.0, 3.0, 0.5], vec![1.0, 0.0, 0.0]]);
        let b = Csr::from_dense_rows(&[vec![1.0, 4.0], vec![0.0, -2.0], vec![3.0, 0.0]]);
        let ab = dense(&a.matmul(&b));
        let expect = [[-1.0, 8.0], [1.5, -6.0], [1.0, 4.0]];
        for r in 0..3 {
            for c in 0..2 {
                assert_eq!(ab[r][c], expect[r][c], "({r},{c})");
            }
        }
        let bt = dense(&b.transpose());
        assert_eq!(bt, vec![vec![1.0, 0.0, 3.0], vec![4.0, -2.0, 0.0]]);
        let x = [1.0, 2.0, 3.0];
        let mut y = [0.0; 3];
        a.mul(&x, &mut y);
        assert_eq!(y, [-1.0, 7.5, 1.0]);
        let mut r = [0.0; 3];
        a.residual(&x, &[0.0, 7.5, 2.0], &mut r);
        assert_eq!(r, [1.0, 0.0, 1.0]);
        assert_eq!(a.diagonal(), vec![2.0, 3.0, 0.0]);
    }
}
