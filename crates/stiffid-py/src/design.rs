//! `Setup.evaluate` and `Setup.select`: the design criteria of a group of postures and the
//! posture search, over [`stiffid::design`].

use crate::arrays::{self, choice};
use crate::error::{raise, value};
use nalgebra::Vector6;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stiffid::cell::Checker;
use stiffid::design::{
    self, Criterion, Evaluation, Gradient, Pool, PoolMethod, PoolOptions, SearchOptions,
};
use stiffid::limits::{self, check_count};
use stiffid::lsq::Factor;
use stiffid::observation::rope_observation_matrix;
use stiffid::Setup;

/// The criteria of a group, as a dict (see `Setup.evaluate`), after checking that the group can
/// identify every joint.
pub fn evaluate<'py>(
    py: Python<'py>,
    setup: &Setup,
    group: &[Vector6<f64>],
) -> PyResult<Bound<'py, PyDict>> {
    let e = py.detach(|| {
        identifiable(setup, group)?;
        Ok(design::evaluate(setup, group))
    });
    criteria(py, &e.map_err(raise)?)
}

/// Fails, naming the joints, when the group's observation matrix cannot identify every joint.
fn identifiable(setup: &Setup, group: &[Vector6<f64>]) -> stiffid::Result<()> {
    Factor::try_new(rope_observation_matrix(setup, group)).map(|_| ())
}

/// An evaluation under the keys of `stiffid evaluate --json`, plus `relative_std`; `None` for
/// what the setup lacks a field for (NaN in [`Evaluation`], nowhere else).
pub fn criteria<'py>(py: Python<'py>, e: &Evaluation) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let given = |v: f64| (!v.is_nan()).then_some(v);
    d.set_item("classical", given(e.classical))?;
    d.set_item("zhang2021", given(e.zhang2021))?;
    d.set_item("scaled_cond", given(e.scaled_cond))?;
    d.set_item("d_optimal", given(e.d_optimal))?;
    d.set_item("relative_a", given(e.relative_a))?;
    d.set_item("test_pose_mm", e.test_pose * 1e3)?;
    d.set_item("cond_psi", e.cond_psi)?;
    let scaled = !e.relative_std.iter().any(|v| v.is_nan());
    d.set_item(
        "relative_std",
        scaled.then(|| arrays::vec1(py, e.relative_std.iter().copied())),
    )?;
    d.set_item(
        "predicted_deviation_pct",
        scaled.then(|| arrays::table(py, &e.predicted_deviation_pct)),
    )?;
    Ok(d)
}

/// The arguments of `Setup.select`, shapes and ranges not yet checked.
pub struct Request<'a> {
    pub criterion: &'a str,
    pub method: Option<&'a str>,
    /// Checked against the setup's bounds.
    pub start: Option<Vec<Vector6<f64>>>,
    pub n: Option<usize>,
    pub seed: u64,
    pub starts: Option<u64>,
    pub screen_steps: Option<u64>,
    pub polished: Option<u64>,
    pub max_evals: Option<u64>,
    pub gradient: &'a str,
    /// Checked against the robot's joint limits.
    pub pool: Option<Vec<Vector6<f64>>>,
    pub restarts: Option<u64>,
}

#[derive(Clone, Copy, PartialEq)]
enum Method {
    Global,
    Local,
    Pool,
}

/// What a search or a pool choice found.
struct Found {
    postures: Vec<Vector6<f64>>,
    value: f64,
    start_value: Option<f64>,
    evaluations: usize,
    pool: Option<PoolFound>,
}

/// What a pool choice found besides the group.
struct PoolFound {
    /// Pool rows chosen, 0-based, ascending.
    indices: Vec<usize>,
    method: PoolMethod,
    /// The rows skipped and the checks they fail.
    skipped: Vec<(usize, Vec<&'static str>)>,
}

/// Runs `Setup.select` (the GIL released during the search).
pub fn select<'py>(py: Python<'py>, setup: &Setup, r: Request) -> PyResult<Bound<'py, PyDict>> {
    let criterion: Criterion = r.criterion.parse().map_err(raise)?;
    let method = method(&r)?;
    let n = match (&r.start, r.n) {
        (Some(s), Some(n)) if s.len() != n => {
            return Err(value(format!(
                "n = {n} but start holds {} postures: give one or the other",
                s.len()
            )))
        }
        (Some(s), _) => s.len(),
        (None, n) => n.unwrap_or(6),
    };
    check_postures(n)?;
    let found = match method {
        Method::Pool => {
            let restarts = r
                .restarts
                .map_or(Ok(8), |v| count("restarts", v, 1, 1000))?;
            let options = PoolOptions {
                restarts,
                seed: r.seed,
                ..PoolOptions::default()
            };
            let pool = r.pool.unwrap_or_default();
            py.detach(|| from_pool(setup, &pool, criterion, n, &options))
        }
        _ => {
            if r.restarts.is_some() {
                return Err(value("restarts: only with pool"));
            }
            let options = search_options(&r)?;
            let start = r.start.clone();
            py.detach(|| search(setup, method, criterion, n, start, &options))
        }
    }
    .map_err(raise)?;
    let d = PyDict::new(py);
    d.set_item(
        "method",
        match method {
            Method::Global => "global",
            Method::Local => "local",
            Method::Pool => "pool",
        },
    )?;
    d.set_item("criterion", criterion.name())?;
    d.set_item("postures_deg", arrays::degrees(py, &found.postures))?;
    d.set_item("value", found.value)?;
    d.set_item("start_value", found.start_value)?;
    d.set_item("evaluations", found.evaluations)?;
    let e = py.detach(|| design::evaluate(setup, &found.postures));
    d.set_item("criteria", criteria(py, &e)?)?;
    if let Some(p) = found.pool {
        d.set_item("pool_indices", p.indices)?;
        let how = match p.method {
            PoolMethod::Enumeration => "enumeration",
            PoolMethod::Exchange => "exchange",
        };
        d.set_item("pool_method", how)?;
        d.set_item("pool_skipped", p.skipped)?;
    }
    Ok(d)
}

/// The method asked for, or implied by `start` (local) or `pool`.
fn method(r: &Request) -> PyResult<Method> {
    let methods = [
        ("global", Method::Global),
        ("local", Method::Local),
        ("pool", Method::Pool),
    ];
    let m = match (r.method, &r.start, &r.pool) {
        (Some(m), _, _) => choice("method", m, &methods)?,
        (None, Some(_), _) => Method::Local,
        (None, None, Some(_)) => Method::Pool,
        (None, None, None) => Method::Global,
    };
    if r.start.is_some() && m != Method::Local {
        return Err(value("start: only with method=\"local\""));
    }
    if (m == Method::Pool) != r.pool.is_some() {
        return Err(value(
            "pool: give the pool postures with method=\"pool\", and only then",
        ));
    }
    Ok(m)
}

/// The search budget: the library's defaults, overridden within the command line's ranges.
fn search_options(r: &Request) -> PyResult<SearchOptions> {
    let mut o = SearchOptions {
        seed: r.seed,
        gradient: r.gradient.parse::<Gradient>().map_err(raise)?,
        ..SearchOptions::default()
    };
    let (starts, evals) = (limits::MAX_STARTS, limits::MAX_EVALS);
    if let Some(v) = r.starts {
        o.starts = count("starts", v, 1, starts)?;
    }
    if let Some(v) = r.screen_steps {
        o.screen_steps = count("screen_steps", v, 0, evals)?;
    }
    if let Some(v) = r.polished {
        o.polished = count("polished", v, 1, starts)?;
    }
    if let Some(v) = r.max_evals {
        o.max_evals = count("max_evals", v, 1, evals)?;
    }
    Ok(o)
}

/// A count within `[min, max]`.
fn count(field: &str, v: u64, min: u64, max: u64) -> PyResult<usize> {
    let (v, min, max) = (v as usize, min as usize, max as usize);
    check_count(field, v, min, max).map_err(raise)?;
    Ok(v)
}

/// The size of a searched group: 2 to 100 postures.
pub fn check_postures(n: usize) -> PyResult<()> {
    count("n", n as u64, 2, limits::MAX_SEARCH_POSTURES).map(|_| ())
}

fn search(
    setup: &Setup,
    method: Method,
    criterion: Criterion,
    n: usize,
    start: Option<Vec<Vector6<f64>>>,
    options: &SearchOptions,
) -> stiffid::Result<Found> {
    let o = match method {
        Method::Global => design::global(setup, criterion, n, options, &())?,
        _ => {
            let start = start.unwrap_or_else(|| design::random_group(setup, n, options.seed));
            design::local(setup, criterion, &start, options)?
        }
    };
    Ok(Found {
        postures: o.postures,
        value: o.value,
        start_value: Some(o.start_value),
        evaluations: o.evaluations,
        pool: None,
    })
}

fn from_pool(
    setup: &Setup,
    postures: &[Vector6<f64>],
    criterion: Criterion,
    n: usize,
    options: &PoolOptions,
) -> stiffid::Result<Found> {
    let checker = Checker::new(setup);
    let skipped: Vec<(usize, Vec<&'static str>)> = postures
        .iter()
        .enumerate()
        .filter_map(|(i, q)| {
            let f = checker.feasibility(q);
            let failed: Vec<&'static str> = f.violations().map(|c| c.kind.key()).collect();
            (!failed.is_empty()).then_some((i, failed))
        })
        .collect();
    let usable: Vec<bool> = (0..postures.len())
        .map(|i| skipped.iter().all(|(s, _)| *s != i))
        .collect();
    let pool = Pool::new(setup, postures, &usable)?;
    let c = pool.best(criterion, n, options)?;
    Ok(Found {
        postures: pool.postures(&c.indices),
        value: c.value,
        start_value: None,
        evaluations: c.evaluations,
        pool: Some(PoolFound {
            indices: c.indices,
            method: c.method,
            skipped,
        }),
    })
}
