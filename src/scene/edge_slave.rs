//! A 3D slave side that is a straight edge: nodes on one line (a body's edge, such as the
//! corner line of a block a strip is drawn over), weighted by their tributary lengths — the
//! 3D counterpart of a 2D slave point, whose penalty is per unit thickness. Its penalties are
//! per unit length (`N = ε_N ℓ_s ⟨−ζ⟩`); a face's are per unit area.

/// The nodes of an edge slave sorted along the line and each one's tributary length (half
/// the distance to each neighbour), or why the nodes are not an edge: fewer than two, two at
/// one place, or off the line through the two farthest apart by more than `1e-9` of their
/// distance.
pub fn edge_lengths(nodes: &[[f64; 3]], ids: &[usize]) -> Result<(Vec<usize>, Vec<f64>), String> {
    if ids.len() < 2 {
        return Err(format!("{} node: an edge needs two or more", ids.len()));
    }
    let p = |i: usize| nodes[ids[i]];
    let dist = |a: [f64; 3], b: [f64; 3]| (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt();
    let farthest = |from: [f64; 3]| (0..ids.len()).max_by(|&a, &b| dist(from, p(a)).total_cmp(&dist(from, p(b))));
    let a = farthest(p(0)).unwrap_or(0);
    let b = farthest(p(a)).unwrap_or(0);
    let length = dist(p(a), p(b));
    if !(length > 0.0 && length.is_finite()) {
        return Err("its nodes are all at one place".into());
    }
    let dir: [f64; 3] = std::array::from_fn(|c| (p(b)[c] - p(a)[c]) / length);
    let mut along: Vec<(f64, usize)> = Vec::with_capacity(ids.len());
    for (i, &id) in ids.iter().enumerate() {
        let d: [f64; 3] = std::array::from_fn(|c| p(i)[c] - p(a)[c]);
        let s = (0..3).map(|c| d[c] * dir[c]).sum::<f64>();
        let off = dist(d, dir.map(|v| v * s));
        if off > 1e-9 * length {
            return Err(format!(
                "node {id} lies {off:.3e} off the line through the selection's ends: the nodes are not on one straight edge"
            ));
        }
        along.push((s, id));
    }
    along.sort_by(|x, y| x.0.total_cmp(&y.0));
    if along.windows(2).any(|w| w[1].0 - w[0].0 <= 1e-12 * length) {
        return Err("two of its nodes are at one place".into());
    }
    let lengths = (0..along.len())
        .map(|i| {
            let before = if i > 0 { along[i].0 - along[i - 1].0 } else { 0.0 };
            let after = along.get(i + 1).map_or(0.0, |n| n.0 - along[i].0);
            0.5 * (before + after)
        })
        .collect();
    Ok((along.into_iter().map(|(_, id)| id).collect(), lengths))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unequal spacings, nodes given out of order: sorted along the line, half-spacings summed
    /// (the lengths add up to the edge's length).
    #[test]
    fn lengths_are_half_the_neighbouring_spacings() {
        let nodes = [[0.0, 0.0, 1.0], [0.0, 3.0, 1.0], [0.0, 1.0, 1.0], [9.0, 9.0, 9.0]];
        let (ids, len) = edge_lengths(&nodes, &[1, 0, 2]).unwrap();
        assert_eq!(ids, vec![0, 2, 1]);
        assert_eq!(len, vec![0.5, 1.5, 1.0]);
    }

    #[test]
    fn nodes_off_a_line_one_node_or_coincident_nodes_are_not_an_edge() {
        let nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 0.1, 0.0], [1.0, 0.0, 0.0]];
        assert!(edge_lengths(&nodes, &[0, 1, 2])
            .unwrap_err()
            .contains("not on one straight edge"));
        assert!(edge_lengths(&nodes, &[0]).is_err());
        assert!(edge_lengths(&nodes, &[0, 1, 3]).unwrap_err().contains("one place"));
    }
}
