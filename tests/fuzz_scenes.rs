//! Fuzzing the scene parser, model builder and solver: the built-in scenes are mutated
//! (numbers replaced by hostile values, tokens inserted, ranges deleted or duplicated, bytes
//! changed, `--set` overrides with hostile paths and values); loading must end in a model or
//! a `SceneError` with a message — never a panic — and a model that builds must have only
//! finite coordinates and pass the size limits. A mutant that loads (what `check` accepts)
//! is also solved for its first increment (at most one cut-back and 5 Newton iterations, up
//! to 5 000 DOFs): it completes or fails with a `SolveError`, never a panic. Failing cases
//! are kept in `proptest-regressions/` and replayed first.
//!
//! CI runs a bounded number of cases (256 per property); a long run:
//! `CONTRAIL_FUZZ_CASES=100000 cargo test --release --test fuzz_scenes`.

use contrail::scene::builtin::BUILTINS;
use contrail::scene::{build, parse, SceneSource};
use proptest::prelude::*;
use std::sync::atomic::AtomicBool;

fn cases() -> u32 {
    std::env::var("CONTRAIL_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256)
}

const HOSTILE: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "-1.0",
    "0",
    "0.0",
    "1e308",
    "-9.2e18",
    "1e-300",
    "9223372036854775807",
    "18446744073709551615",
    "4294967296",
    "100000000",
    "0.5",
    "-1",
    "\"\"",
    "[]",
    "[0.0]",
    "[nan, 0.0]",
    "[[0.0, 0.0]]",
    "[[0.0, 0.0], [0.0, 0.0]]",
    "{}",
    "true",
];

const TOKENS: &[&str] = &[
    "[[rigid]]\nname = \"C\"\npoint = [0.0, 0.0]\n",
    "[[contact]]\nname = \"base\"\n",
    "[[body]]\n",
    "arc = { centre = [0.0, 1.0], radius = inf, from_deg = -30.0, to_deg = -150.0 }\n",
    "\n[limits]\nmax_dofs = 18446744073709551615\n",
    "[",
    "]",
    "\"",
    "=",
    "\n",
    ",",
    "#",
    "{",
    "}",
    "'",
    "\\",
];

#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the `k`-th number of the text by a hostile value.
    Number {
        k: usize,
        with: usize,
    },
    Insert {
        at: usize,
        token: usize,
    },
    Delete {
        at: usize,
        len: usize,
    },
    Duplicate {
        at: usize,
        len: usize,
    },
    Byte {
        at: usize,
        b: u8,
    },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..HOSTILE.len()).prop_map(|(k, with)| Mutation::Number { k, with }),
        1 => (any::<usize>(), 0..TOKENS.len()).prop_map(|(at, token)| Mutation::Insert { at, token }),
        1 => (any::<usize>(), 1..40usize).prop_map(|(at, len)| Mutation::Delete { at, len }),
        1 => (any::<usize>(), 1..200usize).prop_map(|(at, len)| Mutation::Duplicate { at, len }),
        1 => (any::<usize>(), 32..127u8).prop_map(|(at, b)| Mutation::Byte { at, b }),
    ]
}

/// Byte ranges of the numbers in a text (digits with sign, dot and exponent).
fn numbers(t: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < t.len() {
        let starts = t[i].is_ascii_digit() || (t[i] == b'-' && t.get(i + 1).is_some_and(u8::is_ascii_digit));
        let in_word = i > 0 && (t[i - 1].is_ascii_alphanumeric() || t[i - 1] == b'_');
        if starts && !in_word {
            let s = i;
            i += 1;
            while i < t.len() && (t[i].is_ascii_digit() || matches!(t[i], b'.' | b'e' | b'E' | b'-' | b'+')) {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Apply mutations to a scene text (kept valid UTF-8).
fn mutate(text: &str, ms: &[Mutation]) -> String {
    let mut t = text.as_bytes().to_vec();
    for m in ms {
        let n = t.len().max(1);
        match *m {
            Mutation::Number { k, with } => {
                let nums = numbers(&t);
                if let Some(&(s, e)) = nums.get(k % nums.len().max(1)) {
                    t.splice(s..e, HOSTILE[with].bytes());
                }
            }
            Mutation::Insert { at, token } => {
                let at = at % (t.len() + 1);
                t.splice(at..at, TOKENS[token].bytes());
            }
            Mutation::Delete { at, len } => {
                let at = at % n;
                let end = (at + len).min(t.len());
                t.drain(at.min(end)..end);
            }
            Mutation::Duplicate { at, len } => {
                let at = at % n;
                let end = (at + len).min(t.len());
                let piece: Vec<u8> = t[at.min(end)..end].to_vec();
                t.splice(end..end, piece);
            }
            Mutation::Byte { at, b } => {
                if !t.is_empty() {
                    let at = at % t.len();
                    t[at] = b;
                }
            }
        }
    }
    String::from_utf8_lossy(&t).into_owned()
}

/// Load a mutated scene: `Ok(dofs)` or the error message; panics are test failures.
fn load(text: String, sets: &[String]) -> Result<usize, String> {
    let src = SceneSource {
        origin: "fuzz.toml".into(),
        text,
    };
    let scene = parse(&src, sets).map_err(|e| e.to_string())?;
    let mut problem = build(&src, &scene).map_err(|e| e.to_string())?;
    let m = &problem.model;
    for p in &m.nodes {
        assert!(p[0].is_finite() && p[1].is_finite(), "a node at {p:?}");
    }
    assert!(m.dof_count() <= scene.limits.max_dofs);
    let dofs = m.dof_count();
    if dofs <= 5000 {
        solve_first_increment(&src, &mut problem);
    }
    Ok(dofs)
}

/// Solve the first increment of a problem that loaded: completion or a `SolveError`, never a
/// panic (the result itself is not judged: a hostile scene may well fail).
fn solve_first_increment(src: &SceneSource, problem: &mut contrail::problem::Problem) {
    let st = &mut problem.settings.stepping;
    st.end /= st.increments.max(1) as f64;
    st.increments = 1;
    st.max_cutbacks = st.max_cutbacks.min(1);
    problem.settings.newton.max_iterations = problem.settings.newton.max_iterations.min(5);
    let info = contrail::run_info(src, &[], problem);
    let mut mem = contrail::record::Memory::default();
    let _ = contrail::solver::run(problem, &info, &mut mem, &AtomicBool::new(false));
}

fn set_value() -> impl Strategy<Value = String> {
    let keys = prop_oneof![
        Just("stepping.end".to_string()),
        Just("stepping.increments".into()),
        Just("body.0.mesh.elements".into()),
        Just("body.mesh.size".into()),
        Just("contact.mu".into()),
        Just("contact.eps_n".into()),
        Just("contact.search_radius".into()),
        Just("rigid.0.point".into()),
        Just("rigid.arc.radius".into()),
        Just("limits.max_dofs".into()),
        "[a-z_.0-9]{0,40}",
        (1..5000usize).prop_map(|n| vec!["a"; n].join(".")),
    ];
    (keys, 0..HOSTILE.len()).prop_map(|(k, v)| format!("{k}={}", HOSTILE[v]))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: Some(Box::new(proptest::test_runner::FileFailurePersistence::SourceParallel("proptest-regressions"))), ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenes_load_or_explain(
        scene in 0..BUILTINS.len(),
        ms in proptest::collection::vec(mutation(), 1..6),
    ) {
        let text = mutate(BUILTINS[scene].text, &ms);
        if let Err(e) = load(text, &[]) {
            prop_assert!(e.contains("fuzz.toml"), "{e}");
        }
    }

    #[test]
    fn hostile_overrides_load_or_explain(
        scene in 0..BUILTINS.len(),
        sets in proptest::collection::vec(set_value(), 1..4),
    ) {
        if let Err(e) = load(BUILTINS[scene].text.to_string(), &sets) {
            prop_assert!(e.contains("fuzz.toml"), "{e}");
        }
    }
}
