//! The design's identification Jacobian of one posture and the exact derivative of a criterion
//! through it.
//!
//! Every column of the identification Jacobian ([`ErrorModel::jacobian`]) is the velocity of
//! the measuring point `b` under a unit motion of a screw: a rotation about the unit axis `s`
//! through `o` (column `s x (b - o)`) or a translation along `s` (column `s`), the screw fixed in
//! link `L` of the chain (moved by the joints `j < L`: 0 for the measurement frame, `i` for the
//! errors of joint `i` (0-based, they sit before its rotation), 6 for a measuring point in the
//! flange). A gravity term's column is the point Jacobian's column of its joint (a weighted sum
//! of joint screws) times its torque regressor `y(q)`. So the derivative of a column with respect
//! to the kinematic angle `theta_j` is `z_j x col` when joint `j` moves the screw (`j < L`), and
//! otherwise `s x (z_j x (b - o_j))` for a rotation and 0 for a translation (`z_j`, `o_j` joint
//! `j`'s axis and a point on it). For a criterion `f` with gradient `G` with respect to the
//! Jacobian (3 rows `g_c` per reading and column), this sums to
//!
//! ```text
//! df/dtheta_j = z_j . [ sum_{L_c > j} col_c x g_c  +  (b - o_j) x sum_{rotations, L_c <= j} g_c x s_c ]
//!               + sum_t (g_t . col_t / y_t) dy_t/dtheta_j
//! ```
//!
//! per reading, and `df/dq = M^T df/dtheta` through the axis map. The regressors' derivatives
//! follow from the same rule: `y` sums `(z_i x arm) . g` over joint axes `i` and link points or
//! directions `arm` of link `l >= i`.
//!
//! The design Jacobian is evaluated on the nominal chain at the commanded posture (no deflection
//! under gravity: it changes the columns by a relative amount of the deflection's size, micro
//! radians, as the gravity regressors themselves are taken on the nominal chain).

use nalgebra::{DMatrix, DVector, Matrix6, Point3, Vector3, Vector6};
use stiffid_core::robot::kinematics::Coordinates;
use stiffid_core::Frames;
use stiffid_metrology::calibration::error_model::{Component, Target};
use stiffid_metrology::calibration::gravity::{Term, G};
use stiffid_metrology::calibration::ErrorModel;

/// A kept column of the design Jacobian: what it moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Column {
    /// The frame's translation along base axis `0..3`: constant.
    FrameTranslation(usize),
    /// The frame's rotation about base axis `0..3`, through the origin.
    FrameRotation(usize),
    /// Measuring point `point`'s coordinate `axis` (flange frame).
    Point { point: usize, axis: usize },
    /// An error of joint `joint` (0-based).
    Joint { joint: usize, component: Component },
    /// Gravity term `term` (index in the gravity model's terms).
    Gravity { term: usize, joint: usize },
    /// A parameter of the carrier under the arm (a track's direction or error motion): slot
    /// `0..` of [`Layout::carrier`]; affine in the point, `a x b + c` with `a` fixed in the cell.
    Carrier(usize),
    /// A compliance under an applied wrench: zero on the unloaded readings a design reads (and
    /// an error map's coefficient, which no design's model holds).
    Unloaded,
}

impl Column {
    /// The column of the model's parameter `target` (gravity terms at `index` among the terms).
    pub(super) fn of(target: Target, model: &ErrorModel, index: usize) -> Self {
        match target {
            Target::Frame(a) if a < 3 => Column::FrameTranslation(a),
            Target::Frame(a) => Column::FrameRotation(a - 3),
            Target::Point { point, axis } => Column::Point { point, axis },
            Target::Joint { joint, component } => Column::Joint { joint, component },
            Target::Gravity(term) => Column::Gravity {
                term: index - model.gravity_start(),
                joint: term.joint(),
            },
            Target::Compliance { .. }
            | Target::Map { .. }
            | Target::Backlash { .. }
            | Target::External { .. }
            | Target::Table { .. } => Column::Unloaded,
        }
    }
}

/// What one posture needs for its rows and their derivative.
pub(super) struct Posture {
    frames: Frames,
    /// Each joint's error basis `(u, v)` in the base frame (before its rotation).
    u: [Vector3<f64>; 6],
    v: [Vector3<f64>; 6],
    /// The gravity terms' regressors and their derivatives in the kinematic angles.
    regressors: Vec<f64>,
    regressor_gradients: Vec<Vector6<f64>>,
    /// The base-frame position of every measuring point.
    points: Vec<Vector3<f64>>,
    /// Per measuring point, the lever `b - o_i` of every joint axis and the point Jacobian's
    /// kinematic columns `z_i x (b - o_i)`.
    levers: Vec<[Vector3<f64>; 6]>,
    screws: Vec<[Vector3<f64>; 6]>,
    /// Per measuring point, the point Jacobian's column of every spring (the springs'
    /// coordinates); empty without gravity terms.
    springs: Vec<[Vector3<f64>; 6]>,
    /// Per measuring point, the column of every carrier slot; and each slot's turn axis `a`
    /// (its column is `a x b + c`): empty without a carrier.
    carrier: Vec<Vec<Vector3<f64>>>,
    carrier_axes: Vec<Vector3<f64>>,
}

/// The model, its kept parameters' columns and scales, and the measuring points (flange frame,
/// m, nominal).
#[derive(Debug, Clone)]
pub(super) struct Layout {
    pub(super) model: ErrorModel,
    pub(super) columns: Vec<Column>,
    pub(super) scales: Vec<f64>,
    pub(super) points: Vec<Vector3<f64>>,
    /// The kept carrier parameters' indices in the model, by slot ([`Column::Carrier`]).
    carrier: Vec<usize>,
    /// The values the columns are taken at (the rigid nominal chain).
    pub(super) values: DVector<f64>,
}

impl Layout {
    /// The layout of the parameters `kept` of `model`, scaled by `scales` (one per kept).
    /// The layout of the parameters `kept` of `model`, scaled by `scales` (one per kept), its
    /// columns taken at `values`.
    pub(super) fn new(
        model: ErrorModel,
        kept: &[usize],
        scales: Vec<f64>,
        values: DVector<f64>,
    ) -> Self {
        let carriers = model.robot().external().map_or(0, |x| x.carrier_len());
        let mut carrier = Vec::new();
        let columns = (kept.iter())
            .map(|&c| match model.parameters()[c].target {
                Target::External { axis, .. } if axis < carriers => {
                    carrier.push(c);
                    Column::Carrier(carrier.len() - 1)
                }
                target => Column::of(target, &model, c),
            })
            .collect();
        let points = (0..model.points())
            .map(|k| model.point(&values, k))
            .collect();
        Layout {
            model,
            columns,
            scales,
            points,
            carrier,
            values,
        }
    }

    /// The layout of the model's parameters `kept` (a subset of this one's, model indices)
    /// with their `scales`, taken at the same values.
    pub(super) fn subset(&self, kept: &[usize], scales: Vec<f64>) -> Layout {
        Layout::new(self.model.clone(), kept, scales, self.values.clone())
    }

    /// The rows of the Jacobian: 3 per measuring point and posture.
    pub(super) fn rows(&self, postures: usize) -> usize {
        3 * self.points.len() * postures
    }

    /// The terms of posture `q` (axis angles, rad) with the external axes at `e` (SI, the
    /// cell's order; empty without).
    pub(super) fn posture(&self, q: &Vector6<f64>, e: &[f64]) -> Posture {
        let robot = self.model.robot();
        let frames = robot.frames_at(q, e);
        let mut u = [Vector3::zeros(); 6];
        let mut v = [Vector3::zeros(); 6];
        for i in 0..6 {
            let before = if i == 0 {
                frames.base
            } else {
                frames.joints[i - 1]
            };
            let r = (before * robot.joints()[i].pre).rotation;
            let basis = self.model.basis(i);
            u[i] = r * basis.u;
            v[i] = r * basis.v;
        }
        let (regressors, regressor_gradients) = regressors(&self.model, &frames);
        let points: Vec<Vector3<f64>> = self.points.iter().map(|c| frames.point(c)).collect();
        let levers: Vec<[Vector3<f64>; 6]> = (points.iter())
            .map(|b| std::array::from_fn(|i| b - frames.axis_points[i]))
            .collect();
        let screws: Vec<[Vector3<f64>; 6]> = (levers.iter())
            .map(|r| std::array::from_fn(|i| frames.axis_directions[i].cross(&r[i])))
            .collect();
        let springs = match regressors.is_empty() {
            true => Vec::new(),
            false => (screws.iter())
                .map(|s| {
                    std::array::from_fn(|joint| {
                        let w = self.spring_weights(joint);
                        (0..6).map(|i| s[i] * w[i]).sum()
                    })
                })
                .collect(),
        };
        let (carrier, carrier_axes) = self.carrier_terms(&points, e);
        Posture {
            frames,
            u,
            v,
            regressors,
            regressor_gradients,
            points,
            levers,
            screws,
            springs,
            carrier,
            carrier_axes,
        }
    }

    /// The carrier slots' columns at every point of `points` (cell frame, m) at `e`, and their
    /// turn axes `a` (a column is `a x b + c`: from the columns at the origin and at the unit
    /// x and y points, `a = (d_y.z, -d_x.z, d_x.y)` with `d = a x unit`).
    pub(super) fn carrier_terms(
        &self,
        points: &[Vector3<f64>],
        e: &[f64],
    ) -> (Vec<Vec<Vector3<f64>>>, Vec<Vector3<f64>>) {
        if self.carrier.is_empty() {
            return (Vec::new(), Vec::new());
        }
        let at = |b: &Vector3<f64>| {
            let mut out = vec![Vector3::zeros(); self.carrier.len()];
            self.model.carrier_columns(&self.values, e, b, |c, col| {
                if let Some(slot) = self.carrier.iter().position(|&k| k == c) {
                    out[slot] = col;
                }
            });
            out
        };
        let origin = at(&Vector3::zeros());
        let (x, y) = (at(&Vector3::x()), at(&Vector3::y()));
        let axes = (0..self.carrier.len())
            .map(|s| {
                let (dx, dy) = (x[s] - origin[s], y[s] - origin[s]);
                Vector3::new(dy.z, -dx.z, dx.y)
            })
            .collect();
        (points.iter().map(at).collect(), axes)
    }

    /// The unscaled column `c` at measuring point `k` of posture `p`.
    fn column(&self, p: &Posture, c: Column, k: usize) -> Vector3<f64> {
        match c {
            Column::Unloaded => Vector3::zeros(),
            Column::FrameTranslation(a) => Vector3::ith(a, 1.0),
            Column::FrameRotation(a) => Vector3::<f64>::ith(a, 1.0).cross(&p.points[k]),
            Column::Point { point, axis } => match point == k {
                true => p.frames.flange.rotation * Vector3::ith(axis, 1.0),
                false => Vector3::zeros(),
            },
            Column::Joint {
                joint: i,
                component,
            } => match component {
                Component::Theta => p.screws[k][i],
                Component::D => p.frames.axis_directions[i],
                Component::A => p.u[i],
                Component::Alpha => p.u[i].cross(&p.levers[k][i]),
                Component::Beta => p.v[i].cross(&p.levers[k][i]),
                Component::B => p.v[i],
            },
            Column::Gravity { term, joint } => p.springs[k][joint] * p.regressors[term],
            Column::Carrier(slot) => p.carrier[k][slot],
        }
    }

    /// The kinematic joints' weights in the spring coordinate `joint` (a column of `M` in axis
    /// coordinates, a unit vector in kinematic ones).
    fn spring_weights(&self, joint: usize) -> Vector6<f64> {
        match self.model.gravity().coordinates() {
            Coordinates::Kinematic => Vector6::ith(joint, 1.0),
            Coordinates::Axis => self.model.robot().axis_map().matrix.column(joint).into(),
        }
    }

    /// Writes the scaled rows of posture `p` (3 per measuring point) into `j` from row `row`.
    pub(super) fn write_rows(&self, p: &Posture, j: &mut DMatrix<f64>, row: usize) {
        for (c, (column, scale)) in self.columns.iter().zip(&self.scales).enumerate() {
            for k in 0..p.points.len() {
                let col = self.column(p, *column, k) * *scale;
                j.fixed_view_mut::<3, 1>(row + 3 * k, c).copy_from(&col);
            }
        }
    }

    /// `df/dq` (axis angles) of posture `p` given `g`, the gradient of `f` with respect to the
    /// scaled Jacobian `j`, at their rows from `row` (module docs).
    pub(super) fn gradient(
        &self,
        p: &Posture,
        j: &DMatrix<f64>,
        g: &DMatrix<f64>,
        row: usize,
    ) -> Vector6<f64> {
        let f = &p.frames;
        let mut theta = Vector6::zeros();
        let mut eta = vec![0.0; p.regressors.len()];
        for k in 0..p.points.len() {
            // by_link[L]: sum of col x g over the columns of link L; turns[L]: sum of g x s over
            // its rotations (L = 7 slots: 0..=6).
            let mut by_link = [Vector3::zeros(); 7];
            let mut turns = [Vector3::zeros(); 7];
            for (c, (column, scale)) in self.columns.iter().zip(&self.scales).enumerate() {
                let gs: Vector3<f64> = g.fixed_view::<3, 1>(row + 3 * k, c).into_owned();
                if gs == Vector3::zeros() || *scale == 0.0 {
                    continue;
                }
                // col x g of the unscaled column and gradient: the scaled column times the
                // gradient with respect to it.
                let js: Vector3<f64> = j.fixed_view::<3, 1>(row + 3 * k, c).into_owned();
                let gc = gs * *scale;
                match *column {
                    Column::FrameTranslation(_) | Column::Unloaded => {}
                    Column::FrameRotation(a) => turns[0] += gc.cross(&Vector3::ith(a, 1.0)),
                    Column::Carrier(slot) => turns[0] += gc.cross(&p.carrier_axes[slot]),
                    Column::Point { point, .. } if point == k => by_link[6] += js.cross(&gs),
                    Column::Point { .. } => {}
                    Column::Joint {
                        joint: i,
                        component,
                    } => {
                        by_link[i] += js.cross(&gs);
                        let s = match component {
                            Component::Theta => Some(f.axis_directions[i]),
                            Component::Alpha => Some(p.u[i]),
                            Component::Beta => Some(p.v[i]),
                            _ => None,
                        };
                        if let Some(s) = s {
                            turns[i] += gc.cross(&s);
                        }
                    }
                    Column::Gravity { term, joint } => {
                        let y = p.regressors[term];
                        let weights = self.spring_weights(joint);
                        for (i, w) in weights.iter().enumerate() {
                            if *w == 0.0 {
                                continue;
                            }
                            by_link[i] += p.screws[k][i].cross(&gc) * (*w * y);
                            turns[i] += gc.cross(&f.axis_directions[i]) * (*w * y);
                        }
                        eta[term] += gc.dot(&p.springs[k][joint]);
                    }
                }
            }
            // Suffix sums of by_link over L > j, prefix sums of turns over L <= j.
            let mut after: Vector3<f64> = by_link[1..].iter().sum();
            let mut before = Vector3::zeros();
            for j in 0..6 {
                before += turns[j];
                if j > 0 {
                    after -= by_link[j];
                }
                let z = f.axis_directions[j];
                theta[j] += z.dot(&(after + p.levers[k][j].cross(&before)));
            }
        }
        for (e, d) in eta.iter().zip(&p.regressor_gradients) {
            theta += d * *e;
        }
        self.model.robot().axis_map().matrix.transpose() * theta
    }
}

/// The gravity terms' regressors of `model` at the posture `f` and their derivatives in the
/// kinematic angles: the torques `(z_i x arm) . g` of unit masses and moments
/// ([`stiffid_metrology::calibration::gravity`], module docs), equal to its `regressors`. Only
/// the mass moments the terms read are formed; known masses are summed into one arm per joint
/// first (`a_i = sum_{l >= i} m_l (p_l - o_i)`, `p_l` link `l`'s centre), so a compliance term
/// costs what one unit moment does.
fn regressors(model: &ErrorModel, f: &Frames) -> (Vec<f64>, Vec<Vector6<f64>>) {
    let gm = model.gravity();
    if gm.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let m: Matrix6<f64> = model.robot().axis_map().matrix;
    // The spring `joint`'s row of a kinematic torque vector and of its derivatives.
    let spring = |(theta, d): &Torques, joint: usize| match gm.coordinates() {
        Coordinates::Kinematic => (theta[joint], d.row(joint).transpose()),
        Coordinates::Axis => {
            let w = m.column(joint);
            (w.dot(theta), d.tr_mul(&w))
        }
    };
    let masses = gm.link_masses().map(|masses| {
        let mut arms = [Vector3::zeros(); 6];
        let (mut moment, mut mass) = (Vector3::zeros(), 0.0);
        for l in (0..6).rev() {
            let lm = &masses[l];
            moment += (f.joints[l] * Point3::from(lm.centre)).coords * lm.mass;
            mass += lm.mass;
            arms[l] = moment - f.axis_points[l] * mass;
        }
        torques(f, &arms)
    });
    // unit[l][k]: link l's mass (k = 0) or first moment along its x, y, z (k = 1..3), formed
    // on first use.
    let mut unit: [[Option<Torques>; 4]; 6] = Default::default();
    let mut y = Vec::with_capacity(gm.len());
    let mut dy = Vec::with_capacity(gm.len());
    for term in gm.terms() {
        let (v, d) = match *term {
            Term::Lumped {
                joint,
                link,
                moment,
            } => {
                let t = unit[link][moment].get_or_insert_with(|| {
                    let frame = &f.joints[link];
                    let mut arms = [Vector3::zeros(); 6];
                    for (i, a) in arms.iter_mut().enumerate().take(link + 1) {
                        *a = match moment {
                            0 => frame.translation.vector - f.axis_points[i],
                            _ => frame.rotation * Vector3::ith(moment - 1, 1.0),
                        };
                    }
                    torques(f, &arms[..=link])
                });
                spring(t, joint)
            }
            Term::Arm { joint, link } => {
                let axis = f.joints[link].rotation * gm.arm_axis(link);
                spring(&torques(f, &[axis; 6][..=link]), joint)
            }
            Term::Compliance { joint } => spring(
                masses.as_ref().expect("a compliance term has masses"),
                joint,
            ),
        };
        y.push(v);
        dy.push(d);
    }
    (y, dy)
}

/// Kinematic joint torques and their derivatives in the kinematic angles ([`torques`]).
type Torques = (Vector6<f64>, Matrix6<f64>);

/// The kinematic joint torques `theta_i = (z_i x a_i) . g` of a weight whose arm about joint
/// `i` is `arms[i]` (joints `i < arms.len()`, the links the weight hangs on; 0 beyond), and
/// their derivatives `d[(i, j)] = dtheta_i / dtheta_j`. With `t_i = (z_i x a_i) x g`: turning
/// joint `j < i` turns `z_i` and `a_i` together (`z_j . t_i`); turning joint `j >= i` turns the
/// part beyond `j`, whose arm about `o_j` is `a_j`, so `a_i` changes by `z_j x a_j` and
/// `theta_i` by `z_i . t_j`.
fn torques(f: &Frames, arms: &[Vector3<f64>]) -> Torques {
    let g = Vector3::new(0.0, 0.0, -G);
    let z = &f.axis_directions;
    let mut theta = Vector6::zeros();
    let mut t = [Vector3::zeros(); 6];
    for (i, a) in arms.iter().enumerate() {
        let torque = z[i].cross(a);
        theta[i] = torque.dot(&g);
        t[i] = torque.cross(&g);
    }
    let last = arms.len();
    let d = Matrix6::from_fn(|i, j| match (i < last, j < last) {
        (false, _) | (_, false) => 0.0,
        _ if j < i => z[j].dot(&t[i]),
        _ => z[i].dot(&t[j]),
    });
    (theta, d)
}
