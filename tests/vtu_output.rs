//! ParaView output of a run (`--out RUN.pvd`): the `VtuSink` writes every N-th increment and
//! the last, and the files hold what the run computed — checked by decoding the arrays here
//! (the independent reader check is `.ci/vtu_check.py` with meshio, run by `.ci/interop.sh`).
//!
//! Scene: the built-in `half-disc` (5 increments), `every = 2` → increments 2, 4 and 5.
//! Checks: the `.pvd` lists 3 time steps × 2 parts at the recorded load levels; the last
//! mesh file's `displacement` equals the solver's final displacement bit for bit; the contact
//! file's `normal_traction` sums to the monitored reaction (1e-9); `von_mises` is positive.

mod common;

use base64::Engine;
use contrail::record::vtu::sink::VtuSink;
use contrail::record::{Fanout, Memory, Observer};
use std::sync::atomic::AtomicBool;

/// Decode the inline binary `DataArray` called `name` (UInt64 byte count + little-endian f64).
fn array(xml: &str, name: &str) -> Vec<f64> {
    let start = xml
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no array {name}"));
    let body = &xml[start..];
    let from = body.find('>').unwrap() + 1;
    let to = body.find("</DataArray>").unwrap();
    let raw = base64::engine::general_purpose::STANDARD
        .decode(body[from..to].trim())
        .unwrap();
    let n = u64::from_le_bytes(raw[..8].try_into().unwrap()) as usize;
    assert_eq!(n, raw.len() - 8, "{name}: byte count");
    raw[8..]
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect()
}

#[test]
fn vtu_series_of_half_disc() {
    let problem = common::scene("half-disc", &[]);
    let dir = std::env::temp_dir().join(format!("contrail-vtu-{}", std::process::id()));
    let pvd = dir.join("hd.pvd");
    let mut sink = VtuSink::create(&pvd, 2).unwrap();
    let mut mem = Memory::default();
    let src = contrail::scene::SceneSource::resolve("half-disc").unwrap();
    let info = contrail::run_info(&src, &[], &problem);
    {
        let mut fan = Fanout {
            sinks: vec![&mut sink as &mut dyn Observer, &mut mem],
        };
        contrail::solver::run(&problem, &info, &mut fan, &AtomicBool::new(false)).unwrap();
    }
    let collection = std::fs::read_to_string(&pvd).unwrap();
    let steps: Vec<&str> = collection.lines().filter(|l| l.contains("<DataSet")).collect();
    assert_eq!(steps.len(), 6, "{collection}");
    for (k, inc) in [2, 4, 5].iter().enumerate() {
        let t = mem.increments[inc - 1].t;
        assert!(
            steps[2 * k].contains(&format!("timestep=\"{t:?}\"")),
            "{}",
            steps[2 * k]
        );
        assert!(steps[2 * k].contains(&format!("hd/hd_{inc:06}.vtu")));
        assert!(steps[2 * k + 1].contains(&format!("hd/hd_contact_{inc:06}.vtu")));
    }
    let mesh = std::fs::read_to_string(dir.join("hd/hd_000005.vtu")).unwrap();
    let u = array(&mesh, "displacement");
    assert_eq!(u.len(), 3 * problem.model.nodes.len());
    for (n, xy) in mem.final_u.chunks(2).enumerate() {
        assert_eq!([u[3 * n], u[3 * n + 1], u[3 * n + 2]], [xy[0], xy[1], 0.0], "node {n}");
    }
    let vm = array(&mesh, "von_mises");
    assert_eq!(vm.len(), problem.model.elements.len());
    assert!(vm.iter().all(|v| *v > 0.0), "von Mises");
    let contact = std::fs::read_to_string(dir.join("hd/hd_contact_000005.vtu")).unwrap();
    let n: f64 = array(&contact, "normal_traction").iter().sum();
    let reaction = mem.increments[4].monitor.as_ref().unwrap().force;
    assert!((n - reaction).abs() < 1e-9 * reaction, "{n} against {reaction}");
    std::fs::remove_dir_all(&dir).ok();
}
