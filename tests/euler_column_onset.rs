//! The onset of buckling from the tangent's definiteness: a clamped–guided column
//! compressed by its end's prescribed shortening (Timoshenko & Gere, *Theory of Elastic
//! Stability*, 2nd ed. (1961) §2.2: effective length L; Engesser's shear correction §2.17).
//!
//! ```text
//!  |=========================================|→← u_x = −δ(t) on the whole end (its section
//!  clamped            L = 10, h = 0.5                  stays upright; free sideways)
//! ```
//! Plane strain, St. Venant–Kirchhoff, E = 2.1e4, ν = 0.3: EI = E h³ / (12 (1 − ν²)) =
//! 240.3846, P_E = π² EI / L² = 23.725; with shear (κ = 5/6, G = E / 2(1 + ν)):
//! P_cr = P_E / (1 + P_E / κGA) = 23.559. The end is shortened to 1.5 × P_E L / EA'
//! (EA' = E h / (1 − ν²)) in `n` increments; the straight column stays straight (nothing
//! breaks its symmetry), so Newton follows the trivial path past the bifurcation, and the
//! run's tangent check ([`contrail::solver::stability`]) must put the onset between the last
//! increment with a positive definite tangent and the first without. Asserted: the end
//! force at those two increments brackets P_cr within 1.5 %, and they are one increment apart
//! (the bracket 1.5 P_E / n wide within 10 %: the loss is seen where it happens), on 40 × 2
//! and 80 × 4 EAS elements, and at 40 and 80 increments; one negative eigenvalue by the
//! `LDLᵀ` (`linear_solver = "general"`), a negative determinant by the banded LU (`auto`);
//! and that a column shortened to 0.9 P_E L / EA' reports nothing.

mod common;

use contrail::linalg::inertia::Inertia;

const E: f64 = 2.1e4;
const NU: f64 = 0.3;
const L: f64 = 10.0;
const H: f64 = 0.5;

fn euler() -> f64 {
    let ei = E * H.powi(3) / (12.0 * (1.0 - NU * NU));
    std::f64::consts::PI.powi(2) * ei / (L * L)
}

fn engesser() -> f64 {
    let kga = 5.0 / 6.0 * E / (2.0 * (1.0 + NU)) * H;
    euler() / (1.0 + euler() / kga)
}

fn column(elements: [usize; 2], increments: usize, shortening: f64, solver: &str) -> String {
    format!(
        r#"
name = "euler-column"
[[body]]
name = "column"
element = "q4-eas"
material = {{ model = "saint-venant-kirchhoff", young = {E}, poisson = {NU} }}
mesh = {{ kind = "rectangle", origin = [0.0, 0.0], size = [{L}, {H}], elements = [{}, {}] }}

[[fix]]
body = "column"
nodes = "left"
components = ["x", "y"]

[[fix]]
body = "column"
nodes = "right"
components = ["x"]
value = [[0.0, 0.0], [1.0, {}]]

[monitor]
label = "end force"
body = "column"
nodes = "right"
component = "x"
sign = -1.0

[stepping]
increments = {increments}
max_cutbacks = 0

[solver]
linear_solver = "{solver}"
"#,
        elements[0], elements[1], -shortening
    )
}

/// The end force at the last increment with a positive definite tangent and at the first
/// without, and what the first one said.
fn onset(elements: [usize; 2], increments: usize, factor: f64, solver: &str) -> Option<(f64, f64, Inertia)> {
    let ea = E * H / (1.0 - NU * NU);
    let problem = common::scene_text(&column(elements, increments, factor * euler() * L / ea, solver));
    let (summary, mem) = common::solve_ok(&problem);
    let i = summary.instability?;
    // `/increment` records it: positive definite up to the bracket, the loss at its end
    for r in mem.increments.iter().filter(|r| r.t <= i.t + 1e-12) {
        let negative = r.tangent.expect("a symmetric tangent tells").negative_eigenvalues;
        assert_eq!(negative > 0, r.t > i.stable_until + 1e-12, "increment {}", r.increment);
    }
    let force_at = |t: f64| {
        mem.increments
            .iter()
            .find(|r| (r.t - t).abs() < 1e-12)
            .map_or(0.0, |r| r.monitor.as_ref().expect("a monitor").force)
    };
    Some((force_at(i.stable_until), force_at(i.t), i.inertia))
}

#[test]
fn the_onset_of_buckling_is_bracketed_at_the_shear_corrected_euler_load() {
    let p_cr = engesser();
    for (elements, increments, solver) in [
        ([40, 2], 40, "auto"),
        ([40, 2], 80, "auto"),
        ([80, 4], 40, "auto"),
        ([40, 2], 40, "general"),
    ] {
        let (before, after, inertia) =
            onset(elements, increments, 1.5, solver).expect("the column passes its buckling load and says so");
        println!(
            "{}×{}, {increments} increments, {solver}: P between {before:.4} and {after:.4} ({:+.2} %, {:+.2} % of P_cr = {p_cr:.4}); {}",
            elements[0],
            elements[1],
            100.0 * (before / p_cr - 1.0),
            100.0 * (after / p_cr - 1.0),
            inertia.describe()
        );
        // the banded LU (`auto` on this strip) tells the determinant's sign, the LDLᵀ
        // (`general`) the count: the first mode alone has crossed
        let expected = Inertia {
            negative: 1,
            exact: solver == "general",
        };
        assert_eq!(inertia, expected);
        let step = 1.5 * euler() / increments as f64;
        assert!(
            after - before > 0.0 && after - before <= 1.1 * step,
            "one increment apart: {before}, {after}"
        );
        assert!(
            before <= p_cr * 1.015 && after >= p_cr * 0.985,
            "[{before}, {after}] against {p_cr}"
        );
    }
}

#[test]
fn a_column_below_its_buckling_load_reports_nothing() {
    assert_eq!(onset([40, 2], 20, 0.9, "auto"), None);
    assert_eq!(onset([40, 2], 20, 0.9, "general"), None);
}
