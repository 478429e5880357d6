//! A two-pass pair read as one interface (`record::interface`, channel `/interface`): both
//! passes combined into the traction on the first pass's master face, each contact force
//! counted once.
//!
//! Reference: the contact patch test (scene `contact-patch`, see `tests/contact_patch.rs`):
//! two elastic blocks (E = 1e3, ν = 0.3, plane strain) with non-matching meshes pressed
//! together by ε = 1e-3 transmit a uniform pressure p ≈ E ε/(1 − ν²) = 1.0989 (the
//! finite-strain value 0.19 % lower). Parameters: base/top meshes 5/4, 9/7, 17/13 elements
//! along the interface, ε_N = 1e7 = 1e4 E (the scene's), frictionless, one increment.
//! Asserted, on every mesh:
//! * the interface pressure `p_j` at every node of the base's face is uniform: largest
//!   `|p_j − p̄|/p̄` ≤ 1e-3 (0.1 %), and `p̄` within 0.5 % of E ε/(1 − ν²) (not half, not twice);
//! * the force is summed once: the interface's normal force `Σ p_j l_j` equals the press's
//!   reaction (monitor `press`) to 1e-6 and `Σ N¹ + Σ N²` to 1e-9 (relative);
//! * each pass alone is not the interface: the second pass carries between 1 % and 99 % of
//!   the force, and at least one pass's own `/pressure` profile is off uniform by > 1 %;
//! * every node of the face is closed (the whole interface is in contact);
//! * the `/interface` messages of a recording read back as computed (same records).
mod common;

use contrail::analysis::recording::Recording;
use contrail::contact::law::ContactState;
use contrail::problem::Problem;
use contrail::record::interface::{interfaces, InterfaceLayout, InterfaceRecord};
use contrail::record::mcap::sink::{McapOptions, McapSink};
use contrail::record::pressure::{profiles, PressureLayout};
use contrail::record::Memory;

const MESHES: [(&str, &str); 3] = [
    ("body.base.mesh.elements=[5,2]", "body.top.mesh.elements=[4,2]"),
    ("body.base.mesh.elements=[9,4]", "body.top.mesh.elements=[7,4]"),
    ("body.base.mesh.elements=[17,8]", "body.top.mesh.elements=[13,8]"),
];

const PRESSURE: f64 = 1.0e3 * 1.0e-3 / (1.0 - 0.3 * 0.3);

/// The interface of the final increment of a solved run.
fn final_interface(p: &Problem, m: &Memory) -> InterfaceRecord {
    let inc = m.increments.last().unwrap();
    let layout = InterfaceLayout::new(&p.model);
    let contact = m.contact.last().unwrap();
    let mut all = interfaces(&layout, &p.model, &m.final_u, inc.t, inc.increment, contact);
    assert_eq!(all.len(), 1, "one two-pass interface");
    all.remove(0)
}

/// Largest `|x − mean|/mean` of the finite values of `x`, and their mean.
fn spread(x: impl Iterator<Item = f64>) -> (f64, f64) {
    let v: Vec<f64> = x.filter(|v| v.is_finite()).collect();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| ((x - mean) / mean).abs()).fold(0.0, f64::max), mean)
}

#[test]
fn a_two_pass_interface_on_the_patch_test_has_a_uniform_pressure_summed_once() {
    for (base, top) in MESHES {
        let p = common::scene("contact-patch", &[base, top]);
        let (_, m) = common::solve_ok(&p);
        let f = final_interface(&p, &m);
        assert_eq!(f.name, "interface");
        assert_eq!(p.model.contacts[f.second_pass].name, "interface/second-pass");
        let (dev, mean) = spread(f.pressure.iter().copied());
        let press = m.increments.last().unwrap().monitor.as_ref().unwrap().force;
        let passes = f.first_pass_force + f.second_pass_force;
        let integral: f64 = f.pressure.iter().zip(&f.tributary).map(|(p, l)| p * l).sum();
        let share = f.second_pass_force / passes;
        let inc = m.increments.last().unwrap();
        let layout = PressureLayout::new(&p.model);
        let own = profiles(
            &layout,
            &p.model,
            &m.final_u,
            inc.t,
            inc.increment,
            m.contact.last().unwrap(),
        );
        let own_dev: Vec<f64> = (own.iter())
            .map(|q| spread(q.points.iter().map(|x| x.pressure)).0)
            .collect();
        println!(
            "{base} {top}: interface p̄ = {mean:.6} (E ε/(1−ν²) = {PRESSURE:.6}), deviation {dev:.2e}; \
             force {:.6} = press {press:.6}, passes {passes:.6}, ∫p dl {integral:.6}; second pass {:.1} %; \
             each pass's own /pressure off uniform by {own_dev:?}",
            f.normal_force,
            100.0 * share
        );
        assert!(dev <= 1e-3, "interface pressure deviation {dev}");
        assert!(
            (mean / PRESSURE - 1.0).abs() < 5e-3,
            "mean pressure {mean} vs {PRESSURE}"
        );
        assert!(
            (f.normal_force / press - 1.0).abs() < 1e-6,
            "{} vs {press}",
            f.normal_force
        );
        assert!(
            (f.normal_force / passes - 1.0).abs() < 1e-9,
            "{} vs {passes}",
            f.normal_force
        );
        assert!((integral / f.normal_force - 1.0).abs() < 1e-12);
        assert!(share > 0.01 && share < 0.99, "second pass share {share}");
        assert!(
            own_dev.iter().any(|d| *d > 1e-2),
            "a pass alone is uniform: {own_dev:?}"
        );
        assert!(f.state.iter().all(|s| *s != ContactState::Open));
        assert_eq!(f.node.len(), f.s.len());
        assert!(f.s.windows(2).all(|w| w[0] < w[1]));
    }
}

#[test]
fn interface_messages_of_a_recording_read_back_as_computed() {
    let p = common::scene("contact-patch", &[]);
    let src = contrail::scene::SceneSource::resolve("contact-patch").unwrap();
    let info = contrail::run_info(&src, &[], &p);
    let mut sink = McapSink::new(std::io::Cursor::new(Vec::new()), "patch", McapOptions::default()).unwrap();
    contrail::solver::run(&p, &info, &mut sink, &std::sync::atomic::AtomicBool::new(false)).unwrap();
    let bytes = sink.into_inner().unwrap().into_inner();
    let rec = Recording::from_bytes(&bytes, "patch").unwrap();
    assert_eq!(rec.interface.len(), 1, "one /interface message (one increment)");
    let (_, m) = common::solve_ok(&p);
    let f = final_interface(&p, &m);
    let json = |r: &InterfaceRecord| serde_json::to_string(r).unwrap();
    assert_eq!(json(&rec.interface[0]), json(&f));
}
