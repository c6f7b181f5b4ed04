//! The free variables of a path on a fixed base, the rotation about tool z and the lead and
//! tilt, chosen by the dynamic programming on their grid and refined around the line it chose
//! (module docs of [`super`], "The free tool axis", "Refining the grid").

use super::feasible::Checks;
use super::lead_tilt::Leaning;
use super::refine::{refine, Evaluate, Layout};
use super::tool_axis::{choose, column, lean_axes, rotation_axis, Column, Cost, Grid, Move};
use super::{Aggregate, FreeRange, Model, Options, Removed};
use nalgebra::Vector6;
use rayon::prelude::*;
use stiffid_core::robot::external::ExternalValues;

/// What the free variables of a path on a fixed base chose at every point: the posture, the
/// rotation about tool z and the `(lead, tilt)`, rad; and each point's states the checks removed.
pub(super) type Picked = (Vec<Vector6<f64>>, Vec<f64>, Vec<(f64, f64)>, Vec<Removed>);

/// The postures, tool rotations and leans of the free tool axis (`rotation`, else none) and the
/// free lead and tilt (`leaning`, module docs), their costs added up by `aggregate`, with each
/// point's states `checks` removed (the arm on its carriage at each point's external values
/// `own`); the grid refined [`Options::refine`] times ([`super::refine`]).
pub(super) fn optimise_tool_axis(
    model: &Model,
    (nominal, own): (&[Vector6<f64>], &[ExternalValues]),
    wrenches: &[Vector6<f64>],
    (rotation, leaning, aggregate): (Option<&FreeRange>, &Leaning, Aggregate),
    (cost, checks): (&Cost, &Checks),
    options: &Options,
) -> Picked {
    let ik_options = &options.ik;
    let angles = rotation.map_or(vec![0.0], FreeRange::angles);
    let a = angles.len();
    let columns: Vec<Column> = (0..leaning.len() * a)
        .into_par_iter()
        .map(|s| {
            let m = Move {
                phi: angles[s % a],
                shift: None,
                lean: leaning.at(s / a),
                line: None,
            };
            column(model, nominal, wrenches, (m, cost), ik_options)
        })
        .collect();
    let mut axes = lean_axes(leaning);
    if let Some(f) = rotation {
        axes.push(rotation_axis(f, &angles));
    }
    let at = vec![own; columns.len()];
    let grid = Grid { axes };
    let (chosen, mut removed) = choose((&columns, &at), &grid, (cost, checks), aggregate);
    let layout = Layout::new(0, leaning, rotation.is_some());
    let evaluate = |values: &[Vec<f64>]| {
        let line: Vec<[f64; 3]> = values.iter().map(|v| layout.turn_lean(v)).collect();
        let m = Move {
            phi: 0.0,
            shift: None,
            lean: leaning.at(leaning.len() / 2),
            line: Some(&line),
        };
        let c = column(model, nominal, wrenches, (m, cost), ik_options);
        (c, own.to_vec())
    };
    let refined = (options.refine, &evaluate as &Evaluate);
    let line = refine(
        &grid,
        (&columns, &chosen, &at),
        refined,
        (cost, checks),
        aggregate,
        &mut removed,
    );
    let mut out: Picked = (Vec::new(), Vec::new(), Vec::new(), removed);
    for (i, v) in line.values.iter().enumerate() {
        out.0
            .push(line.cells[i].as_ref().map_or(nominal[i], |c| c.0));
        let [phi, lead, tilt] = layout.turn_lean(v);
        out.1.push(phi);
        out.2.push((lead, tilt));
    }
    out
}
