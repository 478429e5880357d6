//! Consistency checks of the records of a recording before anything uses them: every node
//! index of the `/model` record points at a node, every body range lies inside the node
//! list, position messages have one entry per node and rigid body, and increment numbers are
//! in order. A recording that passes can be summarised, compared and replayed without an
//! index going out of bounds.

use super::recording::Builder;
use crate::record::mcap::schemas;
use crate::record::messages::ModelRecord;

/// Largest increment number accepted (a run of more increments would not fit in a file).
pub const MAX_INCREMENT: usize = u32::MAX as usize;

/// Check the `/model` record; the error says what is wrong.
pub fn check_model(m: &ModelRecord) -> Result<(), String> {
    let n = m.node_count();
    if m.dim() != 2 && m.dim() != 3 {
        return Err(format!("dimension {}: neither 2 nor 3", m.dim()));
    }
    let node = |what: &str, i: usize| -> Result<(), String> {
        if i < n {
            Ok(())
        } else {
            Err(format!("{what} names node {i}, but the model has {n} nodes"))
        }
    };
    for (k, e) in m.elements.iter().enumerate() {
        for &i in e {
            node(&format!("element {k}"), i)?;
        }
    }
    for (k, e) in m.hexahedra.iter().enumerate() {
        for &i in e {
            node(&format!("hexahedron {k}"), i)?;
        }
    }
    let elements = m.elements.len() + m.hexahedra.len();
    if m.element_body.len() != elements {
        return Err(format!(
            "{elements} elements but {} element bodies",
            m.element_body.len()
        ));
    }
    if let Some((k, b)) = m.element_body.iter().enumerate().find(|(_, &b)| b >= m.bodies.len()) {
        return Err(format!(
            "element {k} belongs to body {b}, but there are {} bodies",
            m.bodies.len()
        ));
    }
    for b in &m.bodies {
        let end = b.first_node.checked_add(b.node_count).filter(|&e| e <= n);
        if end.is_none() {
            return Err(format!(
                "body `{}` has nodes {} + {}, but the model has {n} nodes",
                b.name, b.first_node, b.node_count
            ));
        }
        for f in &b.faces {
            for s in &f.segments {
                node(&format!("face `{}` of body `{}`", f.name, b.name), s[0])?;
                node(&format!("face `{}` of body `{}`", f.name, b.name), s[1])?;
            }
        }
    }
    for c in &m.surface_contacts {
        let what = format!("3D contact `{}`", c.name);
        for &i in c.slave_nodes.iter().chain(c.master_facets.iter().flatten()) {
            node(&what, i)?;
        }
        if c.areas.len() != c.slave_nodes.len() {
            return Err(format!(
                "{what} has {} slave nodes but {} areas",
                c.slave_nodes.len(),
                c.areas.len()
            ));
        }
    }
    for c in &m.contacts {
        for s in &c.master_segments {
            node(&format!("master segment of contact `{}`", c.name), s[0])?;
            node(&format!("master segment of contact `{}`", c.name), s[1])?;
        }
    }
    Ok(())
}

/// Check the other records against the model; the error gives the topic and what is wrong.
pub(crate) fn check_records(m: &ModelRecord, b: &Builder) -> Result<(), (String, String)> {
    let err = |topic: &str, what: String| Err((topic.to_string(), what));
    let mut last = 0;
    for inc in &b.increments {
        if inc.increment > MAX_INCREMENT || (last > 0 && inc.increment <= last) {
            return err(
                schemas::INCREMENT,
                format!("increment {} after increment {last}", inc.increment),
            );
        }
        last = inc.increment;
    }
    for p in &b.positions {
        if p.nodes.len() != m.nodes.len()
            || p.nodes_3d.len() != m.nodes_3d.len()
            || p.rigid_offsets.len() != m.rigid.len()
        {
            return err(
                schemas::POSITIONS,
                format!(
                    "positions of increment {} have {} nodes and {} rigid bodies; the model has {} and {}",
                    p.increment,
                    p.nodes.len(),
                    p.rigid_offsets.len(),
                    m.nodes.len(),
                    m.rigid.len()
                ),
            );
        }
    }
    let too_big = |topic: &str, i: usize| {
        if i > MAX_INCREMENT {
            Err((topic.to_string(), format!("increment number {i} is out of range")))
        } else {
            Ok(())
        }
    };
    for i in &b.iterations {
        too_big(schemas::ITERATION, i.increment)?;
    }
    for (&i, points) in &b.contact {
        too_big(schemas::CONTACT, i)?;
        if let Some(p) = points.iter().find(|p| p.pair >= m.contacts.len()) {
            return err(
                schemas::CONTACT,
                format!(
                    "a point of increment {i} is in pair {}; the model has {} pairs",
                    p.pair,
                    m.contacts.len()
                ),
            );
        }
    }
    for (&i, points) in &b.surface {
        too_big(schemas::SURFACE_CONTACT, i)?;
        let facets = |p: &crate::record::surface_contact::SurfacePointRecord| {
            let info = &m.surface_contacts[p.pair];
            let count = info.master_facets.len().max(usize::from(info.rigid.is_some()));
            let bad = |f: Option<usize>| f.is_some_and(|f| f >= count);
            info.slave_nodes[p.slave] != p.node || bad(p.facet) || bad(p.previous_facet)
        };
        if let Some(p) = points.iter().find(|p| facets(p)) {
            return err(
                schemas::SURFACE_CONTACT,
                format!(
                    "slave {} of pair `{}` at increment {i}: its node {} or facets {:?}, {:?} are not the model's",
                    p.slave, p.pair_name, p.node, p.facet, p.previous_facet
                ),
            );
        }
    }
    for c in &b.crossings {
        too_big(schemas::CROSSING, c.increment)?;
    }
    for l in &b.logs {
        too_big(schemas::LOG, l.increment)?;
    }
    for f in &b.interface {
        too_big(schemas::INTERFACE, f.increment)?;
        f.check().or_else(|what| err(schemas::INTERFACE, what))?;
        if f.first_pass >= m.contacts.len() || f.second_pass >= m.contacts.len() {
            return err(
                schemas::INTERFACE,
                format!(
                    "interface `{}` joins pairs {} and {}; the model has {} pairs",
                    f.name,
                    f.first_pass,
                    f.second_pass,
                    m.contacts.len()
                ),
            );
        }
    }
    Ok(())
}
