use super::*;

/// Two quadrilaterals side by side on `[0, 2] × [0, 1]`, the second numbered clockwise;
/// `bottom` listed right to left (against the body's orientation), `top` left to right.
fn two_quads(second_quad: &str, z6: &str) -> String {
    format!(
        r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
4
0 1 "corner"
1 2 "bottom"
1 3 "top"
2 4 "body"
$EndPhysicalNames
$Entities
1 2 1 0
1 0 0 0 1 1
1 0 0 0 2 0 0 1 2 0
2 0 1 0 2 1 0 1 3 0
1 0 0 0 2 1 0 1 4 0
$EndEntities
$Nodes
1 6 1 6
2 1 0 6
1
2
3
4
5
6
0 0 0
1 0 0
2 0 0
0 1 0
1 1 0
2 1 {z6}
$EndNodes
$Elements
4 7 1 7
0 1 15 1
1 1
1 1 1 2
2 3 2
3 2 1
1 2 1 2
4 4 5
5 5 6
2 1 3 2
6 1 2 5 4
7 {second_quad}
$EndElements
"#
    )
}

#[test]
fn quads_are_made_counter_clockwise_and_faces_run_around_the_body() {
    let m = read_gmsh("t.msh", two_quads("2 5 6 3", "0").as_bytes()).unwrap();
    assert_eq!(m.nodes.len(), 6);
    assert_eq!(m.reoriented, 1);
    for q in &m.quads {
        let (area2, _) = quad_shape(&q.map(|i| m.nodes[i]));
        assert!(area2 > 0.0, "{q:?} is clockwise");
    }
    // bottom: body above, so the segments run +x whatever the file's direction
    assert_eq!(m.faces["bottom"], vec![[0, 1], [1, 2]]);
    // top: body below, segments run −x
    assert_eq!(m.faces["top"], vec![[5, 4], [4, 3]]);
    assert_eq!(m.node_sets["corner"], vec![0]);
    assert_eq!(m.node_sets["bottom"], vec![0, 1, 2]);
    assert_eq!(m.node_sets["body"], vec![0, 1, 2, 3, 4, 5]);
    assert_eq!(m.node_sets["all"].len(), 6);
    // outward normal of the bottom face (segment direction turned by −90°) points down
    let [a, b] = m.faces["bottom"][0];
    let t = [m.nodes[b][0] - m.nodes[a][0], m.nodes[b][1] - m.nodes[a][1]];
    assert!(t[0] > 0.0 && (-t[0]) < 0.0);
}

#[test]
fn triangles_are_rejected_with_the_recombine_hint() {
    let text = two_quads("2 5 6 3", "0").replace("2 1 3 2\n6 1 2 5 4\n7 2 5 6 3", "2 1 2 2\n6 1 2 5\n7 2 6 5");
    let e = read_gmsh("t.msh", text.as_bytes()).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e, GmshError::UnsupportedElement { code: 2, count: 2, .. }),
        "{msg}"
    );
    assert!(
        msg.contains("t.msh") && msg.contains("triangle") && msg.contains("RecombineAll"),
        "{msg}"
    );
}

#[test]
fn bad_files_are_typed_errors() {
    let cases: Vec<(String, &str)> = vec![
        (two_quads("2 5 6 3", "0.5"), "z = 5"),
        (two_quads("2 5 6 9", "0"), "node 9"),
        (two_quads("2 3 5 6", "0"), "degenerate"),
        (
            two_quads("2 5 6 3", "0").replace("\n1 1 0\n", "\n1.9 0.1 0\n"),
            "not convex",
        ),
        (two_quads("2 3 3 6", "0"), "degenerate"),
        ("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n".into(), "MSH format 2.2"),
        ("$MeshFormat\n4.1 0 4\n$EndMeshFormat\n".into(), "MSH format 4.1 0 4"),
        ("hello".into(), "$MeshFormat"),
        (
            two_quads("2 5 6 3", "0").replace("$Nodes\n1 6", "$Nodes\n1 7"),
            "inconsistent",
        ),
        {
            let t = two_quads("2 5 6 3", "0");
            (t[..t.find("$Elements").unwrap() + 12].to_string(), "not a readable")
        },
    ];
    for (text, expect) in cases {
        let e = read_gmsh("bad.msh", text.as_bytes()).expect_err(expect);
        let msg = e.to_string();
        assert!(
            msg.contains("bad.msh") && msg.contains(expect),
            "expected `{expect}` in: {msg}"
        );
    }
}

#[test]
fn truncated_and_corrupted_files_never_panic() {
    let good = two_quads("2 5 6 3", "0");
    let bytes = good.as_bytes();
    for cut in 0..bytes.len() {
        let _ = read_gmsh("cut.msh", &bytes[..cut]);
    }
    for k in 0..bytes.len() {
        for c in [b'9', b'-', b' ', b'$', 0] {
            let mut b = bytes.to_vec();
            b[k] = c;
            let _ = read_gmsh("flip.msh", &b);
        }
    }
}

#[test]
fn chain_orders_segments_and_keeps_loops() {
    assert_eq!(chain(vec![[2, 3], [0, 1], [1, 2]]), vec![[0, 1], [1, 2], [2, 3]]);
    assert_eq!(chain(vec![[1, 2], [2, 0], [0, 1]]), vec![[1, 2], [2, 0], [0, 1]]);
    assert_eq!(chain(vec![[5, 6], [0, 1]]).len(), 2);
}
