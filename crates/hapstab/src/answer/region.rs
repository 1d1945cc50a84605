//! The answer of the exact stable region (Section V, Figs. 4–6), as `hapstab boundary --json`
//! writes it: in N/m and Ns/m for a physical loop (with the paper's normalized view beside it
//! for the paper's loop), in α and β for the normalized one, with the edges of each polygon.

use serde::Serialize;

use crate::closed_loop::AffineFamily;
use crate::loop_spec::LoopInput;
use crate::model::Loop;
use crate::region::{EdgeKind, StableRegion};
use crate::system::System;

/// One edge of a region polygon: where it starts and what it lies on.
#[derive(Debug, Clone, Serialize)]
pub struct RegionEdge {
    /// Index of the edge's first vertex.
    pub start: usize,
    /// What the edge lies on (the z = 1 or z = −1 line, the complex-root curve, a window).
    #[serde(flatten)]
    pub kind: EdgeKind,
}

/// The region of a physical loop in N/m and Ns/m.
#[derive(Debug, Clone, Serialize)]
pub struct PhysicalRegion {
    /// K_max in N/m.
    pub k_max: f64,
    /// B at K_max in Ns/m.
    pub b_at_k_max: f64,
    /// False where K_max is a supremum: a corner of the region that only the damping
    /// `b_at_k_max` touches, approached as B → `b_at_k_max`.
    pub k_max_attained: bool,
    /// A damping (Ns/m) at which `k_stable_near_k_max` is stable: `b_at_k_max` when K_max is
    /// attained, one beside it for a supremum.
    pub b_stable_near_k_max: f64,
    /// A stiffness (N/m) within 1e-6 of K_max that the verdict confirms stable at
    /// `b_stable_near_k_max`.
    pub k_stable_near_k_max: f64,
    /// Area of the stable region in N²·s/m².
    pub area: f64,
    /// The polygons as arrays of [K, B] in N/m and Ns/m (counter-clockwise, first vertex
    /// not repeated).
    pub polygons: Vec<Vec<[f64; 2]>>,
    /// K and B of one wall unit: N/m per unit a and Ns/m per unit b (m/T² and m/T for the
    /// paper's plant: per unit α and β).
    pub wall_units: WallUnitsOut,
}

/// K and B of one wall unit (N/m per unit a, Ns/m per unit b).
#[derive(Debug, Clone, Serialize)]
pub struct WallUnitsOut {
    /// N/m per unit a.
    pub stiffness: f64,
    /// Ns/m per unit b.
    pub damping: f64,
}

/// The region of the paper's loop in normalized units.
#[derive(Debug, Clone, Serialize)]
pub struct NormalizedRegion {
    /// Largest stable α.
    pub alpha_max: f64,
    /// β at which it is reached.
    pub beta_at_alpha_max: f64,
    /// Area in α·β.
    pub area: f64,
    /// Closed polygons, each an array of [alpha, beta] (counter-clockwise, first vertex not
    /// repeated).
    pub polygons: Vec<Vec<[f64; 2]>>,
}

/// The normalized view of the paper's loop given in physical units (Table I).
#[derive(Debug, Clone, Serialize)]
pub struct RegionPaperView {
    /// Normalized stiffness γ = kT²/m.
    pub gamma: f64,
    /// Normalized damping δ = bT/m.
    pub delta: f64,
    /// Delay in samples.
    pub d: usize,
    /// Largest stable α.
    pub alpha_max: f64,
    /// β at which it is reached.
    pub beta_at_alpha_max: f64,
    /// Area in α·β.
    pub area: f64,
}

/// The region of a loop with its input echoed.
#[derive(Debug, Clone, Serialize)]
pub struct RegionAnswer {
    /// The loop (the form a loop file takes).
    pub input: LoopInput,
    /// A physical loop: the region in N/m and Ns/m.
    #[serde(flatten)]
    pub physical: Option<PhysicalRegion>,
    /// A normalized loop: the region in α and β.
    #[serde(flatten)]
    pub units: Option<NormalizedRegion>,
    /// Edge labels per polygon.
    pub edges: Vec<Vec<RegionEdge>>,
    /// The paper's loop given in physical units: its normalized view.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normalized: Option<RegionPaperView>,
}

impl PhysicalRegion {
    /// The region `r` of the family `fam` in N/m and Ns/m (its wall units times
    /// [`AffineFamily::to_physical`]; NaN where the region is empty).
    pub fn of(fam: &AffineFamily, r: &StableRegion) -> Self {
        let (k_max, b_at_k_max) = fam.to_physical(r.a_max, r.b_at_a_max);
        let (kpa, bpb) = fam.to_physical(1.0, 1.0);
        PhysicalRegion {
            k_max,
            b_at_k_max,
            k_max_attained: r.a_max_attained,
            b_stable_near_k_max: fam.to_physical(0.0, r.b_stable).1,
            k_stable_near_k_max: fam.to_physical(r.a_stable, 0.0).0,
            area: r.area * kpa * bpb,
            polygons: polygons(r, |a, b| {
                let (k, b) = fam.to_physical(a, b);
                [k, b]
            }),
            wall_units: WallUnitsOut {
                stiffness: kpa,
                damping: bpb,
            },
        }
    }
}

/// The polygons' vertices mapped by `f` from (α, β) (or wall units).
fn polygons(r: &StableRegion, f: impl Fn(f64, f64) -> [f64; 2]) -> Vec<Vec<[f64; 2]>> {
    r.polygons
        .iter()
        .map(|p| p.vertices.iter().map(|v| f(v.a, v.b)).collect())
        .collect()
}

/// The answer of the region `r` of a loop ([`System::region`]); `normalized` says whether the
/// loop is the paper's normalized one (m = T = 1).
pub fn region_answer(sys: &System, normalized: bool, r: &StableRegion) -> RegionAnswer {
    let fam = sys.family();
    let lp = sys.lp();
    let physical = !normalized;
    RegionAnswer {
        input: LoopInput::new(lp, normalized, None),
        physical: physical.then(|| PhysicalRegion::of(fam, r)),
        units: (!physical).then(|| NormalizedRegion {
            alpha_max: r.a_max,
            beta_at_alpha_max: r.b_at_a_max,
            area: r.area,
            polygons: polygons(r, |a, b| [a, b]),
        }),
        edges: r
            .polygons
            .iter()
            .map(|p| {
                p.edges
                    .iter()
                    .map(|e| RegionEdge {
                        start: e.start,
                        kind: e.kind,
                    })
                    .collect()
            })
            .collect(),
        normalized: RegionPaperView::of(lp, r).filter(|_| physical),
    }
}

impl RegionPaperView {
    /// The normalized view of the region `r` of the loop `lp` when it is the paper's loop
    /// ([`Loop::paper_view`]: Table I's γ, δ, d with α_max, its β and the area in α·β).
    pub fn of(lp: &Loop, r: &StableRegion) -> Option<Self> {
        lp.paper_view().map(|pp| RegionPaperView {
            gamma: pp.gamma,
            delta: pp.delta,
            d: lp.delay.samples,
            alpha_max: r.a_max,
            beta_at_alpha_max: r.b_at_a_max,
            area: r.area,
        })
    }
}
