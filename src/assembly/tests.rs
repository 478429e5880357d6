//! The assembler's own tests: parallel and sequential assembly agree to the bit.

use super::*;
use crate::solver::state::TrialState;

/// Assemble (with or without the tangent) from the same state, sequentially or not.
fn assembled(model: &Model, threads: usize, with_tangent: bool) -> (Vec<f64>, Vec<f64>, f64, Vec<f64>) {
    let mut asm = Assembler::new(model);
    asm.set_threads(threads, model.elements.len());
    // every assembly on the team when there is one (the pacing measures nothing here)
    if threads > 1 {
        assert_eq!(asm.threads(), threads);
        asm.pacing.force(pacing::Mode::Team);
    }
    let mut st = TrialState::new(model);
    for (i, u) in st.u.iter_mut().enumerate() {
        *u = 1e-4 * (i as f64 * 0.37).sin();
    }
    st.contact.reset_current();
    asm.assemble(model, &st.u, 0.5, &mut st.alphas, &mut st.contact, with_tangent)
        .unwrap();
    (asm.r_full.clone(), asm.matrix.values.clone(), asm.energy, st.alphas)
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn parallel_and_sequential_assembly_give_the_same_bits() {
    // more elements than one parallel block, so the block loop and the scatter order count
    let sets = vec!["body.block.mesh.elements=[100, 50]".to_string()];
    let model = crate::load_scene("hertz", &sets).unwrap().1.model;
    assert!(model.elements.len() > BLOCK);
    for with_tangent in [true, false] {
        let (rs, ks, es, als) = assembled(&model, 1, with_tangent);
        for threads in [2, 3] {
            let (rp, kp, ep, alp) = assembled(&model, threads, with_tangent);
            assert_eq!(bits(&rs), bits(&rp), "residual ({threads})");
            assert_eq!(bits(&ks), bits(&kp), "tangent ({threads})");
            assert_eq!(es.to_bits(), ep.to_bits(), "energy ({threads})");
            assert_eq!(als, alp, "enhanced-strain parameters ({threads})");
        }
        assert!(rs.iter().any(|r| *r != 0.0) && (!with_tangent || ks.iter().any(|k| *k != 0.0)));
    }
}

#[test]
fn small_models_assemble_on_the_calling_thread() {
    let model = crate::load_scene("cantilever", &[]).unwrap().1.model;
    assert_eq!(model.elements.len(), 24);
    let mut asm = Assembler::new(&model);
    asm.set_threads(2, model.elements.len());
    assert_eq!(asm.threads(), 1);
}
