//! The rank-one update of the banded LU ([`super::BandLu::factorize`]): the kernel that
//! takes most of a factorisation, unrolled for the common heights of a band.
/// The rank-one update `A[j+1.., c] −= l · A[j, c]` of the `columns` columns right of a
/// pivot column in band storage: column `k` (from 0) holds `A[j, c]` at
/// `first + k·stride` and the rows below it right after.
pub(super) struct ColumnUpdate {
    pub first: usize,
    pub stride: usize,
    pub columns: usize,
}

impl ColumnUpdate {
    /// For `km` multipliers known when compiled (the common heights of a band): the inner
    /// loop is unrolled into whole vectors. The same operations in the same order as
    /// [`Self::any`].
    #[inline(always)]
    pub fn fixed<const KM: usize>(&self, right: &mut [f64], l: &[f64; KM]) {
        // a copy on the stack: the compiler then knows that the stores below cannot change it
        let l = *l;
        let l = &l;
        for k in 0..self.columns {
            let base = self.first + k * self.stride;
            let ajc = right[base];
            if ajc != 0.0 {
                let a: &mut [f64; KM] = (&mut right[base + 1..base + 1 + KM]).try_into().expect("KM rows");
                // in blocks of four (one AVX2 vector each), then the rest
                let (a4, a_rest) = a.as_chunks_mut::<4>();
                let (l4, l_rest) = l.as_chunks::<4>();
                for (av, lv) in a4.iter_mut().zip(l4) {
                    for (x, m) in av.iter_mut().zip(lv) {
                        *x -= m * ajc;
                    }
                }
                for (x, m) in a_rest.iter_mut().zip(l_rest) {
                    *x -= m * ajc;
                }
            }
        }
    }

    #[inline(always)]
    pub fn any(&self, right: &mut [f64], l: &[f64]) {
        for k in 0..self.columns {
            let base = self.first + k * self.stride;
            let ajc = right[base];
            if ajc != 0.0 {
                for (a, m) in right[base + 1..=base + l.len()].iter_mut().zip(l) {
                    *a -= m * ajc;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reproducible sequence of numbers in [−1, 1), with exact zeros now and then (the
    /// update skips columns whose pivot-row entry is zero).
    fn numbers(n: usize, seed: u64) -> Vec<f64> {
        let mut x = seed;
        (0..n)
            .map(|i| {
                x = x
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                if i % 11 == 3 {
                    0.0
                } else {
                    (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
                }
            })
            .collect()
    }

    #[test]
    fn the_unrolled_update_does_what_the_general_one_does_to_the_last_bit() {
        fn check<const KM: usize>() {
            let update = ColumnUpdate {
                first: 3,
                stride: KM + 5,
                columns: 7,
            };
            let len = update.first + update.columns * update.stride + KM + 1;
            let start = numbers(len, KM as u64);
            let l = numbers(KM, 100 + KM as u64);
            let (mut a, mut b) = (start.clone(), start);
            update.fixed::<KM>(&mut a, l.as_slice().try_into().unwrap());
            update.any(&mut b, &l);
            assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()), "KM = {KM}");
            assert!(
                a.iter().zip(numbers(len, KM as u64)).any(|(x, y)| *x != y),
                "KM = {KM}: nothing updated"
            );
        }
        check::<1>();
        check::<4>();
        check::<5>();
        check::<13>();
        check::<40>();
    }
}
