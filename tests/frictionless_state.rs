//! A closed point of a frictionless pair is recorded as `slip` (without friction there is
//! no stick), and the record's schema says so where the field is described.
//! Scene `hertz` (μ = 0): every closed point of every increment is `slip`.
mod common;

use contrail::contact::law::ContactState;

#[test]
fn frictionless_closed_points_are_slip_and_the_schema_says_so() {
    let p = common::scene("hertz", &[]);
    assert!(p.model.contacts.iter().all(|c| c.law.mu == 0.0));
    let (_, m) = common::solve_ok(&p);
    let closed: Vec<_> = m
        .contact
        .iter()
        .flatten()
        .filter(|c| c.state != ContactState::Open)
        .collect();
    assert!(!closed.is_empty());
    assert!(closed.iter().all(|c| c.state == ContactState::Slip));
    let schema = include_str!("../schemas/contact.schema.json");
    assert!(schema.contains("a closed point of a frictionless pair (`μ = 0`) is `slip`"));
}
