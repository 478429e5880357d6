//! Scenes that cannot be right are refused: a rigid outline listed the wrong way round (the
//! rigid body on the right of travel) starts with the deformable body inside it. Run anyway,
//! such a scene reported a punch force of the wrong sign that shrank as the punch went in,
//! with exit code 0. Reference: `scene/initial_contact.rs` (slave gaps below −1e-6 of the
//! model's size at t = 0 are an error naming the outline and the fix).

mod common;

#[test]
fn an_arc_die_listed_clockwise_is_refused_with_the_fix() {
    let sets = [
        "rigid.die.arc.from_deg=-10.0".to_string(),
        "rigid.die.arc.to_deg=-170.0".to_string(),
    ];
    let err = match contrail::load_scene("ironing", &sets) {
        Ok(_) => panic!("a clockwise die was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(err.contains("start inside rigid body `die`"), "{err}");
    assert!(err.contains("on the LEFT of the direction of travel"), "{err}");
    // the same outline, meant as an interference, loads when the pair says so
    let mut allowed = sets.to_vec();
    allowed.push("contact.allow_initial_penetration=true".into());
    assert!(contrail::load_scene("ironing", &allowed).is_ok());
}

#[test]
fn a_punch_outline_listed_the_wrong_way_round_is_refused() {
    let text = include_str!("../scenes/flat-punch.toml");
    let reversed = text.replace(
        r#"  { line = [[-1.0, 1.0], [-1.0, 0.2]] },
  { arc = { centre = [-0.8, 0.2], radius = 0.2, from_deg = 180.0, to_deg = 270.0 } },
  { line = [[-0.8, 0.0], [0.8, 0.0]] },
  { arc = { centre = [0.8, 0.2], radius = 0.2, from_deg = 270.0, to_deg = 360.0 } },
  { line = [[1.0, 0.2], [1.0, 1.0]] },"#,
        r#"  { line = [[1.0, 1.0], [1.0, 0.2]] },
  { arc = { centre = [0.8, 0.2], radius = 0.2, from_deg = 360.0, to_deg = 270.0 } },
  { line = [[0.8, 0.0], [-0.8, 0.0]] },
  { arc = { centre = [-0.8, 0.2], radius = 0.2, from_deg = 270.0, to_deg = 180.0 } },
  { line = [[-1.0, 0.2], [-1.0, 1.0]] },"#,
    );
    assert_ne!(reversed, text, "the outline to reverse was not found");
    // the block's top 0.01 below the punch face, so that only the mis-orientation overlaps
    let reversed = reversed.replace("size = [6.0, 2.0]", "size = [6.0, 1.99]");
    let err = common::scene_text_err(&reversed);
    assert!(
        err.contains("start inside rigid body `punch`") && err.contains("reverse order"),
        "{err}"
    );
    // listed the right way round with the same gap, it loads
    common::scene_text(&text.replace("size = [6.0, 2.0]", "size = [6.0, 1.99]"));
}

/// A punch listed the wrong way round 1.0 above the block (four search radii away): no
/// slave point is within reach at the start, yet each is on the solid side of the outline,
/// and run anyway the punch swept through the block with no force and exit 0.
#[test]
fn a_reversed_punch_far_from_the_block_is_refused_too() {
    let scene = |outline: &str| {
        format!(
            r#"name = "far-punch"
[[body]]
name = "block"
material = {{ model = "neo-hookean", young = 1.0e3, poisson = 0.3 }}
mesh = {{ kind = "rectangle", origin = [-1.5, -1.0], size = [3.0, 1.0], elements = [24, 8] }}
[[fix]]
body = "block"
nodes = "bottom"
components = ["x", "y"]
[[rigid]]
name = "punch"
polyline = {outline}
move = {{ y = -1.1 }}
[[contact]]
name = "punch"
slave = {{ body = "block", nodes = "top" }}
master = {{ rigid = "punch" }}
eps_n = 1.0e5
"#
        )
    };
    let err = common::scene_text_err(&scene("[[0.5, 1.5], [0.5, 1.0], [-0.5, 1.0], [-0.5, 1.5]]"));
    assert!(
        err.contains("start inside rigid body `punch`") && err.contains("reverse order"),
        "{err}"
    );
    common::scene_text(&scene("[[-0.5, 1.5], [-0.5, 1.0], [0.5, 1.0], [0.5, 1.5]]"));
}
