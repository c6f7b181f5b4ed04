//! The checks a posture must pass in the cell, with the signed margin of every pair they test.

use super::bodies::{bodies, Body, Capsule, Part};
use super::check::{CheckKind, Margin, Thing};
use super::distance::{body_body, body_body_witness, body_box_witness, body_floor_witness};
use super::distance::{capsule_box_witness, closest_on_segment, Witness};
use super::motion::{part_carrier, Carrier, Deferred, MarginGradients, Margins};
use crate::setup::{Obstacle, Setup};
use nalgebra::{Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The tightest pair of one check.
#[derive(Debug, Clone, PartialEq)]
pub struct Check {
    /// Which check.
    pub kind: CheckKind,
    /// Whether it passes (`margin >= 0`).
    pub ok: bool,
    /// The smallest signed margin of its pairs: m, or rad for [`CheckKind::is_angle`].
    pub margin: f64,
    /// For the checks that require the clearance (floor, obstacles, self-collision, rope), the
    /// smallest distance between the pair's surfaces, m (negative: penetration); `None` for the
    /// others.
    pub clearance: Option<f64>,
    /// The names of the tightest pair, e.g. `("link 3", "floor")`.
    pub between: (String, String),
}

/// The feasibility of one posture: one [`Check`] per active check kind.
#[derive(Debug, Clone, PartialEq)]
pub struct Feasibility {
    /// The checks the setup asks for, in [`CheckKind::ALL`] order.
    pub checks: Vec<Check>,
}

impl Feasibility {
    /// Whether every check passes.
    pub fn feasible(&self) -> bool {
        self.checks.iter().all(|c| c.ok)
    }

    /// The checks that fail.
    pub fn violations(&self) -> impl Iterator<Item = &Check> {
        self.checks.iter().filter(|c| !c.ok)
    }

    /// The smallest distance between bodies (and the rope) that must keep the clearance, m;
    /// `None` without `[cell]`.
    pub fn min_clearance(&self) -> Option<f64> {
        self.checks
            .iter()
            .filter_map(|c| c.clearance)
            .reduce(f64::min)
    }

    /// The check of lengths (the cell's, the tracker's line of sight and `[constraints]`: every
    /// check but the bounds and the incidence) with the smallest margin, the posture's distance
    /// to its nearest constraint (beyond what the checker keeps, [`Checker::keeping`]); `None`
    /// without such checks.
    pub fn min_margin(&self) -> Option<&Check> {
        self.checks
            .iter()
            .filter(|c| !c.kind.is_angle())
            .min_by(|a, b| a.margin.total_cmp(&b.margin))
    }
}

/// Postures of the sample that decides which body pairs always touch.
const CONTACT_SAMPLE: usize = 64;

/// The feasibility checker of a setup: which checks apply and which body pairs are tested, worked
/// out once, for any number of postures.
#[derive(Debug, Clone)]
pub struct Checker<'a> {
    setup: &'a Setup,
    kinds: Vec<CheckKind>,
    /// Capsule index pairs of the self-collision check.
    pairs: Vec<(usize, usize)>,
    /// The margin every check but the bounds keeps on top of what it requires, m
    /// ([`Checker::keeping`]).
    keep: f64,
}

impl<'a> Checker<'a> {
    /// The checker of `setup`: bounds and `[constraints]` always; floor, obstacles, self-collision
    /// and rope with a `[cell]`; line of sight (and incidence, with `max_incidence_deg`) with a
    /// `[tracker]`.
    ///
    /// Self-collision tests pairs of capsules of non-adjacent parts (links whose chain between
    /// them has zero length, like links 4 and 6 of a spherical wrist, count as adjacent) and the
    /// tool against the base and links 1-3, except pairs closer than the clearance in every one
    /// of 64 seeded postures spread over the bounds: those overlap by construction (the upper
    /// arm and the forearm at an offset elbow), as a collision checker's "always in contact"
    /// list. When no pair is left (bodies as large as the robot), self-collision is not among
    /// [`Checker::kinds`].
    pub fn new(setup: &'a Setup) -> Self {
        let mut kinds = vec![CheckKind::Bounds];
        if let Some(cell) = &setup.cell() {
            if cell.floor_z.is_some() {
                kinds.push(CheckKind::Floor);
            }
            if !cell.obstacles.is_empty() {
                kinds.push(CheckKind::Obstacles);
            }
            kinds.extend([CheckKind::SelfCollision, CheckKind::Rope]);
        }
        if let Some(t) = &setup.tracker() {
            kinds.push(CheckKind::LineOfSight);
            if t.max_incidence.is_some() {
                kinds.push(CheckKind::Incidence);
            }
        }
        if setup.constraints().loading_point_min_z.is_some() {
            kinds.push(CheckKind::LoadingPointHeight);
        }
        if setup.constraints().anchor_below_loading_point {
            kinds.push(CheckKind::AnchorBelow);
        }
        let mut checker = Self {
            setup,
            kinds,
            pairs: Vec::new(),
            keep: 0.0,
        };
        if setup.cell().is_some() {
            checker.pairs = checker.self_pairs();
            if checker.pairs.is_empty() {
                // Every pair overlaps in every sampled posture (bodies as large as the robot):
                // nothing is left to test.
                checker.kinds.retain(|&k| k != CheckKind::SelfCollision);
            }
        }
        checker
    }

    /// The setup.
    pub fn setup(&self) -> &'a Setup {
        self.setup
    }

    /// This checker with every check but the bounds keeping a margin of `keep` (m, finite and
    /// `>= 0`; a negative or non-finite value counts as 0) on top of what it requires, so that
    /// a posture it passes survives a cell, tracker or robot that is off by up to `keep`: the
    /// bodies keep the clearance plus `keep` from the floor, the obstacles, each other and the
    /// rope; a line of sight passes `keep` from every body and obstacle; the tool, which the
    /// rope and the line of sight start from, beyond its radius (and the clearance, for the
    /// rope) from the loading or the measuring point, as without `keep`; the loading point
    /// stands `keep` above its lowest height and the anchor; the incidence angle keeps `keep /
    /// L` rad below its largest (`L` the length of the line of sight: the angle a tracker moved
    /// by `keep` across the line turns it by). Every margin ([`Checker::margins`],
    /// [`Checker::feasibility`]) is then the plain checker's less `keep` (the same pairs, the
    /// same distances: one margin computation for the design, `evaluate` and the plan), and its
    /// gradient exact.
    pub fn keeping(mut self, keep: f64) -> Self {
        self.keep = if keep.is_finite() { keep.max(0.0) } else { 0.0 };
        self
    }

    /// The margin every check but the bounds keeps ([`Checker::keeping`]), m: 0 unless asked.
    pub fn keep(&self) -> f64 {
        self.keep
    }

    /// The check kinds that apply, in [`CheckKind::ALL`] order.
    pub fn kinds(&self) -> &[CheckKind] {
        &self.kinds
    }

    /// Whether any check beyond the bounds applies.
    pub fn constrains(&self) -> bool {
        self.kinds.len() > 1
    }

    /// The feasibility of posture `q` (axis angles, rad), the external axes (if any) at the
    /// cell's origin and the boxes a positioner carries at `e = 0`.
    pub fn feasibility(&self, q: &Vector6<f64>) -> Feasibility {
        self.feasibility_at(q, &[])
    }

    /// The feasibility of posture `q` (axis angles, rad) with the cell's external axes at `e`
    /// (SI, the cell's order, [`crate::robot::external`]): the arm's bodies on their carriage,
    /// its base at `C(e) * base` ([`crate::Robot::frames_at`]), against the floor, the fixed
    /// obstacles, the rope's anchor and the tracker, which stand in the cell frame, and the
    /// boxes a positioner carries where `e` turns them ([`crate::setup::Obstacle::at`]). Empty
    /// `e` (or a robot without external axes): [`Checker::feasibility`], the carried boxes at
    /// `e = 0`.
    pub fn feasibility_at(&self, q: &Vector6<f64>, e: &[f64]) -> Feasibility {
        let mut exact = Margins::new(false, false);
        self.collect(q, e, &mut exact);
        let margins = exact.margins;
        let checks = self
            .kinds
            .iter()
            .filter_map(|&kind| {
                let tightest = margins
                    .iter()
                    .filter(|m| m.kind == kind)
                    .min_by(|a, b| a.margin.total_cmp(&b.margin))?;
                let body = matches!(
                    kind,
                    CheckKind::Floor
                        | CheckKind::Obstacles
                        | CheckKind::SelfCollision
                        | CheckKind::Rope
                );
                Some(Check {
                    kind,
                    ok: tightest.margin >= 0.0,
                    margin: tightest.margin,
                    clearance: body.then_some(tightest.margin + tightest.required),
                    between: (
                        tightest.between.0.name(self.setup),
                        tightest.between.1.name(self.setup),
                    ),
                })
            })
            .collect();
        Feasibility { checks }
    }

    /// The sum over the failing pairs of how much they fail by (m and rad): 0 when `q` passes
    /// every check.
    pub fn violation(&self, q: &Vector6<f64>) -> f64 {
        if !self.constrains() {
            return 0.0;
        }
        self.margins(q).iter().map(|m| (-m.margin).max(0.0)).sum()
    }

    /// The signed margin of every pair every active check tests at posture `q` (axis angles,
    /// rad), in [`Checker::kinds`] order; the same pairs in every posture. The broad phase: a
    /// pair of bodies (or a body and an obstacle, the floor, the rope or a line of sight) whose
    /// bounding spheres are more than `FAR_MARGIN` beyond what the check requires apart gets
    /// the spheres' gap as its margin (a lower bound of its distance, never failing) instead of
    /// the exact distance ([`Checker::feasibility`] works every distance out).
    pub fn margins(&self, q: &Vector6<f64>) -> Vec<Margin> {
        self.margins_at(q, &[])
    }

    /// [`Checker::margins`] with the cell's external axes at `e`, the arm on its carriage
    /// ([`Checker::feasibility_at`]).
    pub fn margins_at(&self, q: &Vector6<f64>, e: &[f64]) -> Vec<Margin> {
        let mut out = Margins::new(false, true);
        self.collect(q, e, &mut out);
        out.margins
    }

    /// [`Checker::margins`] (with its broad phase: a far pair's gradient is its spheres' gap's)
    /// and what their gradients with respect to the six axis angles (m/rad,
    /// or rad/rad for angles) are worked out from, on demand (`MarginGradients::gradient`), so
    /// that a caller pays only for the gradients it uses: exact, from the witness points of each
    /// distance (the normal times the difference of the witness points' velocities) and the
    /// derivatives of the incidence angle and the heights. Where the closest points of a pair are
    /// not unique (a tie) the gradient is one of the one-sided ones.
    ///
    /// # Examples
    /// The gradient of the floor margin of a posture against central differences.
    /// ```
    /// use stiffid_core::cell::{CheckKind, Checker};
    /// let text = stiffid_core::setup::builtin_text("zhang2021-comau-nj165")?.to_string()
    ///     + "[cell]\nfloor_z_mm = 0.0\n";
    /// let setup = stiffid_core::setup::parse(&text, "cell.toml", |r, _| stiffid_core::robot::presets::get(r))?;
    /// let checker = Checker::new(&setup);
    /// let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(3);
    /// let q = stiffid_core::robot::ik::random_posture(setup.robot(), &mut rng);
    /// let (margins, gradients) = checker.margins_and_gradients(&q);
    /// let i = margins.iter().position(|m| m.kind == CheckKind::Floor).unwrap();
    /// let h = 1e-6;
    /// for a in 0..6 {
    ///     let (mut up, mut down) = (q, q);
    ///     up[a] += h;
    ///     down[a] -= h;
    ///     let fd = (checker.margins(&up)[i].margin - checker.margins(&down)[i].margin) / (2.0 * h);
    ///     assert!((gradients.gradient(i)[a] - fd).abs() < 1e-6);
    /// }
    /// # Ok::<(), stiffid_core::Error>(())
    /// ```
    pub fn margins_and_gradients(&self, q: &Vector6<f64>) -> (Vec<Margin>, MarginGradients) {
        let mut out = Margins::new(true, true);
        self.collect(q, &[], &mut out);
        out.finish()
    }

    /// The margins of posture `q` with the external axes at `e` (the arm on its carriage;
    /// empty: at the cell's origin) into `out`.
    fn collect(&self, q: &Vector6<f64>, e: &[f64], out: &mut Margins) {
        let s = self.setup;
        for a in 0..6 {
            let (low, high) = (q[a] - s.bounds().lower[a], s.bounds().upper[a] - q[a]);
            let m = low.min(high);
            let m = if m.is_nan() { f64::NEG_INFINITY } else { m };
            let sign = if low <= high { 1.0 } else { -1.0 };
            let axis = Thing::Axis(a);
            let m = margin(CheckKind::Bounds, m, 0.0, axis, axis);
            out.push(m, Deferred::Value(Vector6::ith(a, sign)));
        }
        if !self.constrains() {
            return;
        }
        let frames = match e.is_empty() {
            true => s.robot().frames(q),
            false => s.robot().frames_at(q, e),
        };
        let bodies = bodies(s.arm(), &frames);
        let loading = frames.point(&s.tool().loading_point);
        let obstacles = s.cell().map(|c| c.obstacles_at(s.robot(), e));
        let obstacles = obstacles.as_deref().unwrap_or(&[]);
        if let Some(cell) = &s.cell() {
            self.body_margins(&bodies, &loading, cell, obstacles, out);
        }
        if let Some(t) = &s.tracker() {
            for (i, p) in s.tool().measuring_points.iter().enumerate() {
                let p = frames.point(p);
                let sight = line(&t.position, &p, s.geometry().tool_radius);
                let things = (&bodies[..], obstacles);
                self.line_margins(
                    CheckKind::LineOfSight,
                    &sight,
                    Thing::Sight(i),
                    things,
                    self.keep,
                    out,
                );
                if let Some(max) = t.max_incidence {
                    let normal = frames.flange.rotation * t.measuring_normals[i];
                    let sight = t.position - p;
                    let angle = normal.angle(&sight);
                    let turn = self.keep / sight.norm();
                    let m = Thing::MeasuringPoint(i);
                    let m = margin(CheckKind::Incidence, max - angle - turn, turn, m, m);
                    let keep = self.keep;
                    out.push(
                        m,
                        Deferred::Angle {
                            normal,
                            sight,
                            p,
                            keep,
                        },
                    );
                }
            }
        }
        let c = &s.constraints();
        let height = Deferred::Height(loading);
        if let Some(z) = c.loading_point_min_z {
            let (l, f) = (Thing::LoadingPoint, Thing::Floor);
            let m = margin(
                CheckKind::LoadingPointHeight,
                loading.z - z - self.keep,
                self.keep,
                l,
                f,
            );
            out.push(m, height);
        }
        if c.anchor_below_loading_point {
            let (l, a) = (Thing::LoadingPoint, Thing::Anchor);
            let m = margin(
                CheckKind::AnchorBelow,
                loading.z - s.load().anchor.z - self.keep,
                self.keep,
                l,
                a,
            );
            out.push(m, height);
        }
        out.frames(frames);
    }

    fn body_margins(
        &self,
        bodies: &[Body],
        loading: &Vector3<f64>,
        cell: &crate::setup::Cell,
        obstacles: &[Obstacle],
        out: &mut Margins,
    ) {
        let c = cell.clearance + self.keep;
        if let Some(z) = cell.floor_z {
            for b in bodies.iter().filter(|b| b.part() != Part::Base) {
                let (centre, r) = b.bound();
                let foot = Vector3::new(centre.x, centre.y, z);
                // Only a sphere above the floor is far from it: one below is in it.
                let far = (centre.z > z).then(|| far_gap(out, &centre, &foot, r, c));
                let (d, w) = match far.flatten() {
                    Some((d, w)) => (d, w),
                    None => body_floor_witness(b, z),
                };
                let (pb, f) = (Thing::Part(b.part()), Thing::Floor);
                let m = margin(CheckKind::Floor, d - c, c, pb, f);
                out.witness(m, part_carrier(b.part()), Carrier::Fixed, Some(w));
            }
        }
        for b in bodies {
            let (centre, r) = b.bound();
            for (i, o) in obstacles.iter().enumerate() {
                let inside = o.nearest(&centre);
                let (d, w) = match far_gap(out, &centre, &inside, r, c) {
                    Some((d, w)) => (d, Some(w)),
                    None => body_box_witness(b, o),
                };
                let (pb, oi) = (Thing::Part(b.part()), Thing::Obstacle(i));
                let m = margin(CheckKind::Obstacles, d - c, c, pb, oi);
                out.witness(m, part_carrier(b.part()), Carrier::Fixed, w);
            }
        }
        for &(i, j) in &self.pairs {
            let ((ci, ri), (cj, rj)) = (bodies[i].bound(), bodies[j].bound());
            let (d, w) = match far_gap(out, &ci, &cj, ri + rj, c) {
                Some((d, w)) => (d, Some(w)),
                None => body_body_witness(&bodies[i], &bodies[j]),
            };
            let (pi, pj) = (bodies[i].part(), bodies[j].part());
            let m = margin(
                CheckKind::SelfCollision,
                d - c,
                c,
                Thing::Part(pi),
                Thing::Part(pj),
            );
            out.witness(m, part_carrier(pi), part_carrier(pj), w);
        }
        let exempt = self.setup.geometry().tool_radius + cell.clearance;
        let rope = line(&self.setup.load().anchor, loading, exempt);
        let things = (bodies, obstacles);
        self.line_margins(CheckKind::Rope, &rope, Thing::Rope, things, c, out);
    }

    /// Margins of a line (rope or sight) against every body and obstacle (where they stand).
    fn line_margins(
        &self,
        kind: CheckKind,
        line: &Line,
        thing: Thing,
        (bodies, obstacles): (&[Body], &[Obstacle]),
        required: f64,
        out: &mut Margins,
    ) {
        for b in bodies {
            let (segment, carrier) = match b.part() {
                Part::Tool => (line.short.as_ref(), line.short_carrier),
                _ => (Some(&line.full), line.full_carrier),
            };
            let (m, w) = match segment {
                Some(s) => {
                    let (centre, r) = b.bound();
                    let near = closest_on_segment(s, &centre);
                    let (d, w) = match far_gap(out, &near, &centre, r, required) {
                        Some((d, w)) => (d, Some(w)),
                        None => body_body_witness(&Body::Capsule(*s), b),
                    };
                    (d - required, w)
                }
                None => (f64::INFINITY, None),
            };
            let m = margin(kind, m, required, thing, Thing::Part(b.part()));
            out.witness(m, carrier, part_carrier(b.part()), w);
        }
        for (i, o) in obstacles.iter().enumerate() {
            let (d, w) = capsule_box_witness(&line.full, o);
            let m = margin(kind, d - required, required, thing, Thing::Obstacle(i));
            out.witness(m, line.full_carrier, Carrier::Fixed, w);
        }
    }

    /// The self-collision pairs: non-adjacent parts, not in contact in every sampled posture.
    fn self_pairs(&self) -> Vec<(usize, usize)> {
        let s = self.setup;
        let rest = bodies(s.arm(), &s.robot().frames(&s.bounds().lower));
        let candidates: Vec<(usize, usize)> = (0..rest.len())
            .flat_map(|i| (i + 1..rest.len()).map(move |j| (i, j)))
            .filter(|&(i, j)| !adjacent(&rest, rest[i].part(), rest[j].part()))
            .collect();
        let clearance = s.cell().map_or(0.0, |c| c.clearance);
        let mut free = vec![false; candidates.len()];
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        for _ in 0..CONTACT_SAMPLE {
            let q = Vector6::from_fn(|a, _| {
                rng.random_range(s.bounds().lower[a]..=s.bounds().upper[a])
            });
            let bodies = bodies(s.arm(), &s.robot().frames(&q));
            for (k, &(i, j)) in candidates.iter().enumerate() {
                let ((ci, ri), (cj, rj)) = (bodies[i].bound(), bodies[j].bound());
                free[k] = free[k]
                    || (ci - cj).norm() - ri - rj >= clearance
                    || body_body(&bodies[i], &bodies[j]) >= clearance;
            }
        }
        candidates
            .into_iter()
            .zip(free)
            .filter_map(|(p, f)| f.then_some(p))
            .collect()
    }
}

/// Whether two parts need no self-collision test: the same part, neighbours in the chain (with
/// zero-length parts between them skipped), or the tool and a part other than the base and links
/// 1-3.
fn adjacent(bodies: &[Body], p: Part, q: Part) -> bool {
    let (lo, hi) = (p.index().min(q.index()), p.index().max(q.index()));
    if hi == Part::Tool.index() {
        return lo > 3;
    }
    let zero_length = |k: usize| {
        bodies
            .iter()
            .filter(|b| b.part().index() == k)
            .all(Body::degenerate)
    };
    (lo + 1..hi).all(zero_length)
}

/// How far beyond what a check requires (m) a pair's bounding spheres must be apart for the
/// broad phase to take their gap as its margin ([`Checker::margins`]): 0.1 m, 50 times the
/// smoothing of the searches' constraints, so that where a check's smallest margin is within
/// 17 mm of failing such a pair weighs less than `2^-60` in its smooth minimum (and the
/// constraint's value and gradient are those of the exact distances, to the rounding).
pub(crate) const FAR_MARGIN: f64 = 0.1;

/// The gap `|b - a| - radii` between two spheres (centres `a`, `b`) and its witness, when the
/// broad phase is on and it exceeds `required` by more than [`FAR_MARGIN`].
fn far_gap(
    out: &Margins,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    radii: f64,
    required: f64,
) -> Option<(f64, Witness)> {
    let d = b - a;
    let n = d.norm();
    let gap = n - radii;
    (out.broad && gap - required > FAR_MARGIN && n > 0.0).then(|| {
        let witness = Witness {
            a: *a,
            b: *b,
            normal: d / n,
        };
        (gap, witness)
    })
}

/// A rope or line of sight as capsules of radius 0: the whole segment, and the part the tool must
/// clear (`None` when too short), with how their points move.
struct Line {
    full: Capsule,
    short: Option<Capsule>,
    full_carrier: Carrier,
    short_carrier: Carrier,
}

/// The line from the fixed point `from` to `to` (on the tool), and its part beyond `exempt` (m)
/// of `to`.
fn line(from: &Vector3<f64>, to: &Vector3<f64>, exempt: f64) -> Line {
    let d = from - to;
    let length = d.norm();
    let capsule = |b: Vector3<f64>| Capsule {
        part: Part::Tool,
        a: *from,
        b,
        radius: 0.0,
    };
    let short = (length > exempt).then(|| capsule(to + d * (exempt / length)));
    Line {
        full: capsule(*to),
        full_carrier: Carrier::line(from, to, to, 0.0),
        short_carrier: Carrier::line(from, to, &short.map_or(*to, |s| s.b), exempt),
        short,
    }
}

fn margin(kind: CheckKind, margin: f64, required: f64, a: Thing, b: Thing) -> Margin {
    Margin {
        kind,
        margin,
        required,
        between: (a, b),
    }
}

/// The feasibility of posture `q` (axis angles, rad) in the setup's cell: a [`Checker`] built for
/// this one posture (build one [`Checker`] to check many).
pub fn feasibility(setup: &Setup, q: &Vector6<f64>) -> Feasibility {
    Checker::new(setup).feasibility(q)
}
