//! The banded LU of one pattern ([`super::band`]): the reverse Cuthill–McKee order that gives
//! the narrowest band, the band slot of each stored entry, and the permuted right-hand side.

use super::band::{band_widths, reverse_cuthill_mckee, supervariable_rcm, BandLu, Root, ZeroPivot};

/// The banded factorisation of a pattern: RCM permutation and the band slot of each stored
/// entry.
pub struct BandPlan {
    pub lu: BandLu,
    /// `perm[new] = old`
    perm: Vec<usize>,
    /// band slot of `values[k]`
    slots: Vec<usize>,
    rhs: Vec<f64>,
}

impl BandPlan {
    /// A plan if the RCM-ordered pattern has a narrow band (see [`BandLu::worth_it`]).
    pub fn new(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> Option<Self> {
        // RCM on the supervariables (nodes) from a far level or a node, and on the unknowns:
        // the narrowest band wins
        let candidates = [
            supervariable_rcm(n, col_ptr, row_idx, Root::FarLevel),
            supervariable_rcm(n, col_ptr, row_idx, Root::Node),
            reverse_cuthill_mckee(n, col_ptr, row_idx, Root::Node),
        ];
        let (perm, (kl, ku)) = candidates
            .into_iter()
            .map(|p| {
                let w = band_widths(n, col_ptr, row_idx, &p);
                (p, w)
            })
            .min_by_key(|(_, (kl, ku))| kl * ku)
            .expect("three candidates");
        let mut inv = vec![0; n];
        for (new, &old) in perm.iter().enumerate() {
            inv[old] = new;
        }
        let entries = || (0..n).flat_map(|c| row_idx[col_ptr[c]..col_ptr[c + 1]].iter().map(move |&r| (r, c)));
        if !BandLu::worth_it(n, kl.max(ku)) {
            return None;
        }
        let lu = BandLu::new(n, kl, ku);
        let slots = entries().map(|(r, c)| lu.slot(inv[r], inv[c])).collect();
        Some(BandPlan {
            lu,
            perm,
            slots,
            rhs: vec![0.0; n],
        })
    }

    /// Factorise the matrix with stored values `values` (the pattern's order).
    pub fn factorize(&mut self, values: &[f64]) -> Result<(), ZeroPivot> {
        self.lu.clear();
        for (&s, &v) in self.slots.iter().zip(values) {
            self.lu.add(s, v);
        }
        self.lu.factorize()
    }

    /// Solve `A x = b` in place with the last factorisation.
    pub fn solve(&mut self, b: &mut [f64]) {
        for (r, &old) in self.rhs.iter_mut().zip(&self.perm) {
            *r = b[old];
        }
        self.lu.solve(&mut self.rhs);
        for (r, &old) in self.rhs.iter().zip(&self.perm) {
            b[old] = *r;
        }
    }
}
