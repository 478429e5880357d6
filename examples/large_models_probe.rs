//! Probe for docs/large-models.md: on the `punch-large` scene at the meshes given as
//! arguments (`NXxNY`), (1) element assembly sequential vs parallel (time, and that the bits
//! agree), (2) the fill of the sparse LU with faer's ordering (COLAMD, the only one its LU
//! offers) against a symmetric AMD ordering of the same pattern (the fill a Cholesky or
//! `LDLᵀ` would have), and the time of one supernodal LU (symbolic and numeric).
//!
//! Run: `cargo run --release --example large_models_probe -- 316x15 1000x50`

use contrail::assembly::Assembler;
use contrail::solver::state::TrialState;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{factorize_symbolic_cholesky, SymmetricOrdering};
use faer::sparse::linalg::colamd;
use faer::sparse::linalg::lu::simplicial::{
    factorize_simplicial_numeric_lu, factorize_simplicial_numeric_lu_scratch, SimplicialLu,
};
use faer::sparse::{SparseColMat, SymbolicSparseColMat, Triplet};
use faer::{perm::PermRef, Side};
use std::time::Instant;

fn main() {
    let scene = std::env::var("SCENE").unwrap_or_else(|_| "scenes/punch-large.toml".into());
    for arg in std::env::args().skip(1) {
        let (nx, ny) = arg.split_once('x').expect("NXxNY");
        let sets = vec![format!("body.block.mesh.elements=[{nx},{ny}]")];
        let (_, problem) = contrail::load_scene(&scene, &sets).expect("scene");
        let model = &problem.model;
        let mut asm = Assembler::new(model);
        let mut st = TrialState::new(model);
        for (i, u) in st.u.iter_mut().enumerate() {
            *u = 1e-7 * (i as f64 * 0.37).sin(); // small strains: the tangent stays SPD
        }
        for p in &model.prescribed {
            st.u[p.dof] = 0.0;
        }
        let n = asm.dofs.n_free;
        let reps = (2_000_000 / model.dof_count()).clamp(3, 200);
        let time = |asm: &mut Assembler, st: &mut TrialState, par: bool| {
            let threads = if par { contrail::threads::available_cores() } else { 1 };
            asm.set_threads(threads, model.elements.len());
            if par {
                asm.pacing.force(contrail::assembly::pacing::Mode::Team);
            }
            let alphas0 = st.alphas.clone();
            asm.assemble(model, &st.u, 0.5, &mut st.alphas, &mut st.contact, true)
                .unwrap();
            let t0 = Instant::now();
            for _ in 0..reps {
                st.alphas.copy_from_slice(&alphas0);
                asm.assemble(model, &st.u, 0.5, &mut st.alphas, &mut st.contact, true)
                    .unwrap();
            }
            let dt = t0.elapsed().as_secs_f64() / reps as f64;
            (dt, asm.r_full.clone(), asm.matrix.values.clone(), asm.energy)
        };
        let alphas_start = st.alphas.clone();
        let (ts, rs, ks, es) = time(&mut asm, &mut st, false);
        st.alphas.copy_from_slice(&alphas_start);
        let (tp, rp, kp, ep) = time(&mut asm, &mut st, true);
        let same = rs.iter().zip(&rp).all(|(a, b)| a.to_bits() == b.to_bits())
            && ks.iter().zip(&kp).all(|(a, b)| a.to_bits() == b.to_bits())
            && es.to_bits() == ep.to_bits();
        println!(
            "{arg}: dofs {} free {n} elements {} | assembly seq {:.2} ms, par {:.2} ms ({} threads), speed-up {:.2}, identical bits: {same}",
            model.dof_count(),
            model.elements.len(),
            ts * 1e3,
            tp * 1e3,
            contrail::threads::available_cores(),
            ts / tp
        );

        // the matrix as triplets (element pattern; the rigid contact adds no coupling)
        let mut trip = Vec::new();
        for el in &model.elements {
            let eqs: Vec<usize> = el
                .nodes
                .iter()
                .flat_map(|&nd| [asm.dofs.eq[2 * nd], asm.dofs.eq[2 * nd + 1]])
                .flatten()
                .collect();
            for &c in &eqs {
                for &r in &eqs {
                    trip.push((r, c));
                }
            }
        }
        trip.sort_unstable();
        trip.dedup();
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(
            n,
            n,
            &trip
                .iter()
                .map(|&(r, c)| Triplet::new(r, c, asm.matrix.values[asm.matrix.index(r, c).unwrap()]))
                .collect::<Vec<_>>(),
        )
        .unwrap();
        let nnz_a = a.compute_nnz();

        // COLAMD (faer's LU ordering) + simplicial LU: exact nnz(L) + nnz(U)
        let (lu_nnz, t_simpl) = if n <= 250_000 {
            let mut fwd = vec![0usize; n];
            let mut inv = vec![0usize; n];
            let mut mem = MemBuffer::new(colamd::order_scratch::<usize>(n, n, nnz_a));
            colamd::order(
                &mut fwd,
                &mut inv,
                a.symbolic(),
                Default::default(),
                MemStack::new(&mut mem),
            )
            .unwrap();
            let perm = PermRef::new_checked(&fwd, &inv, n);
            let mut rp = vec![0usize; n];
            let mut rpi = vec![0usize; n];
            let mut lu = SimplicialLu::<usize, f64>::new();
            let mut mem = MemBuffer::new(factorize_simplicial_numeric_lu_scratch::<usize, f64>(n, n));
            let t0 = Instant::now();
            factorize_simplicial_numeric_lu(&mut rp, &mut rpi, &mut lu, a.as_ref(), perm, MemStack::new(&mut mem))
                .unwrap();
            let t = t0.elapsed().as_secs_f64();
            (
                Some(lu.l_factor_unsorted().compute_nnz() + lu.u_factor_unsorted().compute_nnz()),
                Some(t),
            )
        } else {
            (None, None)
        };

        // AMD on the (structurally symmetric) pattern: nnz(L) of LLᵀ, i.e. 2 nnz(L) − n for L+U
        let upper: Vec<(usize, usize)> = trip.iter().copied().filter(|(r, c)| r <= c).collect();
        let mut col_ptr = vec![0usize; n + 1];
        for &(_, c) in &upper {
            col_ptr[c + 1] += 1;
        }
        for c in 0..n {
            col_ptr[c + 1] += col_ptr[c];
        }
        // triplets are sorted by (r, c): regroup by column
        let mut by_col: Vec<Vec<usize>> = vec![Vec::new(); n];
        for &(r, c) in &upper {
            by_col[c].push(r);
        }
        let row_idx_c: Vec<usize> = by_col.into_iter().flatten().collect();
        let sym = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx_c);
        let chol =
            factorize_symbolic_cholesky(sym.as_ref(), Side::Upper, SymmetricOrdering::Amd, Default::default()).unwrap();
        let l_amd = chol.len_val();

        // numeric times: faer's supernodal LU (as the solver uses it) and Cholesky with AMD
        let t0 = Instant::now();
        let lu = a.sp_lu().unwrap();
        let t_lu = t0.elapsed().as_secs_f64();
        drop(lu);
        println!(
            "{arg}: nnz(A) {nnz_a} | COLAMD LU nnz(L+U) {} ({}), simplicial {} | AMD LLT nnz(L) {l_amd} -> 2L-n {} ({:.1}x A) | supernodal LU (symbolic+numeric) {:.3} s",
            lu_nnz.map_or("-".into(), |v| v.to_string()),
            lu_nnz.map_or("-".into(), |v| format!("{:.1}x A", v as f64 / nnz_a as f64)),
            t_simpl.map_or("-".into(), |t| format!("{t:.3} s")),
            2 * l_amd - n,
            (2 * l_amd - n) as f64 / nnz_a as f64,
            t_lu,
        );
    }
}
