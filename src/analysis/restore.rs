//! Putting back the contact records a recording leaves out: a slave node that stays out of
//! reach carries nothing but its position, so a format-2 or -3 recording writes its record
//! when it leaves reach and leaves it out while it stays there (the rule is
//! [`crate::record::mcap::sink::OutOfReach`]). A restored record has the node's position in
//! that increment's `/positions` (bit for bit where they are kept in double precision) and
//! NaN where the increment has none (`--positions-every N`) or does not keep that node.

use crate::record::messages::{ModelRecord, PositionsMessage};
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::{ContactPointRecord, IncrementRecord};
use std::collections::{BTreeMap, BTreeSet};

/// Put back the `/contact` records left out: at every increment (of `increments`, of the
/// contact records or of `positions`), a node slave whose last record was out of reach and
/// that has none is out of reach still; its record is the last one with no previous segment,
/// no crossing and the node's position there. The points of each increment are kept in pair
/// and slave order.
pub fn restore_out_of_reach(
    contact: &mut BTreeMap<usize, Vec<ContactPointRecord>>,
    positions: &[PositionsMessage],
    increments: &[IncrementRecord],
) {
    let at: BTreeMap<usize, &PositionsMessage> = positions.iter().map(|p| (p.increment, p)).collect();
    let all: BTreeSet<usize> = (contact.keys().copied())
        .chain(at.keys().copied())
        .chain(increments.iter().map(|i| i.increment))
        .collect();
    let mut last: BTreeMap<(usize, usize), ContactPointRecord> = BTreeMap::new();
    for inc in all {
        let here = at.get(&inc).copied();
        let points = contact.entry(inc).or_default();
        let mut present = BTreeSet::new();
        for p in points.iter() {
            last.insert((p.pair, p.slave), p.clone());
            present.insert((p.pair, p.slave));
        }
        let mut added = false;
        for (key, l) in last.iter_mut() {
            let Some(node) = crate::record::mcap::sink::node_of_label(&l.slave_label) else {
                continue;
            };
            if l.segment.is_some() || present.contains(key) {
                continue;
            }
            let position = match here {
                Some(p) => match p.nodes.get(node) {
                    Some(&x) => x,
                    None => continue,
                },
                None => [f64::NAN; 2],
            };
            l.previous_segment = None;
            l.crossing = false;
            l.position = position;
            points.push(l.clone());
            added = true;
        }
        if added {
            points.sort_by_key(|p| (p.pair, p.slave));
        }
    }
    contact.retain(|_, v| !v.is_empty());
}

/// Put back the slaves that one `/surface_contact` message of pair `pair` leaves out (every
/// slave of the pair not among `points` is out of reach:
/// [`SurfacePointRecord::out_of_reach`]), with their positions in `positions` (that
/// increment's, if it has any). `points` stays in slave order.
pub fn restore_surface_out_of_reach(
    points: &mut Vec<SurfacePointRecord>,
    (pair, pair_name): (usize, &str),
    model: &ModelRecord,
    positions: Option<&PositionsMessage>,
) {
    let Some(info) = model.surface_contacts.get(pair) else {
        return;
    };
    if points.len() >= info.slave_nodes.len() {
        return;
    }
    let mut present = vec![false; info.slave_nodes.len()];
    for p in points.iter() {
        if let Some(f) = present.get_mut(p.slave) {
            *f = true;
        }
    }
    for (slave, &node) in info.slave_nodes.iter().enumerate() {
        if present[slave] {
            continue;
        }
        let position = positions
            .and_then(|p| p.nodes_3d.get(node).copied())
            .unwrap_or([f64::NAN; 3]);
        points.push(SurfacePointRecord::out_of_reach(
            (pair, pair_name),
            (slave, node),
            position,
        ));
    }
    points.sort_by_key(|p| p.slave);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_surface_slave_left_out_comes_back_out_of_reach_at_its_position_or_nan() {
        let mut model = ModelRecord::default();
        model
            .surface_contacts
            .push(crate::record::surface_contact::SurfacePairInfo {
                name: "top".into(),
                slave_nodes: vec![4, 7, 9],
                areas: vec![1.0; 3],
                master: "rigid ball".into(),
                master_facets: Vec::new(),
                rigid: None,
                transfer: "continuous".into(),
                eps_n: 1.0,
                eps_t: 1.0,
                mu: 0.0,
            });
        let written = SurfacePointRecord::out_of_reach((0, "top"), (1, 7), [1.0, 2.0, 3.0]);
        let mut positions = PositionsMessage {
            increment: 3,
            t: 0.5,
            nodes: Vec::new(),
            rigid_offsets: Vec::new(),
            nodes_3d: vec![[0.0; 3]; 10],
        };
        positions.nodes_3d[4] = [4.0, 0.5, 0.25];
        let mut points = vec![written.clone()];
        restore_surface_out_of_reach(&mut points, (0, "top"), &model, Some(&positions));
        assert_eq!(points.iter().map(|p| p.slave).collect::<Vec<_>>(), [0, 1, 2]);
        assert_eq!(points[0].node, 4);
        assert_eq!(points[0].position, [4.0, 0.5, 0.25]);
        assert!(points.iter().all(SurfacePointRecord::is_bare_out_of_reach));
        // an increment without positions: NaN
        let mut points = vec![written];
        restore_surface_out_of_reach(&mut points, (0, "top"), &model, None);
        assert!(points[2].position.iter().all(|x| x.is_nan()) && points[2].node == 9);
    }

    #[test]
    fn only_a_record_that_comes_back_bit_for_bit_is_bare() {
        let bare = SurfacePointRecord::out_of_reach((0, "top"), (1, 7), [1.0, 2.0, 3.0]);
        assert!(bare.is_bare_out_of_reach());
        let mut left_reach = bare.clone();
        left_reach.previous_facet = Some(0);
        let mut signed_zero = bare.clone();
        signed_zero.force[2] = -0.0;
        let mut gap = bare.clone();
        gap.gap = 0.5;
        for r in [left_reach, signed_zero, gap] {
            assert!(!r.is_bare_out_of_reach(), "{r:?}");
        }
    }
}
