//! Element assembly and one Newton iteration against the number of DOFs, on a refined
//! cantilever strip (10 × 0.5, EAS quads), from ~1e2 to ~1e5 DOFs.
//!
//! Run: `cargo bench --bench assembly` (figures in docs/performance.md).

use contrail::assembly::Assembler;
use contrail::solver::state::TrialState;
use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};

const MESHES: [[usize; 2]; 4] = [[24, 1], [100, 4], [500, 9], [2500, 19]];

fn model(mesh: [usize; 2]) -> contrail::model::Model {
    let sets = vec![format!("body.strip.mesh.elements=[{}, {}]", mesh[0], mesh[1])];
    contrail::load_scene("cantilever", &sets)
        .expect("built-in scene")
        .1
        .model
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("strip");
    g.sample_size(10);
    for mesh in MESHES {
        let m = model(mesh);
        let dofs = m.dof_count();
        let mut asm = Assembler::new(&m);
        let mut st = TrialState::new(&m);
        // a deformed state: the linear-ramp tip load's first increment
        for (i, u) in st.u.iter_mut().enumerate() {
            *u = 1e-3 * (i as f64 * 0.37).sin();
        }
        for p in &m.prescribed {
            st.u[p.dof] = 0.0;
        }
        g.bench_with_input(BenchmarkId::new("assemble", dofs), &dofs, |b, _| {
            b.iter(|| {
                asm.assemble(&m, &st.u, 0.5, &mut st.alphas, &mut st.contact, true)
                    .unwrap()
            })
        });
        let n = asm.dofs.n_free;
        let mut r = vec![0.0; n];
        g.bench_with_input(BenchmarkId::new("newton-iteration", dofs), &dofs, |b, _| {
            b.iter(|| {
                asm.assemble(&m, &st.u, 0.5, &mut st.alphas, &mut st.contact, true)
                    .unwrap();
                asm.free_residual(&mut r);
                asm.solve(&mut r).unwrap();
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
