//! The shapes and motions of the `[[rigid]]` tables: the 2D outlines (polygon, outline
//! pieces, arcs) and the 3D analytic surfaces (plane, sphere), and the prescribed translation.

use super::types::RampSpec;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A regular polygon of `sides` facets inscribed in the circle `centre`, `radius`, turned so
/// that the middle of one facet is at `facet_at_deg`; the outline runs counter-clockwise
/// through its vertices from the last vertex at or before `from_deg` to the first at or after
/// `to_deg` (the facet-count study of a drum: `--set rigid.drum.polygon.sides=16`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PolygonSpec {
    pub centre: [f64; 2],
    /// Circumradius (the vertices' distance from the centre).
    pub radius: f64,
    pub sides: usize,
    pub from_deg: f64,
    pub to_deg: f64,
    #[serde(default)]
    pub facet_at_deg: f64,
}

impl PolygonSpec {
    /// The outline's points (vertices), counter-clockwise.
    pub fn vertices(&self) -> Vec<[f64; 2]> {
        let step = 360.0 / self.sides as f64;
        let angle = |k: i64| self.facet_at_deg + (k as f64 + 0.5) * step;
        let first = ((self.from_deg - self.facet_at_deg) / step - 0.5).floor() as i64;
        let last = ((self.to_deg - self.facet_at_deg) / step - 0.5).ceil() as i64;
        (first..=last)
            .map(|k| {
                let t = angle(k).to_radians();
                [
                    self.centre[0] + self.radius * t.cos(),
                    self.centre[1] + self.radius * t.sin(),
                ]
            })
            .collect()
    }
}

/// One piece of a composite rigid outline: exactly one of `line` or `arc`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PieceSpec {
    /// A polyline piece (≥ 2 points).
    pub line: Option<Vec<[f64; 2]>>,
    /// An arc piece.
    pub arc: Option<ArcSpec>,
}

#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ArcSpec {
    pub centre: [f64; 2],
    pub radius: f64,
    pub from_deg: f64,
    pub to_deg: f64,
    /// Where the rigid body is: `inside` the circle (a disc; the arc runs counter-clockwise,
    /// `from_deg < to_deg`) or `outside` it (a cavity; clockwise, `from_deg > to_deg`). When
    /// given it must agree with the orientation; `contrail check` shows it either way.
    pub side: Option<ArcSide>,
}

/// Side of an arc the rigid body is on.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ArcSide {
    /// The rigid body is the disc inside the circle (counter-clockwise arc).
    Inside,
    /// The rigid body surrounds the circle (clockwise arc).
    Outside,
}

impl ArcSide {
    /// `inside` or `outside`.
    pub fn name(self) -> &'static str {
        match self {
            ArcSide::Inside => "inside",
            ArcSide::Outside => "outside",
        }
    }

    /// The side implied by an arc's orientation.
    pub fn of(from_deg: f64, to_deg: f64) -> Self {
        if to_deg > from_deg {
            ArcSide::Inside
        } else {
            ArcSide::Outside
        }
    }
}

/// The prescribed translation of a rigid body, per component (default: none).
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MotionSpec {
    pub x: Option<RampSpec>,
    pub y: Option<RampSpec>,
    /// 3D scenes only.
    pub z: Option<RampSpec>,
}

/// A rigid plane (3D): the rigid body is the half-space behind it.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    /// A point of the plane.
    pub point: [f64; 3],
    /// Its outward normal (pointing away from the rigid body, towards the slaves); made unit
    /// by the builder, not zero.
    pub normal: [f64; 3],
}

/// A rigid round bar (3D): the infinite circular cylinder through `point` along `axis` is the
/// contact surface, the slaves outside it.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CylinderSpec {
    /// A point of the axis.
    pub point: [f64; 3],
    /// The axis direction (not zero; made unit).
    pub axis: [f64; 3],
    /// Radius (> 0).
    pub radius: f64,
}

/// A rigid ball (3D): its sphere is the contact surface, the slaves outside it.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    pub centre: [f64; 3],
    /// Radius (> 0).
    pub radius: f64,
}
