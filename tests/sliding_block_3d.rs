//! Sliding block in 3D (issue 33): a deformable block pressed onto a deformable slab, then
//! its top dragged at 30° to the slab's mesh lines, far enough that every slave point
//! crosses several slab facets, over their edges and near and across their vertices.
//!
//! ```text
//!        top: u_z = −0.002 (t ∈ [0, 1]), then u_x, u_y = s (cos 30°, sin 30°), s → 0.8
//!          +-------+
//!          | block |  0.4 × 0.4 × 0.2 at (0.3, 0.3, 0); slave: its zmin face nodes
//!   +------+=======+-----------------------------+
//!   |  slab 2.0 × 1.4 × 0.3 (master: its zmax facets), bottom held  |
//!   +------------------------------------------------------------+
//! ```
//! Parameters: both bodies neo-Hooke, E = 1000, ν = 0.3 (hex8 EAS); node-to-surface one
//! pass, ε_N = ε_T = 1e5 per unit area, μ = 0.3, continuous transfer of the friction history;
//! the press in the first increment(s) of t ∈ [0, 1], the drag of 0.8 over t ∈ [1, 33].
//! Meshes (slab / block elements; non-matching, the slab's facets 2–2.2 times the block's):
//! coarse 10×7×2 / 4×4×2, fine 16×11×3 / 7×7×3; steps 33 and 66 increments (the half step).
//! Reference (Coulomb's law in gross sliding): the friction force is `F_t = μ F_n` and
//! points against the sliding direction.
//! Measured from the recorded contact forces (`force`: what each slave node receives as
//! assembled): `F = Σ force`, `F_n = F_z` (the slab's undeformed normal), `F_t = |(F_x, F_y)|`,
//! at every increment of the steady phase (t ≥ 3: dragged by ≥ 0.05, about thirty times the
//! stick-to-slip travel), where no closed point may be sticking.
//! Asserted: `|F_t/F_n − μ| ≤ 1 % μ` at each of those increments; the same ratio in each
//! point's own frame (`Σ|t_i| / Σ N_i`, each force split along its facet's normal) within
//! 1e-6 of μ (relative); the friction force within 0.5° of the drag direction's opposite;
//! facets crossed (records' `crossing`: at least twice as many as slave nodes), some into a
//! facet sharing only a vertex with the old one; no history lost. The straightforward
//! transfer must fail the ratio and the direction (the check can fail).
//! Measured (2026-11-27, `cargo test --release --test sliding_block_3d -- --include-ignored
//! --nocapture --test-threads=1`; worst steady increment; release wall times, 2 shared cores):
//!
//! | case                 | increments | F_t/F_n mean | worst   | angle  | Newton | crossings (vertex) | s    |
//! |----------------------|-----------:|-------------:|--------:|-------:|-------:|-------------------:|-----:|
//! | coarse 30°           | 33         | 0.29987      | −0.375 %| 0.15°  | 115    | 133 (2)            | 3.5  |
//! | coarse 30°           | 66         | 0.29987      | −0.375 %| 0.16°  | 165    | 133 (2)            | 5.2  |
//! | fine 30°             | 33         | 0.29987      | −0.181 %| 0.07°  | 132    | 508 (36)           | 15.3 |
//! | fine 30°             | 66         | 0.29989      | −0.181 %| 0.09°  | 205    | 524 (20)           | 25.0 |
//! | coarse 45° (vertices)| 33         | 0.29987      | +0.444 %| 0.07°  | 106    | 113 (37)           | 3.0  |
//! | straightforward 30°  | 33         | 0.24430      | −84.2 % | 97.7°  | 135    | 131 (4)            | 3.0  |
//!
//! | coarse 30°, Nagata  | 33         | 0.29990      | −0.214 %| 0.09°  | 83     | 133 (2)            | 1.4  |
//! | fine 30°, Nagata    | 33         | 0.29988      | −0.145 %| 0.07°  | 105    | 508 (36)           | 8.1  |
//!
//! The Nagata rows (`master_smoothing = "nagata"`, measured 2026-11-28, the machine
//! running beside one single-threaded contrail run) have the slab's face as patches through its nodes: the worst ratio is
//! nearer μ and Newton needs fewer iterations than on the bilinear facets; each point's
//! own-frame ratio is μ to 1.1e-6 (asserted: 2e-6). No history was lost in any case. In each point's frame the ratio is μ to 1.2e-7: what is
//! left of `F_t/F_n − μ` is the slab's deformed surface (its normals tilt by up to 5e-3 under
//! the block, so `F_z` and `(F_x, F_y)` mix normal and friction parts), and it halves from the
//! coarse to the fine mesh; the step does not change it (sliding is rate-independent). The
//! coarse case at the nominal step runs in the debug tier (4–6 s), the others in the release
//! tier (`.ci/run`).
//! Not asserted here (measured once, coarse 30°, 33 increments): two-pass (it ran only since
//! the free-border rule of `contact3d::system::on_facets`) slides with `F_t/F_n` down to
//! 0.279 (−7 %) at the increments where slab nodes come under the block's leading edge: they
//! close without a friction history and stick first. ε_N = ε_T = 1e7 keeps the ratio within
//! 0.4 %; with the contact Newton's force unknowns it takes 82 Newton iterations and no
//! cut-back (`tests/contact_newton_3d.rs`; 1248 and 27 when the 3D points decided by their own
//! trial).
mod common;

use contrail::contact::law::ContactState;
use contrail::model::SurfaceMaster;

const MU: f64 = 0.3;
/// The drag's length.
const DRAG: f64 = 0.8;
/// The end of the run: the press over t ∈ [0, 1], the drag over t ∈ [1, END].
const END: f64 = 33.0;
/// The steady phase starts here.
const STEADY: f64 = 3.0;

struct Case {
    /// The drag's angle to the slab's mesh lines (x), in degrees.
    angle: f64,
    slab: [usize; 3],
    block: [usize; 3],
    increments: usize,
    transfer: &'static str,
    /// The slab's face: `"none"` (bilinear facets) or `"nagata"` (patches).
    smoothing: &'static str,
}

const COARSE: Case = Case {
    angle: 30.0,
    slab: [10, 7, 2],
    block: [4, 4, 2],
    increments: 33,
    transfer: "continuous",
    smoothing: "none",
};

const FINE: Case = Case {
    angle: 30.0,
    slab: [16, 11, 3],
    block: [7, 7, 3],
    increments: 33,
    transfer: "continuous",
    smoothing: "none",
};

fn scene(c: &Case) -> String {
    let ([sx, sy, sz], [bx, by, bz], n) = (c.slab, c.block, c.increments);
    // to 12 decimals, as a scene file writes them (the built-in `slide-3d` is the coarse case)
    let round = |v: f64| (v * 1e12).round() / 1e12;
    let (dx, dy) = (
        round(DRAG * c.angle.to_radians().cos()),
        round(DRAG * c.angle.to_radians().sin()),
    );
    let top = |component: &str, values: [f64; 3]| {
        let [a, b, e] = values;
        format!(
            "[[fix]]\nbody = \"block\"\nnodes = \"zmax\"\ncomponents = [\"{component}\"]\n\
             value = [[0.0, {a}], [1.0, {b}], [{END}, {e}]]\n"
        )
    };
    format!(
        r#"name = "sliding-block-3d"
[[body]]
name = "slab"
material = {{ model = "neo-hookean", young = 1.0e3, poisson = 0.3 }}
mesh = {{ kind = "box", origin = [0.0, 0.0, -0.3], size = [2.0, 1.4, 0.3], elements = [{sx}, {sy}, {sz}] }}
[[body]]
name = "block"
material = {{ model = "neo-hookean", young = 1.0e3, poisson = 0.3 }}
mesh = {{ kind = "box", origin = [0.3, 0.3, 0.0], size = [0.4, 0.4, 0.2], elements = [{bx}, {by}, {bz}] }}
[[fix]]
body = "slab"
nodes = "zmin"
components = ["x", "y", "z"]
{}{}{}[[contact]]
name = "interface"
slave = {{ body = "block", nodes = "zmin" }}
master = {{ body = "slab", face = "zmax" }}
eps_n = 1.0e5
eps_t = 1.0e5
mu = {MU}
transfer = "{}"
master_smoothing = "{}"
[stepping]
end = {END}
increments = {n}
"#,
        top("z", [0.0, -0.002, -0.002]),
        top("x", [0.0, 0.0, dx]),
        top("y", [0.0, 0.0, dy]),
        c.transfer,
        c.smoothing
    )
}

/// What a run measured.
struct Sliding {
    /// `F_t/F_n` at each steady increment.
    ratios: Vec<f64>,
    /// The largest `|Σ|t_i|/(μ Σ N_i) − 1|` over the steady increments, `t_i` the part of
    /// point `i`'s force in its facet's tangent plane, `N_i` the part along its normal: the
    /// law itself, free of the slab's deformed surface.
    local: f64,
    /// The largest angle (degrees) between the friction force and the drag's opposite over
    /// the steady increments.
    angle: f64,
    /// Closed points that were not slipping at a steady increment.
    not_slipping: usize,
    /// Records with `crossing`, those into a facet sharing a single node with the old one,
    /// and those with `history_lost`, over the run.
    crossings: usize,
    vertex_crossings: usize,
    lost: usize,
    iterations: usize,
    wall: f64,
}

fn run(c: &Case) -> Sliding {
    let (p, summary, mem) = common::solve_solid_text("sliding-block-3d.toml", &scene(c));
    let SurfaceMaster::Facets { facets, .. } = &p.model.surface_contacts[0].master else {
        panic!("a deformable master")
    };
    let drag = [-c.angle.to_radians().cos(), -c.angle.to_radians().sin()];
    let mut out = Sliding {
        ratios: vec![],
        local: 0.0,
        angle: 0.0,
        not_slipping: 0,
        crossings: 0,
        vertex_crossings: 0,
        lost: 0,
        iterations: summary.newton_iterations,
        wall: summary.wall_time_s,
    };
    for (inc, points) in mem.increments.iter().zip(&mem.surface) {
        for q in points.iter().filter(|q| q.crossing) {
            out.crossings += 1;
            let (a, b) = (facets[q.previous_facet.unwrap()], facets[q.facet.unwrap()]);
            let shared = a.iter().filter(|n| b.contains(n)).count();
            out.vertex_crossings += usize::from(shared == 1);
        }
        out.lost += points.iter().filter(|q| q.history_lost).count();
        if inc.t < STEADY - 1e-9 {
            continue;
        }
        let f: [f64; 3] = std::array::from_fn(|k| points.iter().map(|q| q.force[k]).sum());
        let ft = f[0].hypot(f[1]);
        out.ratios.push(ft / f[2]);
        out.local = out.local.max((local_ratio(points) / MU - 1.0).abs());
        let cos = (f[0] * drag[0] + f[1] * drag[1]) / ft;
        out.angle = out.angle.max(cos.clamp(-1.0, 1.0).acos().to_degrees());
        out.not_slipping += (points.iter()).filter(|q| q.state == ContactState::Stick).count();
    }
    out
}

/// `Σ|t_i| / Σ N_i` over the closed points, each force split along its facet's normal.
fn local_ratio(points: &[contrail::record::surface_contact::SurfacePointRecord]) -> f64 {
    let (mut normal, mut tangential) = (0.0, 0.0);
    for q in points.iter().filter(|q| q.state != ContactState::Open) {
        let n: f64 = (0..3).map(|k| q.force[k] * q.normal[k]).sum();
        let t = (0..3).map(|k| (q.force[k] - n * q.normal[k]).powi(2)).sum::<f64>();
        normal += n;
        tangential += t.sqrt();
    }
    tangential / normal
}

/// The signed error of `F_t/F_n` from μ (per cent) farthest from zero over the steady phase.
fn worst_error(s: &Sliding) -> f64 {
    let error = |r: &f64| (r / MU - 1.0) * 100.0;
    (s.ratios.iter().map(error)).fold(0.0, |a: f64, e| if e.abs() > a.abs() { e } else { a })
}

/// Run `c` and print what it measured (`name` heads the line).
fn measure(name: &str, c: &Case) -> Sliding {
    let s = run(c);
    let mean = s.ratios.iter().sum::<f64>() / s.ratios.len() as f64;
    println!(
        "{name} ({}, {}, {}°): slab {:?} block {:?}, {} increments: F_t/F_n mean {mean:.5}, worst {:+.3} % over {} \
         steady increments (local {:.1e}); angle ≤ {:.3}°; {} Newton iterations; {} crossings ({} over a vertex), {} lost; {:.2} s",
        c.transfer,
        c.smoothing,
        c.angle,
        c.slab,
        c.block,
        c.increments,
        worst_error(&s),
        s.ratios.len(),
        s.local,
        s.angle,
        s.iterations,
        s.crossings,
        s.vertex_crossings,
        s.lost,
        s.wall
    );
    s
}

/// Run `c` and assert Coulomb's ratio, the direction and the crossings (module docs).
fn check(name: &str, c: &Case) {
    let s = measure(name, c);
    let worst = worst_error(&s);
    assert!(s.ratios.len() >= 30, "{} steady increments", s.ratios.len());
    assert_eq!(s.not_slipping, 0, "closed points sticking in the steady phase");
    assert!(worst.abs() <= 1.0, "F_t/F_n off μ by {worst:.3} %");
    // on Nagata patches the point's frame is the patch's at its converged ξ (measured
    // 6.1e-7 coarse, 1.06e-6 fine: the Newton tolerance's share, not a law's)
    let local_tol = if c.smoothing == "nagata" { 2e-6 } else { 1e-6 };
    assert!(s.local <= local_tol, "Σ|t|/Σ N off μ by {:.3e} (relative)", s.local);
    assert!(s.angle <= 0.5, "friction force {:.3}° off the drag", s.angle);
    let points = (c.block[0] + 1) * (c.block[1] + 1);
    assert!(
        s.crossings >= 2 * points,
        "{} crossings of {points} points",
        s.crossings
    );
    assert!(s.vertex_crossings > 0, "no crossing over a vertex");
    assert_eq!(s.lost, 0, "histories lost under the continuous transfer");
}

#[test]
fn coarse_mesh_slides_at_coulombs_ratio() {
    check("coarse", &COARSE);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn coarse_mesh_at_the_half_step_slides_at_coulombs_ratio() {
    check(
        "coarse, half step",
        &Case {
            increments: 66,
            ..COARSE
        },
    );
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn fine_mesh_slides_at_coulombs_ratio() {
    check("fine", &FINE);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn fine_mesh_at_the_half_step_slides_at_coulombs_ratio() {
    check("fine, half step", &Case { increments: 66, ..FINE });
}

/// The slab's face as Nagata patches (`master_smoothing = "nagata"`): each point's normal
/// follows the patch instead of its facet's plane; the ratio and the crossings as bilinear.
#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn nagata_patches_slide_at_coulombs_ratio_on_both_meshes() {
    check(
        "coarse, nagata",
        &Case {
            smoothing: "nagata",
            ..COARSE
        },
    );
    check(
        "fine, nagata",
        &Case {
            smoothing: "nagata",
            ..FINE
        },
    );
}

/// At 45° over the slab's square facets, the block's slave nodes that start on slab vertices
/// slide through the next vertices (up to the block's deformation).
#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn through_vertices_at_45_degrees_slides_at_coulombs_ratio() {
    check("through vertices", &Case { angle: 45.0, ..COARSE });
}

/// The check can fail: the straightforward transfer (`ξ_(n)` and `T_α^(n)` kept as numbers on
/// the new facet) gives the crossing points a slip of about a facet in one increment, their
/// friction force then turns (here to 98° off the drag) and `F_t/F_n` drops (by 84 %).
#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn the_straightforward_transfer_does_not_slide_at_coulombs_ratio() {
    let s = measure(
        "straightforward",
        &Case {
            transfer: "straightforward",
            ..COARSE
        },
    );
    assert!(worst_error(&s) < -20.0, "F_t/F_n off μ by {:.3} %", worst_error(&s));
    assert!(s.angle > 20.0, "friction force {:.3}° off the drag", s.angle);
}

#[test]
fn the_built_in_slide_3d_is_the_coarse_case() {
    let model = |origin: &str, text: &str| {
        let src = contrail::scene::SceneSource {
            origin: origin.into(),
            text: text.into(),
        };
        let file = contrail::scene::parse(&src, &[]).unwrap();
        let contrail::scene::AnyProblem::Solid(mut p) = contrail::scene::build_any(&src, &file).unwrap() else {
            panic!("{origin}: not 3D")
        };
        p.model.name.clear();
        p.model.description.clear();
        format!("{:?} {:?}", p.model, p.settings)
    };
    let builtin = contrail::scene::builtin::find("slide-3d").unwrap().text;
    assert!(
        model("slide-3d", builtin) == model("coarse", &scene(&COARSE)),
        "slide-3d is not the coarse case"
    );
}
