//! The identification Jacobian of the error model and the columns' scales (module docs of
//! [`super`], "The identification Jacobian").

use super::{At, ErrorModel, Observation, Posture, Target, NO_EFFECT};
use nalgebra::{DMatrix, DVector, Matrix3, Unit, UnitQuaternion, Vector3, Vector6};
use stiffid_core::{Error, Result};

impl ErrorModel {
    /// The identification Jacobian `d b / d x` at `values` (module docs): 3 rows per `(q, point)`
    /// pair (axis angles, rad; points 0-based), one column per parameter, base frame, m per unit
    /// of the parameter (m/m, m/rad, m per gravity-term unit). Exact where the frame's six values
    /// are zero (as the fit keeps them); it is also the Jacobian of
    /// `ErrorModel::residuals`.
    ///
    /// # Errors
    /// [`Error::InvalidField`] when a value is not finite; [`Error::InvalidField`] (`point`) for a
    /// point beyond the model's.
    pub fn jacobian(
        &self,
        values: &DVector<f64>,
        at: &[(Vector6<f64>, usize)],
    ) -> Result<DMatrix<f64>> {
        self.jacobian_at(values, At::arm(at), at.len())
    }

    /// [`ErrorModel::jacobian`] of `count` positions `at`.
    fn jacobian_at<'a>(
        &self,
        values: &DVector<f64>,
        at: impl Iterator<Item = At<'a>> + Clone,
        count: usize,
    ) -> Result<DMatrix<f64>> {
        let (points, tables) = (self.points(), self.tables());
        if let Some(a) = at.clone().find(|a| match a.table {
            false => a.point >= points,
            true => a.point >= tables,
        }) {
            return Err(Error::InvalidField {
                field: "point".into(),
                message: match a.table {
                    false => format!(
                        "expected a measuring point 1 to {points}, got {}",
                        a.point + 1
                    ),
                    true => format!(
                        "expected a table reflector 1 to {tables}, got {}",
                        a.point + 1
                    ),
                },
            });
        }
        let robot = self.robot_at(values)?;
        let mut j = DMatrix::zeros(3 * count, self.parameters.len());
        let springs = self.gravity.coordinates();
        let mut last: Option<Posture> = None;
        for (row, a) in at.enumerate() {
            let mut block = j.fixed_rows_mut::<3>(3 * row);
            if a.table {
                let b = self.table_position(values, a.e.as_slice(), a.point);
                block
                    .fixed_view_mut::<3, 3>(0, 0)
                    .copy_from(&Matrix3::identity());
                block
                    .fixed_view_mut::<3, 3>(0, 3)
                    .copy_from(&(-b.cross_matrix()));
                self.table_columns(values, a.e.as_slice(), a.point, |c, col| {
                    block.column_mut(c).copy_from(&col)
                });
                continue;
            }
            let k = &a.point;
            let posture = self.posture_of(&mut last, &robot, values, &a);
            let f = &posture.frames;
            let c = self.point(values, *k);
            let b = f.point(&c);
            block
                .fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&Matrix3::identity());
            block
                .fixed_view_mut::<3, 3>(0, 3)
                .copy_from(&(-b.cross_matrix()));
            block
                .fixed_view_mut::<3, 3>(0, 6 + 3 * k)
                .copy_from(f.flange.rotation.to_rotation_matrix().matrix());
            if let Some(s) = self.joint_start {
                for i in 0..6 {
                    let cols = self.joint_columns(f, &posture.base, values, i, &b);
                    for (c, col) in cols.iter().enumerate() {
                        block.column_mut(s + 6 * i + c).copy_from(col);
                    }
                }
            } else if let Some(s) = self.offsets_start {
                for i in 0..6 {
                    let col = f.axis_directions[i].cross(&(b - f.axis_points[i]));
                    block.column_mut(s + i).copy_from(&col);
                }
            }
            if self.maps.is_some() {
                let jq = f.jacobian(&c, stiffid_core::robot::kinematics::Coordinates::Axis);
                let columns = std::array::from_fn(|i| jq.fixed_view::<3, 1>(0, i).into_owned());
                self.map_columns(&columns, &posture.at, &posture.direction, |m, col| {
                    block.column_mut(m).copy_from(&col)
                });
            }
            if let Some(x) = (self.external.as_ref()).filter(|x| x.axes.carrier_len() > 0) {
                x.carrier_columns(values, a.e.as_slice(), &b, |c, col| {
                    block.column_mut(c).copy_from(&col)
                });
            }
            if !self.gravity.is_empty() {
                let jp = f.jacobian(&c, springs);
                let regressors = &posture.regressors;
                for (t, (term, y)) in self.gravity.terms().iter().zip(regressors).enumerate() {
                    let col = jp.fixed_view::<3, 1>(0, term.joint()) * *y;
                    block.column_mut(self.gravity_start + t).copy_from(&col);
                }
            }
        }
        if !j.iter().all(|v| v.is_finite()) {
            return Err(Error::NotFinite {
                what: "the identification Jacobian".into(),
            });
        }
        Ok(j)
    }

    /// The Jacobian of `ErrorModel::residuals` (and of [`ErrorModel::predict`]) at `values`:
    /// [`ErrorModel::jacobian`] of the observations' postures and points, with, for a loaded
    /// reading, the compliances' columns (its observation rows, `ErrorModel::load_rows`) and
    /// the frame's rotation about the deflected point.
    ///
    /// # Errors
    /// Those of [`ErrorModel::jacobian`].
    pub fn jacobian_of(
        &self,
        values: &DVector<f64>,
        observations: &[Observation],
    ) -> Result<DMatrix<f64>> {
        let mut j = self.jacobian_at(values, At::of(observations), observations.len())?;
        self.zero_held(&mut j);
        let Some(loads) = &self.loads else {
            return Ok(j);
        };
        for (i, o) in observations.iter().enumerate() {
            let Some(rows) = self.load_rows(&o.q, o.point, &o.wrench) else {
                continue;
            };
            let d = self.load_deflection(values, &o.q, o.point, &o.wrench);
            let mut block = j.fixed_rows_mut::<3>(3 * i);
            let turned = block.fixed_view::<3, 3>(0, 3) - d.cross_matrix();
            block.fixed_view_mut::<3, 3>(0, 3).copy_from(&turned);
            for (m, &c) in loads.columns.iter().enumerate() {
                let col = block.column(c) + rows.column(m);
                block.column_mut(c).copy_from(&col);
            }
        }
        Ok(j)
    }

    /// [`ErrorModel::column_scales`] at the observations' postures, with, for a compliance under
    /// the applied wrenches ([`Target::Compliance`]), `1 / rms`, `rms` the RMS length of its
    /// observation rows (`ErrorModel::load_rows`) over the loaded readings: a compliance that moves
    /// a loaded reading by 1 m RMS (0 below 1e-9 times the largest of its unit's); for a drive's
    /// gravity compliance with known masses, the smaller of that and its gravity scale (either
    /// where the other is 0).
    pub fn column_scales_of(&self, length: f64, observations: &[Observation]) -> DVector<f64> {
        let qs: Vec<Vector6<f64>> = observations.iter().map(|o| o.q).collect();
        let mut scales = self.column_scales(length, &qs);
        let Some(loads) = &self.loads else {
            return scales;
        };
        let mut sum = vec![0.0; loads.columns.len()];
        let mut loaded = 0usize;
        for o in observations {
            if let Some(rows) = self.load_rows(&o.q, o.point, &o.wrench) {
                loaded += 1;
                for (s, col) in sum.iter_mut().zip(rows.column_iter()) {
                    *s += col.norm_squared();
                }
            }
        }
        let rms: Vec<f64> = sum
            .iter()
            .map(|s| (s / loaded.max(1) as f64).sqrt())
            .collect();
        for (m, &c) in loads.columns.iter().enumerate() {
            let unit = self.parameters[c].unit();
            let largest = (loads.columns.iter().zip(&rms))
                .filter(|&(&c, _)| self.parameters[c].unit() == unit)
                .map(|(_, r)| *r)
                .fold(0.0, f64::max);
            let loaded = match rms[m] > NO_EFFECT * largest {
                true => 1.0 / rms[m],
                false => 0.0,
            };
            // A drive's gravity compliance (known masses): the smaller of its two scales, the
            // larger effect, where both have one.
            scales[c] = match self.parameters[c].target {
                Target::Gravity(_) if scales[c] > 0.0 && loaded > 0.0 => scales[c].min(loaded),
                Target::Gravity(_) if loaded == 0.0 => scales[c],
                _ => loaded,
            };
        }
        scales
    }

    /// The six columns `[theta, d, a, alpha, beta, b]` of joint `i` for the base-frame point `b`.
    fn joint_columns(
        &self,
        f: &stiffid_core::Frames,
        base: &nalgebra::Isometry3<f64>,
        values: &DVector<f64>,
        i: usize,
        b: &Vector3<f64>,
    ) -> [Vector3<f64>; 6] {
        let before = if i == 0 { *base } else { f.joints[i - 1] };
        let w_frame = before * self.robot.joints()[i].pre;
        let r = w_frame.rotation;
        let e = self.joint_errors(values, i);
        let basis = &self.bases[i];
        let (u, v) = (r * basis.u, r * basis.v);
        let o = (w_frame * nalgebra::Point3::from(basis.u * e[2] + basis.v * e[5])).coords;
        let v_turned =
            r * (UnitQuaternion::from_axis_angle(&Unit::new_unchecked(basis.u), e[3]) * basis.v);
        let (z, oz) = (f.axis_directions[i], f.axis_points[i]);
        [
            z.cross(&(b - oz)),
            z,
            u,
            u.cross(&(b - o)),
            v_turned.cross(&(b - o)),
            v,
        ]
    }

    /// The typical size of each parameter, by which the Jacobian's columns are multiplied to make
    /// them comparable (the column scaling of the identifiability analysis and the design
    /// criteria): 1 m for a length or a translation, `1 / length` rad for an angle (`length` the
    /// characteristic length, m: an angle error that moves a point at that distance by as much as a
    /// 1 m length error), and for a gravity term `1 / (length * y_rms)`, `y_rms` the RMS of its
    /// regressor at the postures `qs` (axis angles, rad), the value that deflects the joint by that
    /// angle; 0 (the column then has no effect) for a term whose regressor's RMS is below 1e-9
    /// times the largest of its unit's (a torque that rounding alone makes non-zero, such as
    /// gravity's about a vertical axis). A scaled column is the position change (m) of a typical
    /// parameter error.
    pub fn column_scales(&self, length: f64, qs: &[Vector6<f64>]) -> DVector<f64> {
        let rms = self.gravity.regressor_rms(qs);
        DVector::from_iterator(
            self.parameters.len(),
            self.parameters
                .iter()
                .enumerate()
                .map(|(i, p)| match p.target {
                    Target::Frame(a) if a >= 3 => 1.0 / length,
                    Target::Joint { component, .. } if component.is_angle() => 1.0 / length,
                    Target::Map { .. } | Target::Backlash { .. } => 1.0 / length,
                    Target::External { part, .. } if part.is_angle() => 1.0 / length,
                    Target::Gravity(term) => {
                        let y = rms[i - self.gravity_start];
                        let largest = (self.gravity.terms().iter().zip(&rms))
                            .filter(|(t, _)| t.unit() == term.unit())
                            .map(|(_, r)| *r)
                            .fold(0.0, f64::max);
                        match y > NO_EFFECT * largest {
                            true => 1.0 / (y * length),
                            false => 0.0,
                        }
                    }
                    _ => 1.0,
                }),
        )
    }
}
