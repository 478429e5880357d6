use super::*;

fn sample() -> PositionsMessage {
    PositionsMessage {
        increment: 4,
        t: 0.5,
        nodes: vec![[1.0 / 3.0, -0.0], [f64::NAN, f64::INFINITY], [5e-324, -1e308]],
        rigid_offsets: vec![[0.0, -0.25]],
        nodes_3d: Vec::new(),
    }
}

fn bits(m: &PositionsMessage) -> Vec<u64> {
    (m.nodes.iter().flatten().chain(m.nodes_3d.iter().flatten()))
        .map(|x| x.to_bits())
        .collect()
}

#[test]
fn packed_positions_unpack_bit_for_bit() {
    let p = sample();
    let text = serde_json::to_string(&PackedPositions::pack(&p)).unwrap();
    let mut direct = Vec::new();
    PackedPositions::write_json(&mut direct, &p, &PositionsContent::default()).unwrap();
    assert_eq!(String::from_utf8(direct).unwrap(), text);
    let back: PackedPositions = serde_json::from_str(&text).unwrap();
    let q = back.unpack().unwrap();
    assert_eq!(bits(&p), bits(&q));
    assert_eq!((q.increment, q.t, q.rigid_offsets), (4, 0.5, vec![[0.0, -0.25]]));
    let mut bad = back.clone();
    bad.nodes.truncate(bad.nodes.len() - 4);
    assert!(bad.unpack().unwrap_err().contains("whole number of nodes"));
    bad.nodes = "0123456789ABCDEF0123456789abcdef".into();
    assert!(bad.unpack().unwrap_err().contains("hexadecimal"));
    // plane 7 (the most significant bytes) comes last: 1.0 is 3ff0000000000000
    let one = PackedPositions::pack(&PositionsMessage {
        nodes: vec![[1.0, 0.0]],
        ..p.clone()
    });
    assert_eq!(one.nodes, format!("{}f000{}3f00", "00".repeat(12), ""));
}

/// A 3D model record of `n` nodes whose surface is `surface`.
fn solid_record(n: usize, surface: Vec<usize>) -> ModelRecord {
    ModelRecord {
        dim: Some(3),
        nodes_3d: (0..n).map(|i| [i as f64, 0.0, 0.0]).collect(),
        positions_nodes: surface,
        ..ModelRecord::default()
    }
}

#[test]
fn surface_positions_hold_the_listed_nodes_and_read_nan_elsewhere() {
    let p = PositionsMessage {
        nodes: Vec::new(),
        nodes_3d: (0..5)
            .map(|i| [i as f64 + 0.1, -(i as f64), 1.0 / (i as f64 + 3.0)])
            .collect(),
        ..sample()
    };
    let content = PositionsContent {
        nodes: Some(vec![0, 3, 4]),
        precision: Precision::Double,
    };
    let mut text = Vec::new();
    PackedPositions::write_json(&mut text, &p, &content).unwrap();
    let packed: PackedPositions = serde_json::from_slice(&text).unwrap();
    assert_eq!(
        (packed.of, packed.dim, packed.nodes.len()),
        (Some(PositionsOf::Surface), Some(3), 3 * 3 * 16)
    );
    let q = packed.unpack_for(&solid_record(5, vec![0, 3, 4])).unwrap();
    for (i, (a, b)) in p.nodes_3d.iter().zip(&q.nodes_3d).enumerate() {
        match i {
            1 | 2 => assert!(b.iter().all(|x| x.is_nan()), "node {i} is not written: {b:?}"),
            _ => assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "node {i}"),
        }
    }
    let err = packed.unpack_for(&solid_record(5, vec![0, 3])).unwrap_err();
    assert!(
        err.contains("3 nodes of the surface, but /model lists 2 of its 5"),
        "{err}"
    );
}

#[test]
fn single_precision_rounds_each_coordinate_to_the_nearest_single() {
    let p = PositionsMessage {
        nodes: vec![[1.0 / 3.0, -2.0 / 7.0], [1e6 + 0.3, f64::NAN]],
        ..sample()
    };
    let content = PositionsContent {
        nodes: None,
        precision: Precision::Single,
    };
    let mut text = Vec::new();
    PackedPositions::write_json(&mut text, &p, &content).unwrap();
    let packed: PackedPositions = serde_json::from_slice(&text).unwrap();
    assert_eq!(
        (packed.precision, packed.nodes.len()),
        (Some(Precision::Single), 4 * 4 * 2)
    );
    let q = packed.unpack().unwrap();
    for (a, b) in p.nodes.iter().flatten().zip(q.nodes.iter().flatten()) {
        match a.is_nan() {
            true => assert!(b.is_nan()),
            false => {
                assert_eq!(*b, f64::from(*a as f32));
                assert!((a - b).abs() <= 2f64.powi(-24) * a.abs(), "{a} -> {b}");
            }
        }
    }
}

#[test]
fn only_exact_positions_restore_what_was_left_out() {
    let all = PositionsContent::default();
    assert!(all.exact_for(7));
    let surface = PositionsContent {
        nodes: Some(vec![1, 4, 9]),
        precision: Precision::Double,
    };
    assert!(surface.exact_for(4) && !surface.exact_for(5));
    let single = PositionsContent {
        precision: Precision::Single,
        ..all
    };
    assert!(!single.exact_for(7));
}
